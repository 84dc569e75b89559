// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_ERROR_H
#define SPRING_MOTION_ERROR_H

#include <cstddef>
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

/// An error about one vertex of the spring network (for instance a free
/// vertex that no spring path joins to a constrained one). `vertex()` is its
/// network index, so that a caller that read the mesh from a file can name
/// the vertex as the file numbers it.
class Vertex_error : public Error
{
public:
  Vertex_error(const std::string& what, std::size_t vertex) : Error(what), vertex_(vertex) {}
  std::size_t vertex() const noexcept { return vertex_; }

private:
  std::size_t vertex_;
};

/// An error about one element (degenerate, inverted, overlapping a neighbour).
class Element_error : public Error
{
public:
  Element_error(const std::string& what, std::size_t element) : Error(what), element_(element) {}
  std::size_t element() const noexcept { return element_; }

private:
  std::size_t element_;
};

namespace internal {
[[noreturn]] inline void throw_error(const char* file, int line, const std::string& message)
{
  std::ostringstream out;
  out << message << " [" << file << ":" << line << "]";
  throw Error(out.str());
}
template <class Exception>
[[noreturn]] void throw_indexed_error(const char* file, int line, const std::string& message, std::size_t index)
{
  std::ostringstream out;
  out << message << " [" << file << ":" << line << "]";
  throw Exception(out.str(), index);
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

/// Throws spring_motion::Vertex_error about network vertex `vertex` when
/// `condition` is false.
#define SPRING_MOTION_VERTEX_CHECK(condition, vertex, message)                        \
  do {                                                                                \
    if(!(condition)) {                                                                \
      std::ostringstream spring_motion_check_stream_;                                 \
      spring_motion_check_stream_ << message;                                         \
      ::spring_motion::internal::throw_indexed_error<::spring_motion::Vertex_error>(  \
          __FILE__, __LINE__, spring_motion_check_stream_.str(), std::size_t(vertex)); \
    }                                                                                 \
  } while(false)

/// Throws spring_motion::Element_error about element `element` when
/// `condition` is false.
#define SPRING_MOTION_ELEMENT_CHECK(condition, element, message)                      \
  do {                                                                                \
    if(!(condition)) {                                                                \
      std::ostringstream spring_motion_check_stream_;                                 \
      spring_motion_check_stream_ << message;                                         \
      ::spring_motion::internal::throw_indexed_error<::spring_motion::Element_error>( \
          __FILE__, __LINE__, spring_motion_check_stream_.str(), std::size_t(element)); \
    }                                                                                 \
  } while(false)

#endif
