// Copyright (c) 2026 SpringMotion developers.
// Private to the spring-motion executable: the one-line progress display.
#ifndef SPRING_MOTION_SRC_CLI_PROGRESS_BAR_H
#define SPRING_MOTION_SRC_CLI_PROGRESS_BAR_H

#include <spring_motion/Deform_report.h>

#include <cstddef>
#include <ostream>
#include <string>

namespace spring_motion {
namespace cli {

/// Redraws one line on a terminal after each step: a bar, step i/n, the
/// angle (pitch) or motion fraction, the solver's iterations, the worst R of
/// the elements touching the moving boundary, elapsed and remaining time.
/// Disabled, it prints nothing at all.
class Progress_bar
{
public:
  Progress_bar(std::ostream& out, bool enabled, std::size_t steps) : out_(out), enabled_(enabled), steps_(steps) {}
  ~Progress_bar() { clear(); }

  void update(const Step_report& step, double elapsed_seconds);
  /// Erases the line, so that what follows starts on a clean one.
  void clear();

  /// The line update() draws, without the carriage return (for tests).
  static std::string format(const Step_report& step, std::size_t steps, double elapsed_seconds, std::size_t width);

private:
  std::ostream& out_;
  bool enabled_;
  std::size_t steps_;
  std::size_t drawn_ = 0; // characters on the line now
};

/// "1:05", "12.3 s", "2:03:04": a duration for people.
std::string format_duration(double seconds);

} // namespace cli
} // namespace spring_motion

#endif
