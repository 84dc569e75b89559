// Copyright (c) 2026 SpringMotion developers.
// Checks on linear operators of 2D systems, shared by the solver tests.
#ifndef SPRING_MOTION_TESTS_TEST_OPERATORS_H
#define SPRING_MOTION_TESTS_TEST_OPERATORS_H

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

namespace spring_motion_test {

/// One 2-vector per row.
using Vec = std::vector<std::array<double, 2>>;

inline double dot(const Vec& a, const Vec& b)
{
  double s = 0;
  for(std::size_t i = 0; i < a.size(); ++i)
    s += a[i][0] * b[i][0] + a[i][1] * b[i][1];
  return s;
}

/// T symmetric (<Tu, v> = <u, Tv> within `tolerance` relative) and positive
/// (<Tu, u> > 0) on random vectors of `rows` rows.
template <class Operator>
void check_symmetric_positive(const Operator& T, std::size_t rows, unsigned seed, double tolerance = 1e-10)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-1, 1);
  for(int trial = 0; trial < 5; ++trial) {
    Vec u(rows), v(rows);
    for(std::size_t i = 0; i < rows; ++i) {
      u[i] = {d(rng), d(rng)};
      v[i] = {d(rng), d(rng)};
    }
    const Vec Tu = T(u), Tv = T(v);
    const double a = dot(Tu, v), b = dot(u, Tv);
    INFO("<Tu, v> = " << a << ", <u, Tv> = " << b);
    CHECK(std::abs(a - b) <= tolerance * std::sqrt(dot(Tu, Tu) * dot(v, v)));
    CHECK(dot(Tu, u) > 0);
  }
}

} // namespace spring_motion_test

#endif
