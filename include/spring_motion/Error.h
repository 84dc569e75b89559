// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_ERROR_H
#define SPRING_MOTION_ERROR_H

#include <sstream>
#include <stdexcept>
#include <string>

namespace spring_motion {

/// Thrown for bad input and API misuse. CGAL's own preconditions vanish under
/// NDEBUG, so every check a user can trip is ours and survives release builds.
class Error : public std::runtime_error
{
public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

namespace internal {
[[noreturn]] inline void throw_error(const char* file, int line, const std::string& message)
{
  std::ostringstream out;
  out << message << " [" << file << ":" << line << "]";
  throw Error(out.str());
}
} // namespace internal

} // namespace spring_motion

/// Throws spring_motion::Error when `condition` is false. `message` is a stream
/// expression, e.g. SPRING_MOTION_CHECK(k >= 0, "edge " << e << " has k = " << k).
#define SPRING_MOTION_CHECK(condition, message)                                       \
  do {                                                                                \
    if(!(condition)) {                                                                \
      std::ostringstream spring_motion_check_stream_;                                 \
      spring_motion_check_stream_ << message;                                         \
      ::spring_motion::internal::throw_error(__FILE__, __LINE__,                      \
                                             spring_motion_check_stream_.str());      \
    }                                                                                 \
  } while(false)

#endif
