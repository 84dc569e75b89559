// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_MOTION_PITCH_MOTION_H
#define SPRING_MOTION_MOTION_PITCH_MOTION_H

#include <spring_motion/Error.h>
#include <spring_motion/motion/Motion_description.h>

#include <array>
#include <cmath>

namespace spring_motion {

/// A rigid pitching rotation following the paper's quarter-sine schedule
/// (docs/method.md, "Test cases"): at motion fraction t in [0, 1] (step i of n is
/// t = i/n) the angle is alpha(t) = alpha_0 + alpha_m sin(pi t / 2).
///
/// The mesh is taken to be at alpha_0, so points turn by alpha(t) - alpha_0
/// about `center` (2D: about +z, counter-clockwise positive; 3D: about
/// `axis`, right-hand rule). Positions are computed from the initial point
/// every time, so a rotating body never drifts or shrinks.
template <int D>
struct Pitch_motion
{
  double amplitude_deg = 45;   ///< alpha_m
  double mean_angle_deg = 0;   ///< alpha_0
  std::array<double, D> center{};
  std::array<double, 3> axis{0, 0, 1}; ///< 3D only; normalised on use

  Pitch_motion() = default;
  Pitch_motion(double amplitude, const std::array<double, D>& c) : amplitude_deg(amplitude), center(c) {}

  double angle_deg(double t) const { return mean_angle_deg + amplitude_deg * std::sin(M_PI * t / 2); }

  std::array<double, D> operator()(const std::array<double, D>& p0, double t) const
  {
    const double a = (angle_deg(t) - mean_angle_deg) * M_PI / 180.0;
    const double c = std::cos(a), s = std::sin(a);
    std::array<double, D> q;
    if constexpr(D == 2) {
      const double x = p0[0] - center[0], y = p0[1] - center[1];
      q = {center[0] + c * x - s * y, center[1] + s * x + c * y};
    } else {
      const double n = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
      SPRING_MOTION_CHECK(n > 0, "pitch axis must be non-zero");
      const std::array<double, 3> k{axis[0] / n, axis[1] / n, axis[2] / n};
      const std::array<double, 3> v{p0[0] - center[0], p0[1] - center[1], p0[2] - center[2]};
      const std::array<double, 3> kxv{k[1] * v[2] - k[2] * v[1], k[2] * v[0] - k[0] * v[2], k[0] * v[1] - k[1] * v[0]};
      const double kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
      for(int i = 0; i < 3; ++i) // Rodrigues
        q[i] = center[i] + v[i] * c + kxv[i] * s + k[i] * kv * (1 - c);
    }
    return q;
  }

  Motion_description description() const
  {
    Motion_description d;
    d.kind = "pitch";
    d.amplitude_deg = amplitude_deg;
    d.mean_angle_deg = mean_angle_deg;
    d.center = {center[0], center[1], D == 3 ? center[D - 1] : 0.0};
    d.axis = D == 3 ? axis : std::array<double, 3>{0, 0, 1};
    return d;
  }
};

/// A rigid translation by `displacement`, applied linearly in t.
template <int D>
struct Translation_motion
{
  std::array<double, D> displacement{};

  std::array<double, D> operator()(const std::array<double, D>& p0, double t) const
  {
    std::array<double, D> q;
    for(int c = 0; c < D; ++c)
      q[c] = p0[c] + t * displacement[c];
    return q;
  }
  Motion_description description() const
  {
    Motion_description d;
    d.kind = "translate";
    for(int c = 0; c < D; ++c)
      d.displacement[c] = displacement[c];
    return d;
  }
};

} // namespace spring_motion

#endif
