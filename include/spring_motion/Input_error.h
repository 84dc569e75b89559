// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_INPUT_ERROR_H
#define SPRING_MOTION_INPUT_ERROR_H

#include <spring_motion/Error.h>

#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

namespace spring_motion {

/// Bad user input (a spring_motion::Error, like every exception of the
/// library and the command line): a mesh file that cannot be read, an output path that
/// cannot be written, an unknown file extension.
///
/// `what()` is one line, "FILE:LINE: message", so that editors and terminals
/// can jump to the offending line; when no line applies (a missing file, an
/// unknown extension) `line()` is 0 and `what()` is "FILE: message".
class Input_error : public Error
{
public:
  Input_error(std::string file, std::size_t line, std::string message)
    : Error(format(file, line, message)),
      file_(std::move(file)),
      line_(line),
      message_(std::move(message))
  {}

  const std::string& file() const noexcept { return file_; }
  /// 1-based line number, 0 when the error is not about one line.
  std::size_t line() const noexcept { return line_; }
  /// The message without the "FILE:LINE: " prefix.
  const std::string& message() const noexcept { return message_; }

private:
  static std::string format(const std::string& file, std::size_t line, const std::string& message)
  {
    std::string text = file;
    if(line != 0)
      text += ":" + std::to_string(line);
    text += ": ";
    text += message;
    return text;
  }

  std::string file_;
  std::size_t line_;
  std::string message_;
};

} // namespace spring_motion

#endif
