// Copyright (c) 2026 SpringMotion developers.
#include <spring_motion/Deform_report.h>
#include <spring_motion/Error.h>

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <ostream>
#include <sstream>
#include <string>

namespace spring_motion {
namespace {

// Shortest text that reads back to the same double; null for NaN and inf,
// which JSON cannot hold.
std::string number(double v)
{
  if(!std::isfinite(v))
    return "null";
  std::array<char, 32> buf;
  const auto r = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return std::string(buf.data(), r.ptr);
}

std::string quoted(const std::string& s)
{
  std::string out = "\"";
  for(char c : s) {
    switch(c) {
    case '"': out += "\\\""; break;
    case '\\': out += "\\\\"; break;
    case '\n': out += "\\n"; break;
    case '\t': out += "\\t"; break;
    default:
      if(static_cast<unsigned char>(c) < 0x20) {
        char u[8];
        std::snprintf(u, sizeof u, "\\u%04x", c);
        out += u;
      } else
        out += c;
    }
  }
  return out + "\"";
}

template <class It>
std::string array(It first, It last)
{
  std::string s = "[";
  for(It it = first; it != last; ++it)
    s += (it == first ? "" : ", ") + number(double(*it));
  return s + "]";
}

std::string histogram(const Skewness_histogram& h)
{
  return "{ \"histogram\": " + array(h.fractions.begin(), h.fractions.end()) + ", \"count\": " +
         std::to_string(h.count) + ", \"mean\": " + number(h.mean) + ", \"max\": " + number(h.max) + " }";
}

} // namespace

void write_report_json(const Deform_report& r, std::ostream& out)
{
  out << "{ \"format\": \"spring_motion.report/1\",\n";
  out << "  \"mesh\": { \"dimension\": " << r.dimension << ", \"vertices\": " << r.vertices
      << ", \"elements\": " << r.elements << ", \"moving_vertices\": " << r.moving_vertices
      << ", \"fixed_vertices\": " << r.fixed_vertices << " },\n";
  out << "  \"model\": { \"name\": " << quoted(r.model.name) << ", \"parameters\": {";
  for(std::size_t i = 0; i < r.model.parameters.size(); ++i)
    out << (i ? ", " : " ") << quoted(r.model.parameters[i].first) << ": " << number(r.model.parameters[i].second);
  out << " } },\n";
  const auto& m = r.motion;
  out << "  \"motion\": { \"kind\": " << quoted(m.kind) << ", \"amplitude_deg\": " << number(m.amplitude_deg)
      << ", \"mean_angle_deg\": " << number(m.mean_angle_deg) << ", \"steps\": " << r.number_of_steps
      << ", \"center\": " << array(m.center.begin(), m.center.end())
      << ", \"axis\": " << array(m.axis.begin(), m.axis.end())
      << ", \"displacement\": " << array(m.displacement.begin(), m.displacement.end()) << " },\n";
  out << "  \"solver\": { \"name\": "
      << quoted(r.solver.method == Solver_method::sor ? "sor" : "conjugate_gradient")
      << ", \"preconditioner\": "
      << quoted(r.solver.method == Solver_method::sor ? "none"
                : r.solver.preconditioner == Preconditioner::multigrid ? "multigrid" : "symmetric_gauss_seidel")
      << ", \"stopping\": " << quoted(r.solver.stopping == Stopping_rule::max_update ? "max_update" : "error_estimate")
      << ", \"relaxation_factor\": " << number(r.solver.relaxation_factor)
      << ", \"tolerance\": " << number(r.solver.tolerance) << ", \"max_iterations\": " << r.solver.max_iterations
      << ", \"warm_start\": " << (r.solver.warm_start ? "true" : "false") << " },\n";
  out << "  \"steps\": [";
  for(std::size_t i = 0; i < r.steps.size(); ++i) {
    const auto& s = r.steps[i];
    out << (i ? ",\n    " : "\n    ") << "{ \"step\": " << s.step << ", \"fraction\": " << number(s.fraction)
        << ", \"angle_deg\": " << number(s.angle_deg) << ", \"iterations\": " << s.iterations
        << ", \"converged\": " << (s.converged ? "true" : "false") << ", \"max_update\": " << number(s.max_update)
        << ", \"residual\": " << number(s.residual) << ", \"error_estimate\": " << number(s.error_estimate) << ", \"substeps\": " << s.substeps
        << ", \"inverted\": " << s.inverted << ", \"min_size_ratio\": " << number(s.min_size_ratio)
        << ", \"max_size_ratio\": " << number(s.max_size_ratio)
        << ", \"max_skewness_moving\": " << number(s.max_skewness_moving)
        << ", \"max_skewness_all\": " << number(s.max_skewness_all) << ", \"seconds\": { \"stiffness\": "
        << number(s.seconds_stiffness) << ", \"solve\": " << number(s.seconds_solve)
        << ", \"check\": " << number(s.seconds_check) << " } }";
  }
  out << (r.steps.empty() ? "],\n" : "\n  ],\n");
  out << "  \"completed\": " << (r.completed ? "true" : "false") << ",\n";
  out << "  \"converged\": " << (r.converged ? "true" : "false") << ",\n";
  out << "  \"first_invalid\": ";
  if(r.first_invalid) {
    const auto& f = *r.first_invalid;
    out << "{ \"step\": " << f.step << ", \"fraction\": " << number(f.fraction)
        << ", \"angle_deg\": " << number(f.angle_deg) << ", \"elements\": " << array(f.elements.begin(), f.elements.end())
        << " }";
  } else
    out << "null";
  out << ",\n  \"final_fraction\": " << number(r.final_fraction) << ",\n";
  out << "  \"final_angle_deg\": " << number(r.final_angle_deg) << ",\n";
  out << "  \"min_size_ratio\": " << number(r.min_size_ratio) << ",\n";
  out << "  \"max_size_ratio\": " << number(r.max_size_ratio) << ",\n";
  out << "  \"quality\": { \"moving_boundary\": " << histogram(r.quality_moving)
      << ",\n               \"all\": " << histogram(r.quality_all) << " },\n";
  out << "  \"seconds_total\": " << number(r.seconds_total) << " }\n";
}

void write_report_json(const Deform_report& report, const std::string& path)
{
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp);
    SPRING_MOTION_CHECK(f, "cannot open " << tmp << " for writing");
    write_report_json(report, f);
    f.close();
    if(!f) {
      std::remove(tmp.c_str());
      SPRING_MOTION_CHECK(false, "writing " << tmp << " failed");
    }
  }
  if(std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    SPRING_MOTION_CHECK(false, "cannot rename " << tmp << " to " << path);
  }
}

} // namespace spring_motion
