// Copyright (c) 2026 SpringMotion developers.
#include "Progress_bar.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace spring_motion {
namespace cli {

std::string format_duration(double seconds)
{
  char b[32];
  if(!std::isfinite(seconds) || seconds < 0)
    return "?";
  if(seconds < 60)
    std::snprintf(b, sizeof b, "%.1f s", seconds);
  else if(seconds < 3600)
    std::snprintf(b, sizeof b, "%d:%02d", int(seconds) / 60, int(seconds) % 60);
  else
    std::snprintf(b, sizeof b, "%d:%02d:%02d", int(seconds) / 3600, int(seconds) / 60 % 60, int(seconds) % 60);
  return b;
}

std::string Progress_bar::format(const Step_report& s, std::size_t steps, double elapsed, std::size_t width)
{
  std::string bar(width, ' ');
  const std::size_t filled = steps == 0 ? width : std::min(width, width * s.step / steps);
  for(std::size_t i = 0; i < filled; ++i)
    bar[i] = '#';
  char where[48];
  if(std::isfinite(s.angle_deg))
    std::snprintf(where, sizeof where, "angle %7.2f deg", s.angle_deg);
  else
    std::snprintf(where, sizeof where, "t %5.3f", s.fraction);
  char r[24] = "R -";
  if(std::isfinite(s.max_skewness_moving))
    std::snprintf(r, sizeof r, "R %.3f", s.max_skewness_moving);
  const double left = s.step == 0 ? NAN : elapsed / double(s.step) * double(steps - s.step);
  char line[256];
  std::snprintf(line, sizeof line, "[%s] step %zu/%zu  %s  %zu it  %s  %s elapsed, %s left", bar.c_str(), s.step,
                steps, where, s.iterations, r, format_duration(elapsed).c_str(), format_duration(left).c_str());
  return line;
}

void Progress_bar::update(const Step_report& step, double elapsed_seconds)
{
  if(!enabled_)
    return;
  const std::string line = format(step, steps_, elapsed_seconds, 20);
  out_ << '\r' << line;
  if(line.size() < drawn_)
    out_ << std::string(drawn_ - line.size(), ' ');
  drawn_ = std::max(drawn_, line.size());
  out_.flush();
}

void Progress_bar::clear()
{
  if(!enabled_ || drawn_ == 0)
    return;
  out_ << '\r' << std::string(drawn_, ' ') << '\r';
  out_.flush();
  drawn_ = 0;
}

} // namespace cli
} // namespace spring_motion
