// Adaptive substepping: a step that inverts an element is
// retried from the last valid state as 2, 4, ... 2^K equal substeps.
#include <spring_motion/spring_motion.h>

#include "test_meshes.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

using namespace spring_motion;
using namespace spring_motion_test;

namespace {

struct Annulus_case
{
  Spring_network<2> net;
  std::vector<Vertex_role> roles;
};

Annulus_case annulus()
{
  CDT cdt;
  make_annulus(cdt);
  Annulus_case c{extract_spring_network(cdt).network, {}};
  c.roles = assign_roles(c.net, moving_boundary_where([](const std::array<double, 2>& p) {
                           return std::hypot(p[0], p[1]) < 1.0;
                         }));
  return c;
}

bool bitwise_equal(const std::vector<std::array<double, 2>>& a, const std::vector<std::array<double, 2>>& b)
{
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
}

} // namespace

TEST_CASE("substepping: a step that inverts without it completes with it, reporting its substeps", "[substep]")
{
  const auto c = annulus();
  // the inner circle turns 60 degrees in one step: one increment inverts
  const Pitch_motion<2> turn(60, {0, 0});
  Deform_options options;
  options.number_of_steps = 1;

  Network_deformer<2> plain(c.net, c.roles);
  const auto without = plain.run(turn, Grid_scaled_stiffness{}, options);
  REQUIRE_FALSE(without.completed);
  REQUIRE(without.first_invalid);
  CHECK_FALSE(without.first_invalid->elements.empty());
  CHECK(without.steps[0].substeps == 1);
  CHECK(plain.fraction() == 0.0); // rolled back to the start

  options.max_substep_halvings = 8;
  Network_deformer<2> split(c.net, c.roles);
  const auto with = split.run(turn, Grid_scaled_stiffness{}, options);
  REQUIRE(with.completed);
  CHECK_FALSE(with.first_invalid);
  CHECK(with.final_fraction == 1.0);
  const std::size_t k = with.steps[0].substeps;
  INFO("substeps " << k);
  CHECK(k > 1);
  CHECK(k <= 256);
  CHECK((k & (k - 1)) == 0); // a power of two
  std::vector<std::size_t> inverted;
  CHECK(find_inverted_elements(c.net, split.positions(), split.orientation_record(), std::back_inserter(inverted)) == 0);

  // The accepted division starts from the same state as a fresh run of k
  // plain steps (the failed tries are rolled back, warm start included), and
  // its substep targets j/k equal that run's step targets: the final
  // positions agree bit for bit.
  options.max_substep_halvings = 0;
  options.number_of_steps = k;
  Network_deformer<2> fine(c.net, c.roles);
  const auto reference = fine.run(turn, Grid_scaled_stiffness{}, options);
  REQUIRE(reference.completed);
  CHECK(bitwise_equal(split.positions(), fine.positions()));
  // The step's report describes that accepted division only: its solves are
  // the reference run's, so their iterations add up and the largest error
  // figures are theirs; the rejected divisions (1, 2, ... k/2 substeps) are
  // counted apart.
  std::size_t iterations = 0;
  double estimate = 0, residual = 0;
  for(const auto& s : reference.steps) {
    iterations += s.iterations;
    estimate = std::max(estimate, s.error_estimate);
    residual = std::max(residual, s.residual);
  }
  CHECK(with.steps[0].iterations == iterations);
  CHECK(with.steps[0].error_estimate == estimate);
  CHECK(with.steps[0].residual == residual);
  CHECK(with.steps[0].converged);
  std::size_t halvings = 0;
  while((std::size_t(1) << halvings) < k)
    ++halvings;
  CHECK(with.steps[0].rejected_attempts == halvings);
  // and k/2 plain steps fail, or the division before would have been taken
  options.number_of_steps = k / 2;
  Network_deformer<2> coarser(c.net, c.roles);
  CHECK_FALSE(coarser.run(turn, Grid_scaled_stiffness{}, options).completed);
}

TEST_CASE("substepping: the limit is honoured and the state rolled back when it is reached", "[substep]")
{
  const auto c = annulus();
  const Pitch_motion<2> turn(60, {0, 0});
  Deform_options options;
  options.number_of_steps = 1;
  // one halving (2 substeps) is not enough for this turn (the test above
  // needs more), so the run stops with the finest division tried recorded
  options.max_substep_halvings = 1;
  Network_deformer<2> d(c.net, c.roles);
  const auto r = d.run(turn, Grid_scaled_stiffness{}, options);
  if(r.completed) {
    // then the first test's k was 2: nothing more to check here
    CHECK(r.steps[0].substeps == 2);
    return;
  }
  CHECK(r.steps[0].substeps == 2);
  CHECK(r.steps[0].inverted > 0);
  CHECK(d.fraction() == 0.0);
  CHECK(bitwise_equal(d.positions(), c.net.points));
}

// The inner circle turns 60 degrees during the first third of the motion,
// then stays: a 3-step run has one 60-degree increment, then two empty ones.
struct Turn_then_hold
{
  std::array<double, 2> operator()(const std::array<double, 2>& p, double t) const
  {
    const double a = angle_deg(t) * std::acos(-1.0) / 180, c = std::cos(a), s = std::sin(a);
    return {c * p[0] - s * p[1], s * p[0] + c * p[1]};
  }
  double angle_deg(double t) const { return 60 * std::min(1.0, 3 * t); }
};

TEST_CASE("substepping: only the steps that need substeps take them", "[substep]")
{
  const auto c = annulus();
  Deform_options options;
  options.number_of_steps = 3;
  options.max_substep_halvings = 8;
  Network_deformer<2> d(c.net, c.roles);
  const auto r = d.run(Turn_then_hold{}, Grid_scaled_stiffness{}, options);
  REQUIRE(r.completed);
  REQUIRE(r.steps.size() == 3);
  // the first step's one increment is the 60-degree turn that inverts in the
  // first test case: it must be split; the other two move nothing
  const std::size_t k = r.steps[0].substeps;
  CHECK(k > 1);
  CHECK((k & (k - 1)) == 0);
  CHECK(r.steps[1].substeps == 1);
  CHECK(r.steps[2].substeps == 1);
  // the JSON report carries the per-step substeps
  std::ostringstream json;
  write_report_json(r, json);
  CHECK_THAT(json.str(), Catch::Contains("\"substeps\": " + std::to_string(k)));
  CHECK_THAT(json.str(), Catch::Contains("\"substeps\": 1"));
}
