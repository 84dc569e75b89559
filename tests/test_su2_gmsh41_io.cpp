// Copyright (c) 2026 SpringMotion developers.
// Tests for the SU2 reader and writer and the Gmsh 4.1 writer
// (read_su2(), write_su2(), write_gmsh()): the SU2 files gmsh wrote from
// tests/data's Gmsh meshes read as those meshes; every writer's output reads
// back to the same mesh bit for bit, labels and names included, 2D and 3D;
// hostile SU2 files give an Input_error naming the file and line.
#include <spring_motion/io/read_mesh.h>
#include <spring_motion/io/write_mesh.h>

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using spring_motion::Indexed_mesh;
using spring_motion::Input_error;
using spring_motion::Mesh_file;

namespace {

std::string data_path(const std::string& name)
{
  return std::string(SPRING_MOTION_TEST_DATA_DIR) + "/" + name;
}

// Bitwise equality of the coordinates (== would take -0.0 for 0.0).
template <int D>
bool same_bits(const std::vector<std::array<double, D>>& a, const std::vector<std::array<double, D>>& b)
{
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
}

Mesh_file read_su2_text(const std::string& text, const std::string& name = "test.su2")
{
  std::istringstream in(text);
  return spring_motion::read_su2(in, name);
}

void check_su2_error(const std::string& text, std::size_t line, const std::string& fragment)
{
  try {
    read_su2_text(text);
    FAIL("no exception, expected one containing: " << fragment);
  } catch(const Input_error& e) {
    INFO("what(): " << e.what());
    CHECK(e.file() == "test.su2");
    CHECK(e.line() == line);
    CHECK(std::string(e.what()).rfind("test.su2:" + std::to_string(line) + ": ", 0) == 0);
    CHECK(e.message().find(fragment) != std::string::npos);
  }
}

// Doubles of every kind a mesh may hold: random bit patterns (finite ones),
// subnormals, -0.0, extremes; the writers must keep each one exactly.
double awkward_double(std::mt19937_64& random, std::size_t i)
{
  switch(i % 8) {
  case 0: return -0.0;
  case 1: return std::numeric_limits<double>::denorm_min() * static_cast<double>(random() % 1000 + 1);
  case 2: return std::numeric_limits<double>::max() / static_cast<double>(random() % 1000 + 1);
  case 3: return 0.1 * static_cast<double>(random() % 100);
  default:
    for(;;) {
      const std::uint64_t bits = random();
      double value;
      std::memcpy(&value, &bits, sizeof value);
      if(std::isfinite(value))
        return value;
    }
  }
}

template <int D>
Indexed_mesh<D> awkward_mesh(const Indexed_mesh<D>& shape, std::uint64_t seed)
{
  Indexed_mesh<D> mesh = shape;
  std::mt19937_64 random(seed);
  std::size_t i = 0;
  for(auto& p : mesh.points)
    for(double& x : p)
      x = awkward_double(random, i++);
  return mesh;
}

enum class Format { gmsh_ascii, gmsh_binary, su2 };
const Format formats[] = {Format::gmsh_ascii, Format::gmsh_binary, Format::su2};

template <int D>
void check_round_trip(const Indexed_mesh<D>& mesh, Format format)
{
  const bool su2 = format == Format::su2;
  std::ostringstream out;
  if(su2)
    spring_motion::write_su2(mesh, out);
  else
    spring_motion::write_gmsh(mesh, out, format == Format::gmsh_binary ? spring_motion::Gmsh_encoding::binary
                                                                       : spring_motion::Gmsh_encoding::ascii);
  if(format == Format::gmsh_binary)
    CHECK(out.str().compare(0, 20, "$MeshFormat\n4.1 1 8\n") == 0);
  std::istringstream in(out.str());
  const Mesh_file back = su2 ? spring_motion::read_su2(in, "round-trip") : spring_motion::read_gmsh(in, "round-trip");
  REQUIRE(back.dimension == D);
  const Indexed_mesh<D>& m = back.template mesh<D>();
  CHECK(same_bits<D>(m.points, mesh.points));
  CHECK(m.elements == mesh.elements);
  CHECK(m.boundary_facets.size() == mesh.boundary_facets.size());
  if(su2) {
    // SU2 groups the facets by marker; labels and names come back by number.
    std::multimap<int, std::array<std::uint32_t, D>> a, b;
    for(std::size_t f = 0; f < mesh.boundary_facets.size(); ++f)
      a.emplace(mesh.boundary_labels[f], mesh.boundary_facets[f]);
    for(std::size_t f = 0; f < m.boundary_facets.size(); ++f)
      b.emplace(m.boundary_labels[f], m.boundary_facets[f]);
    CHECK(a == b);
    CHECK(m.element_labels == std::vector<int>(mesh.elements.size(), 0)); // no place for them in SU2
    CHECK(m.label_names == mesh.label_names);
  } else {
    CHECK(m.element_labels == mesh.element_labels);
    CHECK(m.boundary_facets == mesh.boundary_facets);
    CHECK(m.boundary_labels == mesh.boundary_labels);
    CHECK(m.label_names == mesh.label_names);
  }
}

const std::string su2_square = "NDIME= 2\n"            // 1
                               "NELEM= 2\n"            // 2
                               "5 0 1 2 0\n"           // 3
                               "5 0 2 3 1\n"           // 4
                               "NPOIN= 4\n"            // 5
                               "0 0 0\n"               // 6
                               "1 0 1\n"               // 7
                               "1 1 2\n"               // 8
                               "0 1 3\n"               // 9
                               "NMARK= 1\n"            // 10
                               "MARKER_TAG= bottom\n"  // 11
                               "MARKER_ELEMS= 1\n"     // 12
                               "3 0 1\n";              // 13

} // namespace

TEST_CASE("read_su2: gmsh's SU2 files read as the Gmsh meshes", "[read_mesh][su2]")
{
  for(const auto& [su2, msh] : {std::pair<const char*, const char*>{"square_hole.su2", "square_hole_v41.msh"},
                                {"box_3d.su2", "box_3d_v41.msh"}}) {
    INFO(su2);
    const Mesh_file a = spring_motion::read_mesh(data_path(su2));
    const Mesh_file b = spring_motion::read_mesh(data_path(msh));
    REQUIRE(a.dimension == b.dimension);
    const auto check = [](const auto& x, const auto& y) {
      CHECK(x.points == y.points);
      CHECK(x.elements == y.elements);
      CHECK(x.element_labels == std::vector<int>(y.elements.size(), 0));
      CHECK(x.boundary_facets.size() == y.boundary_facets.size());
      // Markers by name: gmsh's marker tags are the physical names, and the
      // numbers given in file order happen to be Gmsh's own.
      std::multimap<int, std::array<std::uint32_t, std::tuple_size<typename std::decay_t<decltype(x.boundary_facets)>::value_type>::value>> p, q;
      for(std::size_t f = 0; f < x.boundary_facets.size(); ++f)
        p.emplace(x.boundary_labels[f], x.boundary_facets[f]);
      for(std::size_t f = 0; f < y.boundary_facets.size(); ++f)
        q.emplace(y.boundary_labels[f], y.boundary_facets[f]);
      CHECK(p == q);
      for(const auto& [label, name] : x.label_names)
        CHECK(y.label_names.at(label) == name);
    };
    if(a.dimension == 2)
      check(a.mesh_2, b.mesh_2);
    else
      check(a.mesh_3, b.mesh_3);
    CHECK(a.vertex_ids.front() == 0); // SU2 counts from 0
  }
}

TEST_CASE("read_su2: layout variants and marker labels", "[read_mesh][su2]")
{
  const Mesh_file f = read_su2_text(su2_square);
  REQUIRE(f.dimension == 2);
  CHECK(f.mesh_2.points == std::vector<std::array<double, 2>>{{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  CHECK(f.mesh_2.elements == std::vector<std::array<std::uint32_t, 3>>{{0, 1, 2}, {0, 2, 3}});
  CHECK(f.mesh_2.boundary_labels == std::vector<int>{1});
  CHECK(f.mesh_2.label_names == std::map<int, std::string>{{1, "bottom"}});
  CHECK(f.element_lines == std::vector<std::size_t>{3, 4});
  CHECK(f.boundary_facet_lines == std::vector<std::size_t>{13});

  // Comments, no index columns, "NPOIN= n m", values in the keyword token,
  // a numeric marker, a comment giving a tag its number, FFD data skipped.
  const Mesh_file g = read_su2_text("% a comment\n% label 7: top\nNDIME=2\nNELEM= 2 % two\n5 0 1 2\n5 0 2 3\n"
                                    "NPOIN= 4 4\n0 0\n1 0\n1 1\n0 1\nNMARK=3\nMARKER_TAG= 4\nMARKER_ELEMS= 1\n3 0 1\n"
                                    "MARKER_TAG= top\nMARKER_ELEMS= 1\n3 2 3\nMARKER_TAG=left\nMARKER_ELEMS= 1\n"
                                    "3 3 0\nFFD_NBOX= 1\nFFD_TAG= box\n1 2 3\n");
  REQUIRE(g.dimension == 2);
  CHECK(g.mesh_2.boundary_labels == std::vector<int>{4, 7, 1});
  CHECK(g.mesh_2.label_names == std::map<int, std::string>{{1, "left"}, {7, "top"}});
}

TEST_CASE("read_su2: hostile files name the line", "[read_mesh][su2][errors]")
{
  const auto replaced = [](std::string text, const std::string& from, const std::string& to) {
    const std::size_t at = text.find(from);
    REQUIRE(at != std::string::npos);
    return text.replace(at, from.size(), to);
  };
  check_su2_error(replaced(su2_square, "5 0 2 3 1", "9 0 2 3 1"), 4,
                  "quadrilateral (SU2 type 9) in NELEM: expected triangle (SU2 type 5)");
  check_su2_error(replaced(su2_square, "5 0 2 3 1", "10 0 2 3 1"), 4, "tetrahedron (SU2 type 10) in NELEM");
  check_su2_error(replaced(su2_square, "3 0 1", "5 0 1 2"), 13, "triangle (SU2 type 5) in a marker: expected line");
  check_su2_error(replaced(su2_square, "5 0 2 3 1", "5 0 -2 3 1"), 4, "vertex index -2 out of range");
  check_su2_error(replaced(su2_square, "5 0 2 3 1", "5 0 2 4 1"), 4, "vertex index 4 out of range: expected 0 to 4 - 1");
  check_su2_error(replaced(su2_square, "3 0 1", "3 0 9"), 13, "vertex index 9 out of range");
  check_su2_error(replaced(su2_square, "NPOIN= 4", "NPOIN= 4000000000"), 10,
                  "expected a point coordinate, found 'NMARK=' (section NPOIN: expected 4000000000 points, read 4)");
  check_su2_error(replaced(su2_square, "NELEM= 2", "NELEM= 99999999999"), 2, "more than the supported 4294967295");
  check_su2_error(replaced(su2_square, "1 1 2", "1 nan 2"), 8, "found 'nan': not a finite number");
  check_su2_error(replaced(su2_square, "1 1 2", "1 1e999 2"), 8, "not a finite number");
  check_su2_error(replaced(su2_square, "NDIME= 2", "NDIME= 4"), 1, "expected NDIME= 2 or 3");
  check_su2_error(replaced(su2_square, "NDIME= 2", "NZONE= 2"), 1, "multi-zone SU2 files are not supported");
  check_su2_error(replaced(su2_square, "NDIME= 2\n", ""), 1, "NELEM= before NDIME=");
  check_su2_error(replaced(su2_square, "MARKER_TAG= bottom", "MARKER_TAG="), 11, "expected a marker name");
  check_su2_error(replaced(su2_square, "NMARK= 1", "NMARK= 2"), 13, "unexpected end of file: expected MARKER_TAG=");
  check_su2_error(replaced(su2_square, "5 0 2 3 1", "5 0 2 2 1"), 4, "the same vertex twice");
  check_su2_error(replaced(su2_square, "0 1 3\n", "0 1 x\n"), 9, "expected the end of the line or an index");
  // Truncated at every byte: an Input_error each time, except where the
  // cut leaves a complete file (the last point with or without its index
  // and no markers: 68 to 71 bytes; the whole file without its newline).
  const std::size_t complete = su2_square.find("NMARK");
  REQUIRE(complete == 71);
  for(std::size_t size = 0; size + 1 < su2_square.size(); ++size) {
    INFO("cut to " << size << " bytes");
    if(size >= 68 && size <= 71)
      CHECK(read_su2_text(su2_square.substr(0, size)).mesh_2.boundary_facets.empty());
    else
      CHECK_THROWS_AS(read_su2_text(su2_square.substr(0, size)), Input_error);
  }
}

TEST_CASE("write_gmsh (ASCII, binary) and write_su2: the data files come back bit for bit", "[write_mesh][gmsh][su2]")
{
  for(const char* name : {"square_hole_v41.msh", "square_2d.mesh", "box_3d_v41.msh", "cube_3d.mesh"}) {
    INFO(name);
    const Mesh_file f = spring_motion::read_mesh(data_path(name));
    for(Format format : formats) {
      INFO("format " << static_cast<int>(format));
      if(f.dimension == 2)
        check_round_trip(f.mesh_2, format);
      else
        check_round_trip(f.mesh_3, format);
    }
  }
}

TEST_CASE("write_gmsh and write_su2: awkward doubles and labels round-trip exactly", "[write_mesh][gmsh][su2]")
{
  Mesh_file f2 = spring_motion::read_mesh(data_path("square_hole_v22.msh"));
  Mesh_file f3 = spring_motion::read_mesh(data_path("box_3d_v41.msh"));
  for(std::uint64_t seed = 1; seed <= 5; ++seed) {
    INFO("seed " << seed);
    Indexed_mesh<2> m2 = awkward_mesh(f2.mesh_2, seed);
    Indexed_mesh<3> m3 = awkward_mesh(f3.mesh_3, seed);
    // Interleaved labels (runs), label 0, a negative label, names with a
    // blank (not a usable SU2 tag) and a numeric name.
    for(std::size_t i = 0; i < m2.elements.size(); ++i)
      m2.element_labels[i] = static_cast<int>(i % 3) - 1;
    for(std::size_t i = 0; i < m2.boundary_labels.size(); ++i)
      m2.boundary_labels[i] = i % 4 == 0 ? 0 : m2.boundary_labels[i];
    m2.label_names = {{1, "outer wall"}, {2, "17"}, {-1, "minus"}};
    m3.label_names[3] = "walls and more";
    for(Format format : formats) {
      INFO("format " << static_cast<int>(format));
      check_round_trip(m2, format);
      check_round_trip(m3, format);
    }
  }
}

TEST_CASE("write_gmsh: gmsh itself reads the output", "[write_mesh][gmsh][.gmsh]")
{
  // Needs the gmsh program (Debian package gmsh); hidden from the default run.
  const Mesh_file f = spring_motion::read_mesh(data_path("box_3d_v41.msh"));
  const std::string path = (std::filesystem::temp_directory_path() / "spring_motion_write_gmsh.msh").string();
  spring_motion::write_gmsh(f.mesh_3, path);
  const std::string copy = path + ".v22.msh";
  REQUIRE(std::system(("gmsh " + path + " -save -format msh22 -o " + copy + " > /dev/null 2>&1").c_str()) == 0);
  const Mesh_file g = spring_motion::read_mesh(copy);
  CHECK(g.mesh_3.points == f.mesh_3.points);
  CHECK(g.mesh_3.elements.size() == f.mesh_3.elements.size());
  CHECK(g.mesh_3.label_names == f.mesh_3.label_names);
  // The binary output, through gmsh to ASCII 4.1.
  spring_motion::write_gmsh(f.mesh_3, path, spring_motion::Gmsh_encoding::binary);
  REQUIRE(std::system(("gmsh " + path + " -save -format msh41 -o " + copy + " > /dev/null 2>&1").c_str()) == 0);
  const Mesh_file h = spring_motion::read_mesh(copy);
  CHECK(h.mesh_3.points == f.mesh_3.points);
  CHECK(h.mesh_3.elements == f.mesh_3.elements);
  // gmsh orders the facets by entity, that is by label.
  std::multimap<int, std::array<std::uint32_t, 3>> a, b;
  for(std::size_t i = 0; i < f.mesh_3.boundary_facets.size(); ++i)
    a.emplace(f.mesh_3.boundary_labels[i], f.mesh_3.boundary_facets[i]);
  for(std::size_t i = 0; i < h.mesh_3.boundary_facets.size(); ++i)
    b.emplace(h.mesh_3.boundary_labels[i], h.mesh_3.boundary_facets[i]);
  CHECK(a == b);
  std::remove(path.c_str());
  std::remove(copy.c_str());
}
