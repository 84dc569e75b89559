// Copyright (c) 2026 SpringMotion developers.
// Tests for the binary Gmsh reader (read_gmsh() on files of gmsh -bin,
// formats 2.2 and 4.1, both byte orders): the data files of tests/data read
// the same as their ASCII sources, and hostile files built byte by byte here
// give an Input_error naming the file and the byte offset of the problem.
#include <spring_motion/io/read_mesh.h>

#include <catch2/catch.hpp>

#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

using spring_motion::Input_error;
using spring_motion::Mesh_file;

namespace {

std::string data_path(const std::string& name)
{
  return std::string(SPRING_MOTION_TEST_DATA_DIR) + "/" + name;
}

std::string file_bytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

template <int D>
void check_same_mesh(const spring_motion::Indexed_mesh<D>& a, const spring_motion::Indexed_mesh<D>& b)
{
  CHECK(a.points == b.points); // bit for bit: the binary file holds the same doubles
  CHECK(a.elements == b.elements);
  CHECK(a.element_labels == b.element_labels);
  CHECK(a.boundary_facets == b.boundary_facets);
  CHECK(a.boundary_labels == b.boundary_labels);
  CHECK(a.label_names == b.label_names);
}

// Writes the binary parts of a test file in either byte order, and remembers
// where the fields the tests corrupt are.
class Builder
{
public:
  explicit Builder(bool big_endian) : big_(big_endian) {}

  Builder& text(const std::string& t)
  {
    bytes += t;
    return *this;
  }
  Builder& i32(std::int32_t v)
  {
    std::uint32_t u;
    std::memcpy(&u, &v, 4);
    return put(u, 4);
  }
  Builder& u64(std::uint64_t v) { return put(v, 8); }
  Builder& f64(double v)
  {
    std::uint64_t u;
    std::memcpy(&u, &v, 8);
    return put(u, 8);
  }
  Builder& mark(const std::string& name)
  {
    at[name] = bytes.size();
    return *this;
  }

  std::string bytes;
  std::map<std::string, std::size_t> at;

private:
  Builder& put(std::uint64_t v, int size)
  {
    for(int k = 0; k < size; ++k) {
      const int shift = 8 * (big_ ? size - 1 - k : k);
      bytes.push_back(static_cast<char>((v >> shift) & 0xff));
    }
    return *this;
  }
  bool big_;
};

const double square[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};

// A unit square: 4 nodes, triangles (1 2 3) (1 3 4) in physical surface 7
// "fluid", the edge (1 2) in physical curve 5 "wall".
Builder square_v22(bool big_endian)
{
  Builder b(big_endian);
  b.text("$MeshFormat\n2.2 1 8\n").mark("one").i32(1).text("\n$EndMeshFormat\n");
  b.text("$PhysicalNames\n2\n1 5 \"wall\"\n2 7 \"fluid\"\n$EndPhysicalNames\n");
  b.text("$Nodes\n").mark("node count").text("4\n");
  for(int i = 0; i < 4; ++i) {
    b.mark("node " + std::to_string(i + 1)).i32(i + 1);
    b.f64(square[i][0]).f64(square[i][1]).f64(square[i][2]);
  }
  b.text("\n$EndNodes\n$Elements\n3\n");
  b.mark("triangle header").i32(2).i32(2).i32(2);
  b.mark("triangle 1").i32(1).i32(7).i32(1).i32(1).i32(2).i32(3);
  b.mark("triangle 2").i32(2).i32(7).i32(1).i32(1).i32(3).i32(4);
  b.mark("line header").i32(1).i32(1).i32(2);
  b.mark("line 1").i32(3).i32(5).i32(2).i32(1).i32(2);
  b.text("\n$EndElements\n");
  return b;
}

Builder square_v41(bool big_endian)
{
  Builder b(big_endian);
  b.text("$MeshFormat\n4.1 1 8\n").mark("one").i32(1).text("\n$EndMeshFormat\n");
  b.text("$PhysicalNames\n2\n1 5 \"wall\"\n2 7 \"fluid\"\n$EndPhysicalNames\n");
  // One curve (tag 1, physical 5), one surface (tag 1, physical 7).
  b.text("$Entities\n").u64(0).u64(1).u64(1).u64(0);
  b.i32(1).f64(0).f64(0).f64(0).f64(1).f64(0).f64(0).u64(1).i32(5).u64(0);
  b.i32(1).f64(0).f64(0).f64(0).f64(1).f64(1).f64(0).u64(1).i32(7).u64(0);
  b.text("\n$EndEntities\n");
  b.text("$Nodes\n").mark("node header").u64(1).u64(4).u64(1).u64(4);
  b.mark("node block").i32(2).i32(1).i32(0).mark("node block size").u64(4);
  for(int i = 0; i < 4; ++i)
    b.mark("node tag " + std::to_string(i + 1)).u64(static_cast<std::uint64_t>(i + 1));
  for(int i = 0; i < 4; ++i)
    b.mark("node " + std::to_string(i + 1)).f64(square[i][0]).f64(square[i][1]).f64(square[i][2]);
  b.text("\n$EndNodes\n$Elements\n").mark("element header").u64(2).u64(3).u64(1).u64(3);
  b.mark("triangle block").i32(2).i32(1).i32(2).mark("triangle block size").u64(2);
  b.mark("triangle 1").u64(1).u64(1).u64(2).u64(3);
  b.mark("triangle 2").u64(2).u64(1).u64(3).u64(4);
  b.mark("line block").i32(1).i32(1).i32(1).u64(1);
  b.mark("line 1").u64(3).u64(1).u64(2);
  b.text("\n$EndElements\n");
  return b;
}

Mesh_file read_bytes(const std::string& bytes, const std::string& name = "test.msh")
{
  std::istringstream in(bytes);
  return spring_motion::read_gmsh(in, name);
}

// The bytes as a file called test.msh must give an Input_error at byte
// `offset` whose message contains `fragment`.
void check_error(const std::string& bytes, std::size_t offset, const std::string& fragment)
{
  try {
    read_bytes(bytes);
    FAIL("no exception, expected one containing: " << fragment);
  } catch(const Input_error& e) {
    INFO("what(): " << e.what());
    CHECK(e.file() == "test.msh");
    CHECK(e.line() == 0);
    const std::string prefix = "test.msh: byte " + std::to_string(offset) + ": ";
    CHECK(std::string(e.what()).compare(0, prefix.size(), prefix) == 0);
    CHECK(e.message().find(fragment) != std::string::npos);
  }
}

void put_i32(std::string& bytes, std::size_t offset, std::int32_t v)
{
  for(int k = 0; k < 4; ++k)
    bytes[offset + static_cast<std::size_t>(k)] = static_cast<char>((static_cast<std::uint32_t>(v) >> (8 * k)) & 0xff);
}
void put_u64(std::string& bytes, std::size_t offset, std::uint64_t v)
{
  for(int k = 0; k < 8; ++k)
    bytes[offset + static_cast<std::size_t>(k)] = static_cast<char>((v >> (8 * k)) & 0xff);
}
void put_f64(std::string& bytes, std::size_t offset, double v)
{
  std::uint64_t u;
  std::memcpy(&u, &v, 8);
  put_u64(bytes, offset, u);
}

} // namespace

TEST_CASE("read_gmsh binary: the data files read as their ASCII sources", "[read_mesh][gmsh][binary]")
{
  const Mesh_file square = spring_motion::read_mesh(data_path("square_hole_v41.msh"));
  const Mesh_file box = spring_motion::read_mesh(data_path("box_3d_v41.msh"));
  REQUIRE(square.dimension == 2);
  REQUIRE(box.dimension == 3);
  for(const char* name : {"square_hole_v22_bin.msh", "square_hole_v41_bin.msh", "square_hole_v22_bin_be.msh"}) {
    INFO(name);
    const Mesh_file f = spring_motion::read_mesh(data_path(name));
    REQUIRE(f.dimension == 2);
    check_same_mesh(f.mesh_2, square.mesh_2);
    CHECK(f.vertex_ids == square.vertex_ids);
    // No lines in a binary file: byte offsets instead, increasing in file order.
    CHECK(f.element_lines == std::vector<std::size_t>(f.mesh_2.elements.size(), 0));
    REQUIRE(f.element_offsets.size() == f.mesh_2.elements.size());
    REQUIRE(f.boundary_facet_offsets.size() == f.mesh_2.boundary_facets.size());
    for(std::size_t i = 1; i < f.element_offsets.size(); ++i)
      CHECK(f.element_offsets[i] > f.element_offsets[i - 1]);
  }
  for(const char* name : {"box_3d_v22_bin.msh", "box_3d_v41_bin.msh", "box_3d_v41_bin_be.msh"}) {
    INFO(name);
    const Mesh_file f = spring_motion::read_mesh(data_path(name));
    REQUIRE(f.dimension == 3);
    check_same_mesh(f.mesh_3, box.mesh_3);
    CHECK(f.vertex_ids == box.vertex_ids);
  }
  // Text files have lines and no offsets.
  CHECK(square.element_offsets.empty());
  CHECK(square.element_lines.front() > 0);
}

TEST_CASE("read_gmsh binary: hand-built files in both byte orders", "[read_mesh][gmsh][binary]")
{
  for(bool big : {false, true})
    for(int version : {2, 4}) {
      INFO("big-endian " << big << ", version " << version);
      const Builder b = version == 2 ? square_v22(big) : square_v41(big);
      const Mesh_file f = read_bytes(b.bytes);
      REQUIRE(f.dimension == 2);
      const auto& m = f.mesh_2;
      CHECK(m.points == std::vector<std::array<double, 2>>{{0, 0}, {1, 0}, {1, 1}, {0, 1}});
      CHECK(m.elements == std::vector<std::array<std::uint32_t, 3>>{{0, 1, 2}, {0, 2, 3}});
      CHECK(m.element_labels == std::vector<int>{7, 7});
      CHECK(m.boundary_facets == std::vector<std::array<std::uint32_t, 2>>{{0, 1}});
      CHECK(m.boundary_labels == std::vector<int>{5});
      CHECK(m.label_names == std::map<int, std::string>{{5, "wall"}, {7, "fluid"}});
      CHECK(f.element_offsets == std::vector<std::size_t>{b.at.at("triangle 1"), b.at.at("triangle 2")});
      CHECK(f.boundary_facet_offsets == std::vector<std::size_t>{b.at.at("line 1")});
    }
}

TEST_CASE("read_gmsh binary: every truncation is an Input_error", "[read_mesh][gmsh][binary][errors]")
{
  for(const char* name : {"square_hole_v22_bin.msh", "box_3d_v41_bin.msh", "box_3d_v41_bin_be.msh"}) {
    const std::string bytes = file_bytes(data_path(name));
    REQUIRE(bytes.size() > 1000);
    std::size_t errors = 0;
    // The last bytes are "$EndElements\n": a file cut inside that keyword
    // still ends with a wrong keyword, an error too; only the final newline
    // may go.
    for(std::size_t size = 0; size + 1 < bytes.size(); ++size) {
      try {
        read_bytes(bytes.substr(0, size));
      } catch(const Input_error& e) {
        ++errors;
        if(e.file() != "test.msh")
          FAIL("wrong file in " << e.what());
        continue;
      }
      FAIL(name << " cut to " << size << " bytes read without error");
    }
    CHECK(errors == bytes.size() - 1);
  }
  const Builder b = square_v41(false);
  // The size is checked before the block is read: the error names its start.
  check_error(b.bytes.substr(0, b.at.at("node 3") + 5), b.at.at("node 1"),
              "4 node coordinates of 24 bytes each, but only 53 bytes remain in the file");
}

TEST_CASE("read_gmsh binary: hostile values give the byte offset", "[read_mesh][gmsh][binary][errors]")
{
  SECTION("bad byte-order marker")
  {
    Builder b = square_v22(false);
    put_i32(b.bytes, b.at.at("one"), 2);
    check_error(b.bytes, b.at.at("one"), "expected the integer 1 in binary");
  }
  SECTION("huge node count, 2.2")
  {
    Builder b = square_v22(false);
    std::string bytes = b.bytes;
    bytes.replace(b.at.at("node count"), 1, "4000000000");
    check_error(bytes, b.at.at("node count") + 11, "4000000000 nodes of 28 bytes each, but only");
  }
  SECTION("huge node block, 4.1")
  {
    Builder b = square_v41(false);
    put_u64(b.bytes, b.at.at("node header") + 8, 4000000000ULL);
    put_u64(b.bytes, b.at.at("node block size"), 4000000000ULL);
    check_error(b.bytes, b.at.at("node block size") + 8, "4000000000 node tags of 8 bytes each, but only");
  }
  SECTION("count beyond 32 bits, 4.1")
  {
    Builder b = square_v41(false);
    put_u64(b.bytes, b.at.at("node header") + 8, std::numeric_limits<std::uint64_t>::max());
    check_error(b.bytes, b.at.at("node header") + 8, "more than the supported 4294967295");
  }
  SECTION("element block larger than the header's count, 4.1")
  {
    Builder b = square_v41(false);
    put_u64(b.bytes, b.at.at("triangle block size"), 9);
    check_error(b.bytes, b.at.at("triangle block size"), "an entity block of 9 elements after 0");
  }
  SECTION("unknown element type")
  {
    Builder b = square_v22(false);
    put_i32(b.bytes, b.at.at("triangle header"), 99);
    check_error(b.bytes, b.at.at("triangle header"), "unknown element type 99");
    Builder c = square_v41(true);
    c.bytes[c.at.at("triangle block") + 8 + 3] = 99; // big-endian: the low byte is the last one
    check_error(c.bytes, c.at.at("triangle block") + 8, "unknown element type 99");
  }
  SECTION("quadrangles in a 2D mesh")
  {
    Builder b = square_v41(false);
    // The line block becomes one 4-node quadrangle of dimension 2: two more
    // node tags follow, nothing else changes size.
    std::string bytes = b.bytes;
    const std::size_t line = b.at.at("line block");
    put_i32(bytes, line, 2);
    put_i32(bytes, line + 8, 3);
    std::string quad_nodes(16, '\0');
    put_u64(quad_nodes, 0, 3);
    put_u64(quad_nodes, 8, 4);
    bytes.insert(b.at.at("line 1") + 24, quad_nodes);
    check_error(bytes, b.at.at("line 1"), "unsupported elements (quadrangle (Gmsh type 3), 1 in all)");
  }
  SECTION("element count of a 2.2 header beyond the section's count")
  {
    Builder b = square_v22(false);
    put_i32(b.bytes, b.at.at("triangle header") + 4, 4);
    check_error(b.bytes, b.at.at("triangle header") + 4, "an element header announces 4 elements after 0");
    put_i32(b.bytes, b.at.at("triangle header") + 4, -1);
    check_error(b.bytes, b.at.at("triangle header") + 4, "an element header announces -1 elements");
  }
  SECTION("negative and unknown node tags in elements")
  {
    Builder b = square_v22(false);
    put_i32(b.bytes, b.at.at("triangle 2") + 16, -5);
    check_error(b.bytes, b.at.at("triangle 2"), "node -5 is not in $Nodes");
    Builder c = square_v41(false);
    put_u64(c.bytes, c.at.at("triangle 2") + 24, 5);
    check_error(c.bytes, c.at.at("triangle 2"), "node 5 is not in $Nodes");
    put_u64(c.bytes, c.at.at("triangle 2") + 24, std::numeric_limits<std::uint64_t>::max());
    check_error(c.bytes, c.at.at("triangle 2"), "node 18446744073709551615 is not in $Nodes");
  }
  SECTION("negative, zero and repeated node tags")
  {
    Builder b = square_v22(false);
    put_i32(b.bytes, b.at.at("node 3"), 0);
    check_error(b.bytes, b.at.at("node 3"), "expected a positive node tag, found 0");
    Builder c = square_v41(false);
    put_u64(c.bytes, c.at.at("node tag 3"), 2);
    check_error(c.bytes, c.at.at("node 3"), "node tag 2 is used twice");
  }
  SECTION("NaN and infinite coordinates")
  {
    Builder b = square_v22(true);
    std::string bytes = b.bytes;
    for(int k = 0; k < 8; ++k) // a quiet NaN, big-endian
      bytes[b.at.at("node 2") + 12 + static_cast<std::size_t>(k)] = k == 0 ? '\x7f' : (k == 1 ? '\xf8' : '\0');
    check_error(bytes, b.at.at("node 2"), "node 2 has the coordinate nan: expected finite numbers");
    Builder c = square_v41(false);
    put_f64(c.bytes, c.at.at("node 4") + 16, std::numeric_limits<double>::infinity());
    check_error(c.bytes, c.at.at("node 4"), "node 4 has the coordinate inf");
  }
  SECTION("a vertex used twice by a triangle")
  {
    Builder b = square_v41(false);
    put_u64(b.bytes, b.at.at("triangle 1") + 16, 1);
    check_error(b.bytes, b.at.at("triangle 1"), "an element uses the same vertex twice");
  }
  SECTION("z off the plane in a triangle mesh")
  {
    Builder b = square_v22(false);
    put_f64(b.bytes, b.at.at("node 3") + 20, 0.5);
    check_error(b.bytes, b.at.at("node 3"), "surface meshes in 3D are not supported");
  }
  SECTION("a wrong count leaves binary where a keyword should be")
  {
    Builder b = square_v22(false);
    std::string bytes = b.bytes;
    bytes[b.at.at("node count")] = '3';
    check_error(bytes, b.at.at("node 4"), "expected $EndNodes");
  }
}

TEST_CASE("read_gmsh binary: format line checks", "[read_mesh][gmsh][binary][errors]")
{
  // Still text: these errors name the line.
  const auto line_error = [](const std::string& bytes, std::size_t line, const std::string& fragment) {
    try {
      read_bytes(bytes);
      FAIL("no exception, expected " << fragment);
    } catch(const Input_error& e) {
      INFO(e.what());
      CHECK(e.line() == line);
      CHECK(e.message().find(fragment) != std::string::npos);
    }
  };
  line_error("$MeshFormat\n4.1 1 4\n\x01\0\0\0\n$EndMeshFormat\n", 2, "data size 4: expected 8");
  line_error("$MeshFormat\n4.1 2 8\n", 2, "expected the file type 0 (ASCII) or 1 (binary), found 2");
  line_error("$MeshFormat\n2.2 1 8 x\n", 2, "expected the end of the format line");
}
