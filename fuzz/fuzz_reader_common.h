// Shared body of the reader fuzz targets.
#ifndef SPRING_MOTION_FUZZ_READER_COMMON_H
#define SPRING_MOTION_FUZZ_READER_COMMON_H

#include <spring_motion/Error.h>
#include <spring_motion/Input_error.h>
#include <spring_motion/Spring_network.h>
#include <spring_motion/io/read_mesh.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

namespace spring_motion_fuzz {

[[noreturn]] inline void fail(const char* what)
{
  std::fprintf(stderr, "property violated: %s\n", what);
  std::abort();
}

template <int D>
void check_mesh(const spring_motion::Indexed_mesh<D>& m)
{
  const std::size_t n = m.points.size();
  for(const auto& e : m.elements)
    for(auto v : e)
      if(v >= n)
        fail("element vertex index out of range");
  for(const auto& f : m.boundary_facets)
    for(auto v : f)
      if(v >= n)
        fail("boundary facet vertex index out of range");
  if(m.element_labels.size() != m.elements.size())
    fail("element_labels and elements differ in size");
  if(m.boundary_labels.size() != m.boundary_facets.size())
    fail("boundary_labels and boundary_facets differ in size");
  // What a successfully read mesh goes through next: the spring network
  // either builds or throws spring_motion::Error.
  std::vector<spring_motion::Labeled_facet<D>> labeled;
  for(std::size_t i = 0; i < m.boundary_facets.size(); ++i)
    labeled.push_back({m.boundary_facets[i], m.boundary_labels[i]});
  try {
    auto net = spring_motion::make_spring_network<D>(m.points, m.elements, labeled);
    (void)net;
  } catch(const spring_motion::Error&) {
  }
}

/// Either a mesh whose indices are in range, or an Input_error; anything else
/// (another exception, a crash, a sanitizer report) is a finding.
template <class Read>
int run_reader(const std::uint8_t* data, std::size_t size, Read read)
{
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  spring_motion::Mesh_file f;
  try {
    f = read(in, "fuzz-input");
  } catch(const spring_motion::Input_error& e) {
    if(std::string(e.what()).rfind("fuzz-input", 0) != 0)
      fail("Input_error message does not start with the file name");
    return 0;
  }
  if(f.dimension == 2)
    check_mesh(f.mesh_2);
  else if(f.dimension == 3)
    check_mesh(f.mesh_3);
  else
    fail("dimension neither 2 nor 3 after a successful read");
  return 0;
}

} // namespace spring_motion_fuzz

#endif
