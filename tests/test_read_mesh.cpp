// Copyright (c) 2026 SpringMotion developers.
// Tests for include/spring_motion/io/read_mesh.h: the data files of
// tests/data (see its README), and malformed files written next to the line
// their error must name.
#include <spring_motion/io/read_mesh.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <atomic>
#include <cmath>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <random>
#include <sstream>
#include <string>

namespace fs = std::filesystem;
using spring_motion::Input_error;
using spring_motion::Mesh_file;

namespace {

std::string data_path(const std::string& name)
{
  return std::string(SPRING_MOTION_TEST_DATA_DIR) + "/" + name;
}

// A fresh directory, removed with its content at the end of the test.
class Temporary_directory
{
public:
  Temporary_directory()
  {
    static std::atomic<int> counter{0};
    const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
    path_ = fs::temp_directory_path()
            / ("spring_motion_test_read_" + std::to_string(stamp) + "_" + std::to_string(++counter));
    fs::create_directories(path_);
  }
  ~Temporary_directory()
  {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const
  {
    const std::string path = file(name);
    std::ofstream out(path, std::ios::binary);
    out << text;
    return path;
  }

private:
  fs::path path_;
};

// Reads `text` as a file called `name` and checks the error: it names the
// file and the line, and its message contains `fragment`.
void check_error(const std::string& name, const std::string& text, std::size_t line, const std::string& fragment)
{
  Temporary_directory directory;
  const std::string path = directory.write(name, text);
  try {
    spring_motion::read_mesh(path);
    FAIL("no exception reading " << name << ", expected one containing: " << fragment);
  } catch(const Input_error& e) {
    INFO("what(): " << e.what());
    CHECK(e.file() == path);
    CHECK(e.line() == line);
    const std::string prefix = line == 0 ? path + ": " : path + ":" + std::to_string(line) + ": ";
    CHECK(std::string(e.what()).compare(0, prefix.size(), prefix) == 0);
    CHECK(e.message().find(fragment) != std::string::npos);
    CHECK(std::string(e.what()).find('\n') == std::string::npos);
  }
}

std::map<int, std::size_t> histogram(const std::vector<int>& labels)
{
  std::map<int, std::size_t> counts;
  for(int label : labels)
    ++counts[label];
  return counts;
}

const std::string medit_2d_header = "MeshVersionFormatted 2\nDimension 2\n"; // lines 1-2

} // namespace

// ---- happy paths ------------------------------------------------------------

TEST_CASE("read_mesh: Medit 2D square", "[read_mesh][medit]")
{
  const Mesh_file file = spring_motion::read_mesh(data_path("square_2d.mesh"));
  REQUIRE(file.dimension == 2);
  const auto& mesh = file.mesh_2;
  CHECK(file.mesh_3.points.empty());
  REQUIRE(mesh.points.size() == 9);
  REQUIRE(mesh.elements.size() == 8);
  REQUIRE(mesh.element_labels.size() == 8);
  REQUIRE(mesh.boundary_facets.size() == 8);
  REQUIRE(mesh.boundary_labels.size() == 8);
  CHECK(mesh.points[1] == std::array<double, 2>{0.5, 0.0});
  CHECK(mesh.points[8] == std::array<double, 2>{1.0, 1.0});
  CHECK(mesh.elements[0] == std::array<std::uint32_t, 3>{0, 1, 4}); // "1 2 5" in the file
  CHECK(mesh.elements[7] == std::array<std::uint32_t, 3>{4, 8, 7});
  CHECK(histogram(mesh.element_labels) == std::map<int, std::size_t>{{1, 4}, {2, 4}});
  CHECK(mesh.boundary_facets[2] == std::array<std::uint32_t, 2>{2, 5});
  CHECK(histogram(mesh.boundary_labels) == std::map<int, std::size_t>{{1, 2}, {2, 2}, {3, 2}, {4, 2}});
  CHECK(mesh.label_names.empty());
}

TEST_CASE("read_mesh: Medit 3D cube", "[read_mesh][medit]")
{
  const Mesh_file file = spring_motion::read_mesh(data_path("cube_3d.mesh"));
  REQUIRE(file.dimension == 3);
  const auto& mesh = file.mesh_3;
  CHECK(file.mesh_2.points.empty());
  REQUIRE(mesh.points.size() == 8);
  REQUIRE(mesh.elements.size() == 6);
  REQUIRE(mesh.boundary_facets.size() == 12);
  CHECK(mesh.points[6] == std::array<double, 3>{0, 1, 1});
  CHECK(mesh.points[7] == std::array<double, 3>{1, 1, 1});
  CHECK(mesh.elements[0] == std::array<std::uint32_t, 4>{0, 1, 3, 7});
  CHECK(histogram(mesh.element_labels) == std::map<int, std::size_t>{{7, 6}});
  CHECK(histogram(mesh.boundary_labels)
        == std::map<int, std::size_t>{{1, 2}, {2, 2}, {3, 2}, {4, 2}, {5, 2}, {6, 2}});
  // Each labelled face lies on its plane: ref 1 is x = 0, ref 6 is z = 1.
  for(std::size_t i = 0; i < mesh.boundary_facets.size(); ++i)
    for(std::uint32_t v : mesh.boundary_facets[i]) {
      const int ref = mesh.boundary_labels[i];
      const int axis = (ref - 1) / 2;
      CHECK(mesh.points[v][static_cast<std::size_t>(axis)] == ((ref % 2 == 1) ? 0.0 : 1.0));
    }
}

TEST_CASE("read_medit: Dimension 3 with flat triangles only is 2D", "[read_mesh][medit]")
{
  std::istringstream in("MeshVersionFormatted 1\nDimension 3\nVertices 3\n0 0 0 0\n1 0 -0 0\n0 1 0 0\n"
                        "Triangles 1\n1 2 3 5\nEdges 1\n1 2 9\nEnd\n");
  const Mesh_file file = spring_motion::read_medit(in, "flat.mesh");
  REQUIRE(file.dimension == 2);
  CHECK(file.mesh_2.points.size() == 3);
  CHECK(file.mesh_2.points[1] == std::array<double, 2>{1, 0});
  CHECK(file.mesh_2.element_labels == std::vector<int>{5});
  CHECK(file.mesh_2.boundary_labels == std::vector<int>{9});
}

TEST_CASE("read_medit: free format, comments, CRLF, byte order mark, no End", "[read_mesh][medit]")
{
  // every blank of the C locale between tokens, a comment right after a token
  std::istringstream in("\xEF\xBB\xBF# comment\r\nMeshVersionFormatted 2 Dimension\r\n2# trailing comment\r\n"
                        "Vertices 3 0\t0 1\v1 0\f1\r\n0 +1 1 Triangles 1 1 2 3 -4#\r\n"
                        "SomeFutureSection 2 1 2 3 4\r\n");
  const Mesh_file file = spring_motion::read_medit(in, "free.mesh");
  REQUIRE(file.dimension == 2);
  CHECK(file.mesh_2.points[2] == std::array<double, 2>{0, 1});
  CHECK(file.mesh_2.element_labels == std::vector<int>{-4});
}

TEST_CASE("read_mesh: Gmsh 2.2 square with a hole", "[read_mesh][gmsh]")
{
  const Mesh_file file = spring_motion::read_mesh(data_path("square_hole_v22.msh"));
  REQUIRE(file.dimension == 2);
  const auto& mesh = file.mesh_2;
  CHECK(mesh.points.size() == 36);
  CHECK(mesh.elements.size() == 48);
  CHECK(mesh.boundary_facets.size() == 24);
  CHECK(mesh.points[0] == std::array<double, 2>{0, 0});
  CHECK(mesh.points[4] == std::array<double, 2>{0.7, 0.5});
  CHECK(mesh.points[8] == std::array<double, 2>{0.2499999999994121, 0});
  CHECK(histogram(mesh.element_labels) == std::map<int, std::size_t>{{10, 48}});
  CHECK(histogram(mesh.boundary_labels) == std::map<int, std::size_t>{{1, 16}, {2, 8}});
  CHECK(mesh.label_names == std::map<int, std::string>{{1, "outer"}, {2, "hole"}, {10, "fluid"}});
  // The hole's edges are on the circle of radius 0.2 around (0.5, 0.5).
  for(std::size_t i = 0; i < mesh.boundary_facets.size(); ++i)
    if(mesh.boundary_labels[i] == 2)
      for(std::uint32_t v : mesh.boundary_facets[i]) {
        const double dx = mesh.points[v][0] - 0.5, dy = mesh.points[v][1] - 0.5;
        CHECK(std::sqrt(dx * dx + dy * dy) == Approx(0.2));
      }
}

TEST_CASE("read_mesh: Gmsh 4.1 gives the same mesh as 2.2", "[read_mesh][gmsh]")
{
  const Mesh_file v22 = spring_motion::read_mesh(data_path("square_hole_v22.msh"));
  const Mesh_file v41 = spring_motion::read_mesh(data_path("square_hole_v41.msh"));
  REQUIRE(v41.dimension == 2);
  CHECK(v41.mesh_2.points == v22.mesh_2.points);
  CHECK(v41.mesh_2.elements == v22.mesh_2.elements);
  CHECK(v41.mesh_2.element_labels == v22.mesh_2.element_labels);
  CHECK(v41.mesh_2.boundary_facets == v22.mesh_2.boundary_facets);
  CHECK(v41.mesh_2.boundary_labels == v22.mesh_2.boundary_labels);
  CHECK(v41.mesh_2.label_names == v22.mesh_2.label_names);
}

TEST_CASE("read_mesh: Gmsh 4.1 box", "[read_mesh][gmsh]")
{
  const Mesh_file file = spring_motion::read_mesh(data_path("box_3d_v41.msh"));
  REQUIRE(file.dimension == 3);
  const auto& mesh = file.mesh_3;
  CHECK(mesh.points.size() == 45);
  CHECK(mesh.elements.size() == 100);
  CHECK(mesh.boundary_facets.size() == 84);
  CHECK(mesh.points[0] == std::array<double, 3>{0, 0, 0});
  CHECK(mesh.points[7] == std::array<double, 3>{0, 1, 1});
  CHECK(histogram(mesh.element_labels) == std::map<int, std::size_t>{{100, 100}});
  CHECK(histogram(mesh.boundary_labels) == std::map<int, std::size_t>{{1, 14}, {2, 14}, {3, 56}});
  CHECK(mesh.label_names
        == std::map<int, std::string>{{1, "inlet"}, {2, "outlet"}, {3, "walls"}, {100, "domain"}});
  for(std::size_t i = 0; i < mesh.boundary_facets.size(); ++i)
    for(std::uint32_t v : mesh.boundary_facets[i]) {
      if(mesh.boundary_labels[i] == 1)
        CHECK(mesh.points[v][0] == 0.0);
      if(mesh.boundary_labels[i] == 2)
        CHECK(mesh.points[v][0] == 1.0);
    }
}

TEST_CASE("read_gmsh: 2.2 with sparse node tags, duplicates, points and unknown types", "[read_mesh][gmsh]")
{
  // An entity in two physical groups is written twice in 2.2; type 15
  // (point) is dropped; type 99 is unknown and skipped; $Comments skipped.
  std::istringstream in("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
                        "$Comments\nanything $Nodes 3\n$EndComments\n"
                        "$PhysicalNames\n3\n1 5 \"wall\"\n2 7 \"fluid domain\"\n2 5 \"other\"\n$EndPhysicalNames\n"
                        "$Nodes\n4\n10 0 0 0\n30 1 0 0\n20 1 1 0\n1000000000000 0 1 0\n$EndNodes\n"
                        "$Elements\n7\n"
                        "1 15 2 0 1 10\n"
                        "2 1 2 5 1 10 30\n"
                        "3 1 2 6 1 30 10\n"
                        "4 2 2 7 1 10 30 20\n"
                        "5 2 2 7 1 10 20 1000000000000\n"
                        "6 2 2 8 1 20 30 10\n"
                        "7 99 0 1 2 3 4 5 6 7 8 9\n"
                        "$EndElements\n");
  const Mesh_file file = spring_motion::read_gmsh(in, "sparse.msh");
  REQUIRE(file.dimension == 2);
  const auto& mesh = file.mesh_2;
  CHECK(mesh.points.size() == 4);
  CHECK(mesh.points[1] == std::array<double, 2>{1, 0}); // tag 30 is the second node
  CHECK(mesh.elements == std::vector<std::array<std::uint32_t, 3>>{{0, 1, 2}, {0, 2, 3}});
  CHECK(mesh.element_labels == std::vector<int>{7, 7});
  CHECK(mesh.boundary_facets == std::vector<std::array<std::uint32_t, 2>>{{0, 1}});
  CHECK(mesh.boundary_labels == std::vector<int>{5});
  // Number 5 is used in dimensions 1 and 2: the boundary's name wins.
  CHECK(mesh.label_names == std::map<int, std::string>{{5, "wall"}, {7, "fluid domain"}});
}

TEST_CASE("read_gmsh: 4.1 with sparse tags, parametric nodes, no physical groups", "[read_mesh][gmsh]")
{
  std::istringstream in("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
                        "$Entities\n0 1 1 0\n"
                        "3 0 0 0 1 0 0 1 4 0\n"
                        "1 0 0 0 1 1 0 0 0\n"
                        "$EndEntities\n"
                        "$Nodes\n2 4 5 90\n"
                        "1 3 1 2\n5\n90\n0 0 0 0\n1 0 0 1\n"
                        "2 1 0 2\n17\n8\n1 1 0\n0 1 0\n"
                        "$EndNodes\n"
                        "$Elements\n2 3 1 3\n"
                        "1 3 1 1\n1 5 90\n"
                        "2 1 2 2\n2 5 90 17\n3 5 17 8\n"
                        "$EndElements\n");
  const Mesh_file file = spring_motion::read_gmsh(in, "sparse41.msh");
  REQUIRE(file.dimension == 2);
  const auto& mesh = file.mesh_2;
  CHECK(mesh.points == std::vector<std::array<double, 2>>{{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  CHECK(mesh.elements == std::vector<std::array<std::uint32_t, 3>>{{0, 1, 2}, {0, 2, 3}});
  CHECK(mesh.element_labels == std::vector<int>{0, 0});
  CHECK(mesh.boundary_labels == std::vector<int>{4});
}

// ---- errors -----------------------------------------------------------------

TEST_CASE("read_mesh: missing file, unknown extension, directory", "[read_mesh][errors]")
{
  Temporary_directory directory;
  const std::string missing = directory.file("missing.mesh");
  try {
    spring_motion::read_mesh(missing);
    FAIL("no exception");
  } catch(const Input_error& e) {
    CHECK(e.file() == missing);
    CHECK(e.line() == 0);
    CHECK(std::string(e.what()) == missing + ": cannot open file: No such file or directory");
  }

  const std::string wrong = directory.write("mesh.obj", "v 0 0 0\n");
  try {
    spring_motion::read_mesh(wrong);
    FAIL("no exception");
  } catch(const Input_error& e) {
    CHECK(e.line() == 0);
    CHECK(std::string(e.what()).find(wrong + ": unknown mesh file extension '.obj'") == 0);
    CHECK(e.message().find(".mesh") != std::string::npos);
    CHECK(e.message().find(".msh") != std::string::npos);
  }

  try {
    spring_motion::read_mesh(directory.file("mesh"));
    FAIL("no exception");
  } catch(const Input_error& e) {
    CHECK(e.message().find("no file extension: expected .mesh") == 0);
  }

  fs::create_directory(directory.file("folder.msh"));
  CHECK_THROWS_AS(spring_motion::read_mesh(directory.file("folder.msh")), Input_error);
}

TEST_CASE("read_medit: truncated and miscounted sections", "[read_mesh][medit][errors]")
{
  const std::string h = medit_2d_header; // lines 1-2
  check_error("truncated.mesh", h + "Vertices\n4\n0 0 0\n1 0 0\n", 6,
              "unexpected end of file in section Vertices: expected 4 vertices, read 2");
  check_error("truncated_mid.mesh", h + "Vertices\n2\n0 0 0\n1 0", 6,
              "unexpected end of file in section Vertices: expected 2 vertices, read 1");
  check_error("short.mesh", h + "Vertices\n3\n0 0 0\n1 0 0\nTriangles\n1\n1 2 3 0\n", 7,
              "expected a vertex coordinate, found 'Triangles' (section Vertices: expected 3 vertices, read 2)");
  check_error("long.mesh", h + "Vertices\n2\n0 0 0\n1 0 0\n0 1 0\nTriangles\n1\n1 2 3 0\n", 7,
              "expected a section keyword, found '0' after section Vertices (is its count right?)");
  check_error("truncated_triangles.mesh", h + "Vertices 3\n0 0 0\n1 0 0\n0 1 0\nTriangles\n2\n1 2 3 0\n", 9,
              "unexpected end of file in section Triangles: expected 2 triangles, read 1");
  check_error("truncated_skipped.mesh", h + "Corners\n3\n1 2\n", 5,
              "unexpected end of file in section Corners: expected 3 entries, read 2");
  check_error("negative.mesh", h + "Vertices\n-3\n", 4, "a count cannot be negative");
  check_error("no_count.mesh", h + "Vertices\nTriangles\n", 4, "expected the number of vertices, found 'Triangles'");
  check_error("overflowing_count.mesh", h + "Vertices\n99999999999999999999999\n", 4,
              "expected the number of vertices");
  check_error("huge_count.mesh", h + "Vertices\n99999999999\n", 4, "more than the supported 4294967295");
  // The largest count is accepted, and must not allocate what it announces.
  check_error("absurd_count.mesh", h + "Vertices\n4294967295\n0 0 0\n", 5,
              "expected 4294967295 vertices, read 1");
  check_error("empty.mesh", "", 0, "no Dimension section");
  check_error("no_vertices.mesh", h + "\n", 3, "no Vertices section");
}

TEST_CASE("read_medit: bad values", "[read_mesh][medit][errors]")
{
  const std::string h = medit_2d_header + "Vertices\n3\n0 0 0\n1 0 0\n"; // lines 1-6
  const std::string t = "Triangles\n1\n"; // lines 8-9
  check_error("text.mesh", h + "0 0.5x 0\n", 7, "expected a vertex coordinate, found '0.5x'");
  check_error("nan.mesh", h + "nan 1 0\n", 7, "found 'nan': not a finite number");
  check_error("inf.mesh", h + "0 -inf 0\n", 7, "found '-inf': not a finite number");
  check_error("overflow.mesh", h + "0 1e999 0\n", 7, "found '1e999': not a finite number");
  check_error("bad_ref.mesh", h + "0 1 0.5\n", 7, "expected a vertex reference, found '0.5'");
  check_error("index_high.mesh", h + "0 1 0\n" + t + "1 2 4 0\n", 10,
              "vertex index 4 out of range: expected 1 to 3 (Triangles entry 1)");
  check_error("index_zero.mesh", h + "0 1 0\n" + t + "0 1 2 0\n", 10, "vertex index 0 out of range");
  check_error("index_huge.mesh", h + "0 1 0\n" + t + "1 2 99999999999999999999 0\n", 10,
              "expected a vertex index, found '99999999999999999999'");
  check_error("repeated.mesh", h + "0 1 0\n" + t + "1 2 2 0\n", 10,
              "an element uses the same vertex twice: expected 3 distinct vertices (Triangles entry 1)");
  check_error("edge_index.mesh", h + "0 1 0\n" + t + "1 2 3 0\nEdges\n1\n1 7 0\n", 13, "vertex index 7 out of range");
  check_error("dimension.mesh", "MeshVersionFormatted 2\nDimension\n4\n", 3, "expected Dimension 2 or 3, found 4");
  check_error("version.mesh", "MeshVersionFormatted 9\n", 1, "expected MeshVersionFormatted 1 to 4");
  check_error("binary.mesh", "MeshVersionUnformatted 2\n", 1, "binary Medit meshes are not supported");
  check_error("order.mesh", "MeshVersionFormatted 2\nDimension 2\nTriangles\n0\n", 3,
              "section Triangles before Vertices");
  check_error("no_dimension.mesh", "MeshVersionFormatted 2\nVertices\n0\n", 2, "section Vertices before Dimension");
}

TEST_CASE("read_medit: no elements, mixed dimensions, unsupported elements", "[read_mesh][medit][errors]")
{
  const std::string v2 = medit_2d_header + "Vertices\n3\n0 0 0\n1 0 0\n0 1 0\n"; // lines 1-7
  check_error("edges_only.mesh", v2 + "Edges\n1\n1 2 0\nEnd\n", 11, "no triangles or tetrahedra");
  check_error("typo.mesh", v2 + "Triangle\n1\n1 2 3 0\n", 10, "skipped unknown sections: 'Triangle'");
  check_error("tets_in_2d.mesh", v2 + "Tetrahedra\n1\n1 2 3 3 0\n", 8,
              "Tetrahedra in a Dimension 2 file: mixed 2D and 3D elements");
  check_error("quads.mesh", v2 + "Triangles\n1\n1 2 3 0\nQuadrilaterals\n1\n1 2 3 3 0\n", 11,
              "unsupported elements (Quadrilaterals, 1 in all): expected linear triangles only");
  const std::string v3 = "MeshVersionFormatted 2\nDimension 3\nVertices\n3\n0 0 0 0\n1 0 0.25 0\n0 1 0 0\n";
  check_error("surface.mesh", v3 + "Triangles\n1\n1 2 3 0\n", 6,
              "vertex 2 has z = 0.25 in a mesh of triangles without tetrahedra: surface meshes in 3D are not "
              "supported");
  const std::string v3_4 = "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n";
  check_error("prisms.mesh", v3_4 + "Tetrahedra\n1\n1 2 3 4 0\nPrisms\n1\n1 2 3 4 4 4 0\n", 12,
              "unsupported elements (Prisms, 1 in all): expected linear tetrahedra only");
}

TEST_CASE("read_gmsh: malformed files", "[read_mesh][gmsh][errors]")
{
  const std::string f22 = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"; // lines 1-3
  const std::string nodes22 = "$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n"; // lines 4-9
  check_error("empty.msh", "", 0, "empty file: expected a Gmsh mesh starting with $MeshFormat");
  check_error("not_gmsh.msh", "hello\n", 1, "expected $MeshFormat at the start of a Gmsh file, found 'hello'");
  check_error("v3.msh", "$MeshFormat\n3.0 0 8\n$EndMeshFormat\n", 2,
              "unsupported Gmsh format version '3.0': expected 2.2 or 4.1");
  check_error("v40.msh", "$MeshFormat\n4 0 8\n$EndMeshFormat\n", 2, "expected 2.2 or 4.1");
  // Binary files are read (tests/test_read_gmsh_binary.cpp); one cut inside
  // the byte-order marker names the byte where the file ends.
  check_error("binary.msh", std::string("$MeshFormat\n4.1 1 8\n\x01\x00", 22), 0,
              "byte 22: unexpected end of file: expected the binary integer 1 after the format line");
  check_error("no_nodes.msh", f22, 3, "no $Nodes section");
  check_error("truncated_nodes.msh", f22 + "$Nodes\n3\n1 0 0 0\n2 1 0", 7,
              "unexpected end of file in section $Nodes: expected 3 nodes, read 1");
  check_error("short_nodes.msh", f22 + "$Nodes\n3\n1 0 0 0\n2 1 0 0\n$EndNodes\n", 8,
              "expected a node number, found '$EndNodes' (section $Nodes: expected 3 nodes, read 2)");
  check_error("long_nodes.msh", f22 + "$Nodes\n1\n1 0 0 0\n2 1 0 0\n$EndNodes\n", 7,
              "expected $EndNodes after 1 nodes, found '2' (is the count in $Nodes right?)");
  check_error("nan_node.msh", f22 + "$Nodes\n1\n1 0 NaN 0\n$EndNodes\n", 6, "found 'NaN': not a finite number");
  check_error("text_node.msh", f22 + "$Nodes\n1\n1 0 zero 0\n$EndNodes\n", 6, "expected a node coordinate, found 'zero'");
  check_error("duplicate_node.msh", f22 + "$Nodes\n2\n1 0 0 0\n1 1 0 0\n$EndNodes\n", 7, "node tag 1 is used twice");
  check_error("zero_tag.msh", f22 + "$Nodes\n1\n0 0 0 0\n$EndNodes\n", 6, "expected a positive node tag");
  check_error("elements_first.msh", f22 + "$Elements\n0\n$EndElements\n", 4, "section $Elements before $Nodes");
  check_error("missing_node.msh", f22 + nodes22 + "$Elements\n1\n1 2 2 0 1 1 2 4\n$EndElements\n", 12,
              "node 4 is not in $Nodes: expected a node tag of the file ($Elements entry 1)");
  check_error("truncated_elements.msh", f22 + nodes22 + "$Elements\n2\n1 2 2 0 1 1 2 3\n", 12,
              "unexpected end of file in section $Elements: expected 2 elements, read 1");
  check_error("short_elements.msh", f22 + nodes22 + "$Elements\n2\n1 2 2 0 1 1 2 3\n$EndElements\n", 13,
              "expected an element number, found '$EndElements' (section $Elements: expected 2 elements, read 1)");
  check_error("unterminated.msh", f22 + nodes22 + "$Elements\n1\n1 2 2 0 1 1 2 3\n", 12,
              "unexpected end of file: expected $EndElements");
  check_error("unterminated_section.msh", f22 + "$NodeData\n1\n\"x\"\n", 6,
              "unexpected end of file in section $NodeData (started at line 4): expected $EndNodeData");
  check_error("bad_name.msh", f22 + "$PhysicalNames\n1\n1 2 wall\n$EndPhysicalNames\n", 6,
              "expected a quoted physical name, found 'wall'");
  check_error("no_elements.msh", f22 + nodes22 + "$Elements\n1\n1 1 2 0 1 1 2\n$EndElements\n", 13,
              "no triangles or tetrahedra");
  check_error("surface.msh",
              f22 + "$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 1e-9\n$EndNodes\n$Elements\n1\n1 2 2 0 1 1 2 3\n$EndElements\n", 8,
              "vertex 3 has z = 1.0000000000000001e-09 in a mesh of triangles without tetrahedra: surface "
              "meshes in 3D are not supported");
  check_error("quads.msh", f22 + "$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n$EndNodes\n"
              "$Elements\n2\n1 2 2 0 1 1 2 3\n2 3 2 0 1 1 2 3 4\n$EndElements\n", 14,
              "unsupported elements (quadrangle (Gmsh type 3), 1 in all): expected linear triangles only");
  check_error("repeated.msh", f22 + nodes22 + "$Elements\n1\n1 2 2 0 1 1 2 2\n$EndElements\n", 12,
              "an element uses the same vertex twice");

  const std::string f41 = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"; // lines 1-3
  check_error("blocks.msh", f41 + "$Nodes\n1 3 1 3\n0 1 0 2\n1\n2\n0 0 0\n1 0 0\n$EndNodes\n", 10,
              "the $Nodes header announces 3 nodes, its 1 entity blocks hold 2");
  check_error("big_block.msh", f41 + "$Nodes\n1 3 1 3\n0 1 0 4\n", 6,
              "an entity block of 4 nodes after 0: more than the 3 nodes announced in the $Nodes header");
  check_error("truncated_41.msh", f41 + "$Nodes\n1 2 1 2\n0 1 0 2\n1\n2\n0 0 0\n", 9,
              "unexpected end of file in section $Nodes: expected 2 nodes, read 1");
  check_error("entities.msh", f41 + "$Entities\n1 0 0 0\n1 0 0\n$EndEntities\n", 7,
              "expected an entity coordinate, found '$EndEntities' (section $Entities: expected 1 points, read 0)");
}

TEST_CASE("read_mesh: truncated and corrupted copies of the data files never crash", "[read_mesh][errors]")
{
  // Cut every data file at many places and flip bytes: each copy must read
  // or throw Input_error, nothing else (run under the sanitizers too).
  Temporary_directory directory;
  std::mt19937 random(12345);
  for(const char* name : {"square_2d.mesh", "cube_3d.mesh", "square_hole_v22.msh", "square_hole_v41.msh",
                          "box_3d_v41.msh"}) {
    std::ifstream in(data_path(name), std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    REQUIRE(!text.empty());
    const std::string extension = fs::path(name).extension().string();
    std::size_t read = 0, failed = 0;
    const auto attempt = [&](const std::string& copy) {
      const std::string path = directory.write(std::string("copy") + extension, copy);
      try {
        spring_motion::read_mesh(path);
        ++read;
      } catch(const Input_error& e) {
        ++failed;
        CHECK(std::string(e.what()).find('\n') == std::string::npos);
      }
    };
    for(std::size_t length = 0; length < text.size(); length += 1 + text.size() / 200)
      attempt(text.substr(0, length));
    static const char replacements[] = {'0', '9', '-', '$', ' ', '\n', 'x', '\0', '.', 'e'};
    for(int trial = 0; trial < 200; ++trial) {
      std::string copy = text;
      for(int k = 0; k < 3; ++k)
        copy[random() % copy.size()] = replacements[random() % sizeof(replacements)];
      attempt(copy);
    }
    INFO(name << ": " << read << " copies read, " << failed << " rejected");
    CHECK(failed > 0);
  }
}

TEST_CASE("read_mesh: source lines of elements and facets, and the file's vertex numbers", "[read_mesh]")
{
  const Mesh_file medit = spring_motion::read_mesh(data_path("square_2d.mesh"));
  REQUIRE(medit.element_lines.size() == medit.mesh_2.elements.size());
  REQUIRE(medit.boundary_facet_lines.size() == medit.mesh_2.boundary_facets.size());
  REQUIRE(medit.vertex_ids.size() == medit.mesh_2.points.size());
  for(std::size_t i = 0; i < medit.vertex_ids.size(); ++i)
    CHECK(medit.vertex_ids[i] == std::int64_t(i + 1));
  // every recorded line holds that element's vertex numbers, 1-based
  std::ifstream in(data_path("square_2d.mesh"));
  std::vector<std::string> lines;
  for(std::string l; std::getline(in, l);)
    lines.push_back(l);
  for(std::size_t t = 0; t < medit.element_lines.size(); ++t) {
    std::istringstream line(lines.at(medit.element_lines[t] - 1));
    std::array<std::uint32_t, 3> v;
    line >> v[0] >> v[1] >> v[2];
    CHECK(v[0] == medit.mesh_2.elements[t][0] + 1);
    CHECK(v[1] == medit.mesh_2.elements[t][1] + 1);
    CHECK(v[2] == medit.mesh_2.elements[t][2] + 1);
  }
  for(std::size_t f = 0; f < medit.boundary_facet_lines.size(); ++f) {
    std::istringstream line(lines.at(medit.boundary_facet_lines[f] - 1));
    std::array<std::uint32_t, 2> v;
    line >> v[0] >> v[1];
    CHECK(v[0] == medit.mesh_2.boundary_facets[f][0] + 1);
    CHECK(v[1] == medit.mesh_2.boundary_facets[f][1] + 1);
  }

  // Gmsh: sparse node tags are kept as the vertex numbers; duplicates of an
  // element in two physical groups keep the first copy's line
  const std::string text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"          // 1-3
                           "$Nodes\n3\n10 0 0 0\n20 1 0 0\n30 0 1 0\n$EndNodes\n" // 4-9
                           "$Elements\n3\n1 2 2 5 1 10 20 30\n"                    // 10-12
                           "2 1 2 7 1 10 20\n3 2 2 6 1 10 20 30\n$EndElements\n";  // 13-15
  std::istringstream gmsh(text);
  const Mesh_file g = spring_motion::read_gmsh(gmsh, "sparse.msh");
  REQUIRE(g.dimension == 2);
  CHECK(g.vertex_ids == std::vector<std::int64_t>{10, 20, 30});
  CHECK(g.element_lines == std::vector<std::size_t>{12});
  CHECK(g.boundary_facet_lines == std::vector<std::size_t>{13});
}

TEST_CASE("read_mesh: facets of a separate lower-dimensional part are mixed dimensions", "[read_mesh][errors]")
{
  // a tetrahedron plus a triangle that shares no vertex with it
  const std::string v3 = "MeshVersionFormatted 2\nDimension 3\nVertices\n5\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n"
                         "5 5 5 0\n"; // lines 1-9
  check_error("mixed.mesh", v3 + "Tetrahedra\n1\n1 2 3 4 0\nTriangles\n2\n1 2 3 1\n1 2 5 2\nEnd\n", 16,
              "mixed dimensions: this triangle uses vertex 5, which no tetrahedron uses");
  // a triangle plus a line to a vertex outside it
  const std::string v2 = medit_2d_header + "Vertices\n4\n0 0 0\n1 0 0\n0 1 0\n3 3 0\n"; // lines 1-8
  check_error("mixed_2d.mesh", v2 + "Triangles\n1\n1 2 3 0\nEdges\n1\n3 4 1\n", 14,
              "mixed dimensions: this edge uses vertex 4, which no triangle uses");
}
