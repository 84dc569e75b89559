// Copyright (c) 2026 SpringMotion developers.
// Tests for include/spring_motion/io/write_mesh.h.
#include <spring_motion/io/write_mesh.h>

#include <catch2/catch.hpp>

#include <omp.h>

#include <boost/property_tree/ptree.hpp>
#include <boost/property_tree/xml_parser.hpp>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <string>

namespace fs = std::filesystem;
namespace pt = boost::property_tree;
using spring_motion::Data_array;
using spring_motion::Indexed_mesh;
using spring_motion::Input_error;
using spring_motion::Mesh_file;

namespace {

std::string data_path(const std::string& name)
{
  return std::string(SPRING_MOTION_TEST_DATA_DIR) + "/" + name;
}

class Temporary_directory
{
public:
  Temporary_directory()
  {
    static std::atomic<int> counter{0};
    const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
    path_ = fs::temp_directory_path()
            / ("spring_motion_test_write_" + std::to_string(stamp) + "_" + std::to_string(++counter));
    fs::create_directories(path_);
  }
  ~Temporary_directory()
  {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  const fs::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::size_t number_of_entries() const
  {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(path_), fs::directory_iterator()));
  }

private:
  fs::path path_;
};

std::string read_text(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Same bits, so that -0.0 differs from 0.0 and a lost last digit shows.
template <std::size_t N>
bool same_bits(const std::vector<std::array<double, N>>& a, const std::vector<std::array<double, N>>& b)
{
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0);
}

template <int D>
void check_same_mesh(const Indexed_mesh<D>& a, const Indexed_mesh<D>& b)
{
  CHECK(same_bits(a.points, b.points));
  CHECK(a.elements == b.elements);
  CHECK(a.element_labels == b.element_labels);
  CHECK(a.boundary_facets == b.boundary_facets);
  CHECK(a.boundary_labels == b.boundary_labels);
}

template <int D>
void check_medit_round_trip(const Indexed_mesh<D>& mesh)
{
  std::stringstream text;
  spring_motion::write_medit(mesh, text);
  const Mesh_file again = spring_motion::read_medit(text, "round trip");
  REQUIRE(again.dimension == D);
  check_same_mesh(mesh, again.template mesh<D>());
}

// Numbers in the text of an XML element.
std::size_t count_numbers(const std::string& text)
{
  std::istringstream in(text);
  std::size_t count = 0;
  std::string token;
  while(in >> token)
    ++count;
  return count;
}

std::vector<double> numbers_of(const std::string& text)
{
  std::istringstream in(text);
  std::vector<double> values;
  double value;
  while(in >> value)
    values.push_back(value);
  return values;
}

// A parsed .vtu: checks the layout every file must have and returns the Piece.
pt::ptree parse_vtu(const std::string& path)
{
  pt::ptree tree;
  REQUIRE_NOTHROW(pt::read_xml(path, tree));
  CHECK(tree.get<std::string>("VTKFile.<xmlattr>.type") == "UnstructuredGrid");
  return tree.get_child("VTKFile.UnstructuredGrid.Piece");
}

// The DataArrays under `node`, by Name.
std::map<std::string, pt::ptree> data_arrays(const pt::ptree& node)
{
  std::map<std::string, pt::ptree> arrays;
  for(const auto& [tag, child] : node)
    if(tag == "DataArray")
      arrays[child.get<std::string>("<xmlattr>.Name", "")] = child;
  return arrays;
}

} // namespace

TEST_CASE("write_medit: read_medit gives the same mesh back", "[write_mesh][medit]")
{
  for(const char* name : {"square_2d.mesh", "cube_3d.mesh", "square_hole_v22.msh", "box_3d_v41.msh"}) {
    INFO(name);
    const Mesh_file file = spring_motion::read_mesh(data_path(name));
    if(file.dimension == 2)
      check_medit_round_trip(file.mesh_2);
    else
      check_medit_round_trip(file.mesh_3);
  }
}

TEST_CASE("write_medit: every double comes back bit for bit", "[write_mesh][medit]")
{
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Indexed_mesh<3> mesh;
  const double specials[] = {0.1, 1.0 / 3.0, -0.0, 1e-300, 4.9406564584124654e-324, 2.2250738585072014e-308,
                             1.7976931348623157e308, -123456789.123456789, 0.2499999999994121};
  for(double x : specials)
    mesh.points.push_back({x, -x, x * 0.5});
  for(int i = 0; i < 200; ++i)
    mesh.points.push_back({uniform(random), uniform(random) * 1e-5, std::ldexp(uniform(random), i - 100)});
  for(std::uint32_t i = 0; i + 3 < mesh.points.size(); i += 4) {
    mesh.elements.push_back({i, i + 1, i + 2, i + 3});
    mesh.element_labels.push_back(static_cast<int>(i) - 100);
  }
  mesh.boundary_facets.push_back({0, 1, 2});
  mesh.boundary_labels.push_back(std::numeric_limits<int>::min());
  check_medit_round_trip(mesh);

  Indexed_mesh<2> flat;
  for(double x : specials)
    flat.points.push_back({x, 1.0 - x});
  flat.elements.push_back({0, 1, 2});
  // No labels at all: written as 0, so read back as 0.
  std::stringstream text;
  spring_motion::write_medit(flat, text);
  const Mesh_file again = spring_motion::read_medit(text, "flat");
  REQUIRE(again.dimension == 2);
  CHECK(same_bits(flat.points, again.mesh_2.points));
  CHECK(again.mesh_2.element_labels == std::vector<int>{0});
}

TEST_CASE("write_vtu, write_medit: a large mesh written by a team is the file one thread writes",
          "[write_mesh][threads]")
{
  // more points and cells than the library's parallel threshold (16384
  // lines), so that both writers format blocks of lines on the team
  constexpr std::uint32_t side = 131;
  Indexed_mesh<2> mesh;
  for(std::uint32_t j = 0; j < side; ++j)
    for(std::uint32_t i = 0; i < side; ++i)
      mesh.points.push_back({i / 7.0, j / 3.0 + 1e-9 * i});
  for(std::uint32_t j = 0; j + 1 < side; ++j)
    for(std::uint32_t i = 0; i + 1 < side; ++i) {
      const std::uint32_t a = j * side + i;
      mesh.elements.push_back({a, a + 1, a + side + 1});
      mesh.elements.push_back({a, a + side + 1, a + side});
      mesh.element_labels.push_back(int(j));
      mesh.element_labels.push_back(-int(i));
    }
  const std::size_t n = mesh.points.size(), m = mesh.elements.size();
  REQUIRE(m > 2 * 16384);
  Data_array displacement{"displacement", 3, std::vector<double>(3 * n)};
  for(std::size_t k = 0; k < 3 * n; ++k)
    displacement.values[k] = std::sqrt(double(k)) - 1e3;
  Data_array skewness{"skewness", 1, std::vector<double>(m)};
  for(std::size_t t = 0; t < m; ++t)
    skewness.values[t] = 1.0 / double(t + 3);

  const int team = omp_get_max_threads();
  const auto write = [&](int threads) {
    omp_set_num_threads(threads);
    std::ostringstream vtu, medit;
    spring_motion::write_vtu(mesh, vtu, {displacement}, {skewness});
    spring_motion::write_medit(mesh, medit);
    omp_set_num_threads(team);
    return std::make_pair(vtu.str(), medit.str());
  };
  const auto one = write(1), two = write(2);
  CHECK(one.first == two.first);
  CHECK(one.second == two.second);

  // and every line in its place
  std::istringstream medit(two.second);
  const Mesh_file again = spring_motion::read_medit(medit, "large");
  REQUIRE(again.dimension == 2);
  CHECK(same_bits(mesh.points, again.mesh_2.points));
  CHECK(again.mesh_2.elements == mesh.elements);
  CHECK(again.mesh_2.element_labels == mesh.element_labels);
  std::istringstream vtu(two.first);
  pt::ptree tree;
  pt::read_xml(vtu, tree);
  const pt::ptree& piece = tree.get_child("VTKFile.UnstructuredGrid.Piece");
  CHECK(numbers_of(data_arrays(piece.get_child("PointData")).at("displacement").data()) == displacement.values);
  CHECK(numbers_of(data_arrays(piece.get_child("CellData")).at("skewness").data()) == skewness.values);
  std::vector<double> points, connectivity;
  for(const auto& p : mesh.points)
    points.insert(points.end(), {p[0], p[1], 0.0});
  for(const auto& e : mesh.elements)
    connectivity.insert(connectivity.end(), e.begin(), e.end());
  CHECK(numbers_of(piece.get_child("Points.DataArray").data()) == points);
  CHECK(numbers_of(data_arrays(piece.get_child("Cells")).at("connectivity").data()) == connectivity);
}

TEST_CASE("write_medit: to a path, and label names as comments", "[write_mesh][medit]")
{
  Temporary_directory directory;
  Mesh_file file = spring_motion::read_mesh(data_path("square_hole_v41.msh"));
  const std::string path = directory.file("out.mesh");
  spring_motion::write_medit(file.mesh_2, path);
  CHECK(read_text(path).find("# label 2: hole\n") != std::string::npos);
  const Mesh_file again = spring_motion::read_mesh(path);
  REQUIRE(again.dimension == 2);
  check_same_mesh(file.mesh_2, again.mesh_2);
  // the comments give the names back
  CHECK(again.mesh_2.label_names == file.mesh_2.label_names);
  CHECK(again.mesh_2.label_names == std::map<int, std::string>{{1, "outer"}, {2, "hole"}, {10, "fluid"}});
  CHECK(directory.number_of_entries() == 1); // no temporary left
}

TEST_CASE("write_vtu: 2D with point and cell data", "[write_mesh][vtu]")
{
  Temporary_directory directory;
  const Mesh_file file = spring_motion::read_mesh(data_path("square_hole_v22.msh"));
  const Indexed_mesh<2>& mesh = file.mesh_2;
  const std::size_t n = mesh.points.size(), m = mesh.elements.size();

  Data_array displacement{"displacement", 3, std::vector<double>(3 * n, 0.0)};
  for(std::size_t i = 0; i < n; ++i)
    displacement.values[3 * i] = 0.5 * static_cast<double>(i);
  Data_array skewness{"skewness", 1, std::vector<double>(m, 0.25)};
  Data_array valid{"valid", 1, std::vector<double>(m, 1.0)};
  Data_array quoted{"a <\"name\"> & more", 1, std::vector<double>(m, -1.0)};

  const std::string path = directory.file("step.vtu");
  spring_motion::write_vtu(mesh, path, {displacement}, {skewness, valid, quoted});

  const pt::ptree piece = parse_vtu(path);
  CHECK(piece.get<std::size_t>("<xmlattr>.NumberOfPoints") == n);
  CHECK(piece.get<std::size_t>("<xmlattr>.NumberOfCells") == m);

  const auto point_arrays = data_arrays(piece.get_child("PointData"));
  REQUIRE(point_arrays.size() == 1);
  const pt::ptree& d = point_arrays.at("displacement");
  CHECK(d.get<int>("<xmlattr>.NumberOfComponents") == 3);
  const std::vector<double> values = numbers_of(d.data());
  REQUIRE(values.size() == 3 * n);
  CHECK(values[3 * 7] == 3.5);

  const auto cell_arrays = data_arrays(piece.get_child("CellData"));
  REQUIRE(cell_arrays.size() == 3);
  CHECK(count_numbers(cell_arrays.at("skewness").data()) == m);
  CHECK(count_numbers(cell_arrays.at("valid").data()) == m);
  CHECK(cell_arrays.count("a <\"name\"> & more") == 1);

  const pt::ptree& points = piece.get_child("Points.DataArray");
  CHECK(points.get<int>("<xmlattr>.NumberOfComponents") == 3);
  const std::vector<double> coordinates = numbers_of(points.data());
  REQUIRE(coordinates.size() == 3 * n);
  CHECK(coordinates[3 * 8] == mesh.points[8][0]);
  CHECK(coordinates[3 * 8 + 2] == 0.0);

  const auto cells = data_arrays(piece.get_child("Cells"));
  const std::vector<double> connectivity = numbers_of(cells.at("connectivity").data());
  REQUIRE(connectivity.size() == 3 * m);
  CHECK(connectivity[3] == mesh.elements[1][0]);
  const std::vector<double> offsets = numbers_of(cells.at("offsets").data());
  REQUIRE(offsets.size() == m);
  CHECK(offsets.back() == 3.0 * static_cast<double>(m));
  const std::vector<double> types = numbers_of(cells.at("types").data());
  REQUIRE(types.size() == m);
  CHECK(std::all_of(types.begin(), types.end(), [](double t) { return t == 5; }));
}

TEST_CASE("write_vtu: each value is the shortest text of its double", "[write_mesh][vtu]")
{
  // whole numbers around the writer's integer shortcut, where fixed and
  // scientific notation change places ("10000" and "1e+04" are as short),
  // signed zeros and a few values that are not whole
  std::vector<double> values;
  for(int i = -12000; i <= 12000; ++i)
    values.push_back(i);
  for(double x : {-0.0, 0.0, 0.5, -9999.5, 9999.000000000002, 1e5, -1e5, 123456.0, 1e15, 1e22, 4.9406564584124654e-324,
                  std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()})
    values.push_back(x);
  Indexed_mesh<2> mesh;
  mesh.points = {{0, 0}, {1, 0}, {0, 1}};
  mesh.elements.assign(values.size(), {0, 1, 2});
  std::ostringstream out;
  spring_motion::write_vtu(mesh, out, {}, {Data_array{"value", 1, values}});
  const std::string text = out.str();
  const std::size_t first = text.find('>', text.find("Name=\"value\"")) + 1;
  std::istringstream tokens(text.substr(first, text.find("</DataArray>", first) - first));
  std::size_t i = 0;
  for(std::string token; tokens >> token; ++i) {
    REQUIRE(i < values.size());
    char expected[64];
    const auto end = std::to_chars(expected, expected + sizeof expected, values[i]).ptr;
    INFO("value " << i);
    CHECK(token == std::string(expected, end));
  }
  CHECK(i == values.size());
}

TEST_CASE("write_vtu: 3D tetrahedra", "[write_mesh][vtu]")
{
  Temporary_directory directory;
  const Mesh_file file = spring_motion::read_mesh(data_path("box_3d_v41.msh"));
  const std::string path = directory.file("box.vtu");
  spring_motion::write_mesh(path, file); // by extension, from the Mesh_file
  const pt::ptree piece = parse_vtu(path);
  CHECK(piece.get<std::size_t>("<xmlattr>.NumberOfPoints") == 45);
  CHECK(piece.get<std::size_t>("<xmlattr>.NumberOfCells") == 100);
  CHECK(piece.count("PointData") == 0);
  const std::vector<double> coordinates = numbers_of(piece.get_child("Points.DataArray").data());
  REQUIRE(coordinates.size() == 3 * 45);
  CHECK(coordinates[3 * 7 + 2] == file.mesh_3.points[7][2]);
  const auto cells = data_arrays(piece.get_child("Cells"));
  CHECK(count_numbers(cells.at("connectivity").data()) == 400);
  const std::vector<double> types = numbers_of(cells.at("types").data());
  CHECK(std::all_of(types.begin(), types.end(), [](double t) { return t == 10; }));
}

TEST_CASE("write_mesh: format by extension", "[write_mesh]")
{
  Temporary_directory directory;
  const Mesh_file file = spring_motion::read_mesh(data_path("cube_3d.mesh"));
  spring_motion::write_mesh(directory.file("a.MESH"), file.mesh_3);
  CHECK(spring_motion::read_mesh(directory.file("a.MESH")).mesh_3.elements == file.mesh_3.elements);
  spring_motion::write_mesh(directory.file("a.vtu"), file.mesh_3);
  CHECK(read_text(directory.file("a.vtu")).find("<VTKFile") != std::string::npos);
  spring_motion::write_mesh(directory.file("a.Msh"), file.mesh_3);
  CHECK(read_text(directory.file("a.Msh")).rfind("$MeshFormat\n4.1 0 8\n", 0) == 0);
  CHECK(spring_motion::read_mesh(directory.file("a.Msh")).mesh_3.elements == file.mesh_3.elements);
  spring_motion::write_mesh(directory.file("a.su2"), file.mesh_3);
  CHECK(spring_motion::read_mesh(directory.file("a.su2")).mesh_3.elements == file.mesh_3.elements);

  const std::string wrong = directory.file("a.stl");
  try {
    spring_motion::write_mesh(wrong, file.mesh_3);
    FAIL("no exception");
  } catch(const Input_error& e) {
    CHECK(e.file() == wrong);
    CHECK(e.message()
          == "unknown output extension '.stl': expected .vtu (VTK XML), .mesh (Medit ASCII), .msh (Gmsh 4.1 "
             "ASCII) or .su2 (SU2)");
  }
  CHECK(directory.number_of_entries() == 4);
}

TEST_CASE("Pvd_writer: lists the steps, relative to the collection", "[write_mesh][pvd]")
{
  Temporary_directory directory;
  const Mesh_file file = spring_motion::read_mesh(data_path("square_2d.mesh"));
  spring_motion::Pvd_writer collection(directory.file("run.pvd"));
  for(int step = 0; step < 3; ++step) {
    const std::string vtu = directory.file("run_" + std::to_string(step) + ".vtu");
    spring_motion::write_vtu(file.mesh_2, vtu);
    collection.add(0.5 * step, vtu);
  }
  pt::ptree tree;
  REQUIRE_NOTHROW(pt::read_xml(collection.path(), tree));
  CHECK(tree.get<std::string>("VTKFile.<xmlattr>.type") == "Collection");
  std::vector<std::pair<double, std::string>> steps;
  for(const auto& [tag, child] : tree.get_child("VTKFile.Collection"))
    if(tag == "DataSet")
      steps.emplace_back(child.get<double>("<xmlattr>.timestep"), child.get<std::string>("<xmlattr>.file"));
  REQUIRE(steps.size() == 3);
  CHECK(steps[0] == std::make_pair(0.0, std::string("run_0.vtu")));
  CHECK(steps[2] == std::make_pair(1.0, std::string("run_2.vtu")));
  for(const auto& step : steps)
    CHECK(fs::exists(directory.path() / step.second));

  // Entries given by hand are written as they are.
  spring_motion::write_pvd(directory.file("hand.pvd"), {{0.125, "sub dir/a&b.vtu"}});
  pt::read_xml(directory.file("hand.pvd"), tree);
  CHECK(tree.get<std::string>("VTKFile.Collection.DataSet.<xmlattr>.file") == "sub dir/a&b.vtu");
  CHECK(tree.get<double>("VTKFile.Collection.DataSet.<xmlattr>.timestep") == 0.125);
}

TEST_CASE("write_mesh: a failed write leaves no file", "[write_mesh][errors]")
{
  Temporary_directory directory;
  const Mesh_file file = spring_motion::read_mesh(data_path("square_2d.mesh"));

  // Missing directory: an Input_error naming the path, nothing created.
  const std::string missing = directory.file("no/such/dir/out.vtu");
  try {
    spring_motion::write_vtu(file.mesh_2, missing);
    FAIL("no exception");
  } catch(const Input_error& e) {
    CHECK(e.file() == missing);
    CHECK(e.message().find("cannot create a file in directory") != std::string::npos);
    CHECK(e.message().find("No such file or directory") != std::string::npos);
  }
  CHECK_THROWS_AS(spring_motion::write_medit(file.mesh_2, missing), Input_error);
  CHECK_THROWS_AS(spring_motion::write_pvd(directory.file("no/run.pvd"), {}), Input_error);
  CHECK(directory.number_of_entries() == 0);

  // The target is a directory: the rename fails after the data was written;
  // the temporary file must go and the directory stay.
  fs::create_directory(directory.file("taken.vtu"));
  fs::create_directory(directory.file("taken.vtu/inside"));
  CHECK_THROWS_AS(spring_motion::write_vtu(file.mesh_2, directory.file("taken.vtu")), Input_error);
  CHECK(fs::is_directory(directory.file("taken.vtu/inside")));
  CHECK(directory.number_of_entries() == 1);

  // Bad data is refused before anything is created; an old file survives.
  const std::string old_file = directory.file("old.vtu");
  std::ofstream(old_file) << "old";
  const Data_array wrong_size{"skewness", 1, std::vector<double>(3, 0.0)};
  CHECK_THROWS_AS(spring_motion::write_vtu(file.mesh_2, old_file, {}, {wrong_size}), spring_motion::Error);
  CHECK(read_text(old_file) == "old");
  CHECK(directory.number_of_entries() == 2);

  // A successful write replaces the old file.
  spring_motion::write_vtu(file.mesh_2, old_file);
  CHECK(read_text(old_file).find("<VTKFile") != std::string::npos);
  CHECK(directory.number_of_entries() == 2);
}

TEST_CASE("write_vtu: inconsistent meshes and data are refused", "[write_mesh][errors]")
{
  Indexed_mesh<2> mesh;
  mesh.points = {{0, 0}, {1, 0}, {0, 1}};
  mesh.elements = {{0, 1, 2}};
  std::ostringstream out;
  CHECK_NOTHROW(spring_motion::write_vtu(mesh, out));
  CHECK_THROWS_AS(spring_motion::write_vtu(mesh, out, {{"", 1, {0, 0, 0}}}), spring_motion::Error);
  CHECK_THROWS_AS(spring_motion::write_vtu(mesh, out, {{"d", 0, {}}}), spring_motion::Error);
  CHECK_THROWS_AS(spring_motion::write_vtu(mesh, out, {{"d", 2, {0, 0, 0}}}), spring_motion::Error);
  mesh.element_labels = {1, 2};
  CHECK_THROWS_AS(spring_motion::write_medit(mesh, out), spring_motion::Error);
  mesh.element_labels.clear();
  mesh.elements.push_back({0, 1, 3});
  CHECK_THROWS_AS(spring_motion::write_medit(mesh, out), spring_motion::Error);
}
