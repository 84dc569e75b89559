// Fuzz regressions: the inputs of tests/data/fuzz_regressions/
// replayed with the fuzz targets' property: a clean Input_error naming the
// file and line, or a mesh whose indices are in range and that then builds a
// spring network or makes it throw spring_motion::Error. Never a crash.
#include <spring_motion/Error.h>
#include <spring_motion/Input_error.h>
#include <spring_motion/Spring_network.h>
#include <spring_motion/io/read_mesh.h>

#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

using namespace spring_motion;

namespace {

const std::string dir = std::string(SPRING_MOTION_TEST_DATA_DIR) + "/fuzz_regressions/";

template <int D>
void check_read_mesh(const Indexed_mesh<D>& m)
{
  for(const auto& e : m.elements)
    for(auto v : e)
      CHECK(v < m.points.size());
  for(const auto& f : m.boundary_facets)
    for(auto v : f)
      CHECK(v < m.points.size());
  std::vector<Labeled_facet<D>> labeled;
  for(std::size_t i = 0; i < m.boundary_facets.size(); ++i)
    labeled.push_back({m.boundary_facets[i], m.boundary_labels[i]});
  try {
    make_spring_network<D>(m.points, m.elements, labeled);
  } catch(const Error&) {
  }
}

} // namespace

TEST_CASE("fuzz regressions: each hostile input gives its Input_error", "[fuzz][io]")
{
  struct Case
  {
    const char* file;
    const char* message; // after "FILE:LINE: "
    std::size_t line;
  };
  const Case cases[] = {
      {"huge_count.mesh", "unexpected end of file in section Vertices: expected 4000000000 vertices, read 1", 5},
      {"nan_coord.mesh", "found 'nan': not a finite number", 6},
      {"negative_index.mesh", "vertex index -3 out of range: expected 1 to 3", 10},
      {"overflow_index.mesh", "vertex index 4294967297 out of range: expected 1 to 3", 10},
      {"huge_nodes_v41.msh", "found '99999999999': more than the supported 4294967295", 5},
      {"inf_coord_v22.msh", "found '1e400': not a finite number", 7},
      // Binary Gmsh: no lines, the message starts with the byte offset.
      {"huge_nodes_v22_bin.msh", "byte 129: 4000000000 nodes of 28 bytes each, but only", 0},
      {"bad_marker_bin.msh", "byte 20: expected the integer 1 in binary", 0},
      {"nan_coord_v22_bin.msh", "byte 121: node 1 has the coordinate nan", 0},
      {"quad_element.su2", "quadrilateral (SU2 type 9) in NELEM", 3},
      {"huge_npoin.su2", "found '99999999999': more than the supported 4294967295", 51},
      {"negative_index.su2", "vertex index -24 out of range", 3},
  };
  for(const auto& c : cases) {
    INFO(c.file);
    try {
      read_mesh(dir + c.file);
      FAIL("no Input_error");
    } catch(const Input_error& e) {
      CHECK_THAT(e.message(), Catch::Contains(c.message));
      CHECK(e.line() == c.line);
      const std::string where = c.line == 0 ? "" : ":" + std::to_string(c.line);
      CHECK_THAT(std::string(e.what()), Catch::StartsWith(dir + c.file + where + ": "));
    }
  }
}

TEST_CASE("fuzz regressions: every file in the folder keeps the fuzz property", "[fuzz][io]")
{
  std::size_t files = 0;
  for(const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string path = entry.path().string();
    if(entry.path().extension() != ".mesh" && entry.path().extension() != ".msh"
       && entry.path().extension() != ".su2")
      continue;
    ++files;
    INFO(path);
    try {
      const auto f = read_mesh(path);
      REQUIRE((f.dimension == 2 || f.dimension == 3));
      if(f.dimension == 2)
        check_read_mesh(f.mesh_2);
      else
        check_read_mesh(f.mesh_3);
    } catch(const Input_error&) {
      // a clean refusal
    }
  }
  CHECK(files >= 12);
}
