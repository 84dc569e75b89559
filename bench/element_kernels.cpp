// Time per element of the element models' kernels alone: what the block
// assembly asks of a model for one triangle or tetrahedron (its distinct
// blocks where the model gives them, else its whole matrix), on random
// simplices, without the scatter into the system. A table of the median
// over repetitions of ns per element.
//
//   ./build-bench/bench/element_kernels [--repetitions N]
//
// The library is header-only, so the same file built against another
// commit's include folder, with the flags of the CMake build (CGAL's exact
// predicates need -frounding-math), times that commit's kernels:
//   g++ -O3 -DNDEBUG -frounding-math -fopenmp -std=c++17 -I OLD/include bench/element_kernels.cpp
#include <spring_motion/spring_motion.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

namespace sm = spring_motion;

namespace {

template <int D>
using Simplex = std::array<std::array<double, D>, D + 1>;

// the corners of the unit simplex (the origin and the unit vectors), each
// moved by up to 0.2 per coordinate: no element is flat
template <int D>
std::vector<Simplex<D>> simplices(std::size_t n)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  std::vector<Simplex<D>> out(n);
  for(auto& s : out)
    for(int v = 0; v <= D; ++v)
      for(int c = 0; c < D; ++c)
        s[std::size_t(v)][std::size_t(c)] = (v == c + 1 ? 1.0 : 0.0) + u(rng);
  return out;
}

// ns per element of `pass` (one pass over n elements), median of the
// repetitions; `pass` returns a value of its results, kept alive
template <class Pass>
double median_ns_per_element(std::size_t n, int repetitions, Pass pass)
{
  std::vector<double> times;
  double sink = 0;
  for(int r = 0; r < repetitions; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    sink += pass();
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  if(sink == 0.125) // keeps the kernels' results alive
    std::puts("");
  std::nth_element(times.begin(), times.begin() + long(times.size() / 2), times.end());
  return 1e9 * times[times.size() / 2] / double(n);
}

template <int D, class Model>
double ns_per_element(const Model& model, const std::vector<Simplex<D>>& el, int repetitions)
{
  constexpr bool symmetric = sm::internal::Has_symmetric_blocks<Model, D>::value;
  constexpr int size = symmetric ? (D + 1) * (D + 2) / 2 * D * (D + 1) / 2 : (D + 1) * D * (D + 1) * D;
  return median_ns_per_element(el.size(), repetitions, [&] {
    double sink = 0;
    for(const auto& p : el) {
      std::array<double, size> K{};
      if constexpr(symmetric)
        model.add_symmetric_blocks(p, K.data());
      else
        model.add_element_matrix(p, K.data());
      sink += K[0];
    }
    return sink;
  });
}

// The same through symmetric_blocks_of_two, two simplices per call
// (the assembly's form when the model has it); 0 when it has not.
template <int D, class Model>
double ns_per_element_in_twos(const Model& model, const std::vector<Simplex<D>>& el, int repetitions)
{
  if constexpr(!sm::internal::Has_symmetric_blocks_of_two<Model, D>::value)
    return 0;
  else {
    constexpr int size = (D + 1) * (D + 2) / 2 * D * (D + 1) / 2;
    return median_ns_per_element(el.size(), repetitions, [&] {
      double sink = 0;
      for(std::size_t k = 0; k + 1 < el.size(); k += 2) {
        std::array<double, size> K, L;
        if(!model.symmetric_blocks_of_two(el[k], el[k + 1], K.data(), L.data())) {
          K.fill(0.0);
          L.fill(0.0);
          model.add_symmetric_blocks(el[k], K.data());
          model.add_symmetric_blocks(el[k + 1], L.data());
        }
        sink += K[0] + L[0];
      }
      return sink;
    });
  }
}

// The same through symmetric_blocks_of_four, four simplices per call (the
// assembly's form where the model has it and the processor runs AVX); 0
// otherwise.
template <int D, class Model>
double ns_per_element_in_fours(const Model& model, const std::vector<Simplex<D>>& el, int repetitions)
{
  if constexpr(!sm::internal::Has_symmetric_blocks_of_four<Model, D>::value)
    return 0;
  else {
    if(!sm::internal::four_lanes_available())
      return 0;
    constexpr int size = (D + 1) * (D + 2) / 2 * D * (D + 1) / 2;
    return median_ns_per_element(el.size(), repetitions, [&] {
      double sink = 0;
      for(std::size_t k = 0; k + 3 < el.size(); k += 4) {
        std::array<std::array<double, size>, 4> K;
        if(!model.symmetric_blocks_of_four({&el[k], &el[k + 1], &el[k + 2], &el[k + 3]},
                                           {K[0].data(), K[1].data(), K[2].data(), K[3].data()}))
          for(std::size_t l = 0; l < 4; ++l) {
            K[l].fill(0.0);
            model.add_symmetric_blocks(el[k + l], K[l].data());
          }
        sink += K[0][0] + K[1][0] + K[2][0] + K[3][0];
      }
      return sink;
    });
  }
}

template <class Model>
void row(const char* name, const Model& model, int repetitions)
{
  static const auto triangles = simplices<2>(20000);
  static const auto tetrahedra = simplices<3>(20000);
  std::printf("%-26s %12.1f %14.1f", name, ns_per_element<2>(model, triangles, repetitions),
              ns_per_element<3>(model, tetrahedra, repetitions));
  const double two_2 = ns_per_element_in_twos<2>(model, triangles, repetitions);
  if(two_2 > 0)
    std::printf(" %12.1f %14.1f", two_2, ns_per_element_in_twos<3>(model, tetrahedra, repetitions));
  else
    std::printf(" %12s %14s", "-", "-");
  const double four_2 = ns_per_element_in_fours<2>(model, triangles, repetitions);
  if(four_2 > 0)
    std::printf(" %12.1f %14.1f\n", four_2, ns_per_element_in_fours<3>(model, tetrahedra, repetitions));
  else
    std::printf(" %12s %14s\n", "-", "-");
}

} // namespace

int main(int argc, char** argv)
{
  int repetitions = 21;
  for(int a = 1; a < argc; ++a) {
    if(std::strcmp(argv[a], "--repetitions") == 0 && a + 1 < argc)
      repetitions = std::max(1, std::atoi(argv[++a]));
    else {
      std::fprintf(stderr, "usage: element_kernels [--repetitions N]\n");
      return 2;
    }
  }
  std::printf("Element kernels, one thread, 20000 random simplices, median of %d repetitions:\n"
              "(in twos: two simplices per call, the assembly's form where the model has it; in fours: four,\n"
              "its form where the processor runs AVX too, '-' where it does not)\n"
              "%-26s %12s %14s %12s %14s %12s %14s\n",
              repetitions, "model", "ns/triangle", "ns/tetrahedron", "in twos", "in twos", "in fours", "in fours");
  sm::Ball_vertex_stiffness p1, p2, p25, p3;
  p2.exponent = 2;
  p25.exponent = 2.5;
  p3.exponent = 3;
  row("ball_vertex", p1, repetitions);
  row("ball_vertex_p2", p2, repetitions);
  row("ball_vertex_p2.5", p25, repetitions);
  row("ball_vertex_p3", p3, repetitions);
  row("grid_scaled+ball_vertex", sm::With_ball_vertex<sm::Grid_scaled_stiffness>{}, repetitions);
  row("torsional", sm::Torsional_stiffness{}, repetitions);
  return 0;
}
