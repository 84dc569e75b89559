// Copyright (c) 2026 SpringMotion developers.
#include <spring_motion/io/write_mesh.h>

#include <spring_motion/Error.h>
#include <spring_motion/internal/solver/threads.h>

#include "Token_reader.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <ostream>
#include <random>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <system_error>

namespace spring_motion {

namespace {

namespace fs = std::filesystem;

// Formats numbers with std::to_chars: locale-independent, and for doubles
// the shortest text that parses back to the same value, which is what makes
// write_medit -> read_medit exact. Numbers are formatted straight into a
// fixed buffer written out in large chunks: appending each number's text to
// a std::string took two fifths of the instructions of writing a VTU file.
class Text_writer
{
public:
  explicit Text_writer(std::ostream& out) : out_(&out), buffer_(new char[capacity]) {}
  /// Appends to `text` instead (write_lines' blocks).
  explicit Text_writer(std::string& text) : text_(&text), buffer_(new char[capacity]) {}
  ~Text_writer() { flush(); }
  Text_writer(const Text_writer&) = delete;
  Text_writer& operator=(const Text_writer&) = delete;

  Text_writer& operator<<(double value)
  {
    // Whole numbers of at most four digits (labels, flags, the z of a 2D
    // mesh) go out as integers: the same text as the double's shortest form,
    // which is fixed notation up to there, at a tenth of the cost. -0 keeps
    // its sign through to_chars of the double.
    if(value > -10000 && value < 10000 && value == double(int(value)) && !(value == 0 && std::signbit(value)))
      return format(int(value));
    return format(value);
  }
  Text_writer& operator<<(std::int64_t value) { return format(value); }
  Text_writer& operator<<(std::uint32_t value) { return format(value); }
  Text_writer& operator<<(int value) { return format(value); }
  Text_writer& operator<<(std::size_t value) { return format(value); }
  Text_writer& operator<<(char c)
  {
    if(size_ == capacity)
      flush();
    buffer_[size_++] = c;
    return *this;
  }
  Text_writer& operator<<(const std::string& text) { return append(text.data(), text.size()); }
  /// Writes `text` after what the buffer holds, without copying it through
  /// the buffer (write_lines' blocks).
  void write_through(const std::string& text)
  {
    flush();
    if(out_)
      out_->write(text.data(), static_cast<std::streamsize>(text.size()));
    else
      text_->append(text);
  }
  Text_writer& operator<<(const char* text) { return append(text, std::strlen(text)); }

  void flush()
  {
    if(out_)
      out_->write(buffer_.get(), static_cast<std::streamsize>(size_));
    else
      text_->append(buffer_.get(), size_);
    size_ = 0;
  }

private:
  static constexpr std::size_t capacity = std::size_t(1) << 16;
  // more than any number's shortest text (a double's takes at most 24 characters)
  static constexpr std::size_t number_room = 64;

  template <class Number>
  Text_writer& format(Number value)
  {
    if(capacity - size_ < number_room)
      flush();
    char* const first = buffer_.get() + size_;
    size_ += std::size_t(std::to_chars(first, first + number_room, value).ptr - first);
    return *this;
  }
  Text_writer& append(const char* text, std::size_t length)
  {
    while(length > 0) {
      if(size_ == capacity)
        flush();
      const std::size_t n = std::min(length, capacity - size_);
      std::memcpy(buffer_.get() + size_, text, n);
      size_ += n;
      text += n;
      length -= n;
    }
    return *this;
  }

  std::ostream* out_ = nullptr;
  std::string* text_ = nullptr;
  std::unique_ptr<char[]> buffer_;
  std::size_t size_ = 0;
};

// Writes lines [0, count) in order, line(writer, i) formatting line i.
// Formatting is most of the cost of a large file (a double's shortest text
// takes a few hundred instructions: half of a wing's VTU file went to
// to_chars), so past the parallel threshold OpenMP's team formats blocks of
// lines, each into a string of its own, and an ordered loop writes the
// blocks in turn: the same bytes for any thread count.
template <class Line>
void write_lines(Text_writer& w, std::size_t count, const Line& line)
{
  constexpr std::size_t block = 4096;
  const long blocks = long((count + block - 1) / block);
  const int nt = internal::thread_count(0, count);
  if(nt == 1 || blocks < 2) {
    for(std::size_t i = 0; i < count; ++i)
      line(w, i);
    return;
  }
  // an exception must not leave the parallel region: each block keeps its
  // own, the first is thrown after it (the caller's file is then discarded)
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(blocks));
#pragma omp parallel num_threads(nt)
  {
    // each thread's string and writer serve all its blocks: the string
    // grows to a block's size once, not at every block
    std::string text;
    std::unique_ptr<Text_writer> out;
#pragma omp for ordered schedule(static, 1)
    for(long b = 0; b < blocks; ++b) {
      try {
        if(!out)
          out = std::make_unique<Text_writer>(text);
        text.clear();
        const std::size_t first = std::size_t(b) * block, last = std::min(count, first + block);
        for(std::size_t i = first; i < last; ++i)
          line(*out, i);
        out->flush();
      } catch(...) {
        errors[std::size_t(b)] = std::current_exception();
      }
#pragma omp ordered
      w.write_through(text);
    }
  }
  for(const std::exception_ptr& e : errors)
    if(e)
      std::rethrow_exception(e);
}

template <int D>
void check_mesh(const Indexed_mesh<D>& mesh)
{
  const std::size_t n = mesh.points.size();
  const auto check_indices = [n](const auto& simplices, const char* what) {
    for(std::size_t i = 0; i < simplices.size(); ++i)
      for(std::uint32_t v : simplices[i])
        if(v >= n)
          throw Error(std::string("write mesh: ") + what + " " + std::to_string(i)
                                      + " has vertex index " + std::to_string(v) + ", expected less than "
                                      + std::to_string(n));
  };
  check_indices(mesh.elements, "element");
  check_indices(mesh.boundary_facets, "boundary facet");
  if(!mesh.element_labels.empty() && mesh.element_labels.size() != mesh.elements.size())
    throw Error("write mesh: " + std::to_string(mesh.element_labels.size())
                                + " element labels for " + std::to_string(mesh.elements.size())
                                + " elements, expected one per element or none");
  if(!mesh.boundary_labels.empty() && mesh.boundary_labels.size() != mesh.boundary_facets.size())
    throw Error("write mesh: " + std::to_string(mesh.boundary_labels.size())
                                + " boundary labels for " + std::to_string(mesh.boundary_facets.size())
                                + " boundary facets, expected one per facet or none");
}

void check_data(const std::vector<Data_array>& arrays, std::size_t count, const char* kind)
{
  for(const Data_array& a : arrays) {
    if(a.name.empty())
      throw Error(std::string("write_vtu: a ") + kind + " data array has no name");
    if(a.components < 1 || a.components > 9)
      throw Error("write_vtu: " + std::string(kind) + " data '" + a.name + "' has "
                                  + std::to_string(a.components) + " components, expected 1 to 9");
    if(a.values.size() != count * static_cast<std::size_t>(a.components))
      throw Error("write_vtu: " + std::string(kind) + " data '" + a.name + "' has "
                                  + std::to_string(a.values.size()) + " values, expected "
                                  + std::to_string(count) + " x " + std::to_string(a.components));
  }
}

std::string xml_escape(const std::string& text)
{
  std::string escaped;
  for(char c : text) {
    switch(c) {
    case '&': escaped += "&amp;"; break;
    case '<': escaped += "&lt;"; break;
    case '>': escaped += "&gt;"; break;
    case '"': escaped += "&quot;"; break;
    case '\'': escaped += "&apos;"; break;
    case '\n': case '\r': case '\t': escaped += ' '; break;
    default: escaped += c; break;
    }
  }
  return escaped;
}

bool has_extension(const std::string& path, const char* extension)
{
  return io_internal::equal_ignoring_case(fs::path(path).extension().string(), extension);
}

std::string temporary_name(const fs::path& target)
{
  // Unique enough across threads and processes writing the same directory;
  // the leading dot keeps the file out of sight while it is being written.
  static std::atomic<std::uint64_t> counter{0};
  static const std::uint64_t seed = [] {
    std::random_device device;
    return (std::uint64_t(device()) << 32) ^ device()
           ^ static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
  }();
  const std::uint64_t id = seed + 0x9e3779b97f4a7c15ULL * ++counter;
  char hex[17];
  std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(id));
  return "." + target.filename().string() + ".tmp-" + hex;
}

// Writes to a temporary file beside `path`, then renames it over `path`:
// a failure at any point leaves the previous file (or none) untouched.
void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write)
{
  const fs::path target(path);
  if(target.filename().empty())
    throw Input_error(path, 0, "expected a file name, found a directory path");
  const fs::path temporary = target.parent_path() / temporary_name(target);

  std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
  if(!out) {
    const std::string reason = std::strerror(errno);
    const std::string directory = target.parent_path().empty() ? "." : target.parent_path().string();
    throw Input_error(path, 0, "cannot create a file in directory '" + directory + "': " + reason);
  }
  std::error_code ignored;
  try {
    write(out);
    out.flush();
    if(!out)
      throw Input_error(path, 0, std::string("write failed: ") + std::strerror(errno));
    out.close();
    if(out.fail())
      throw Input_error(path, 0, std::string("write failed on close: ") + std::strerror(errno));
  } catch(...) {
    out.close();
    fs::remove(temporary, ignored);
    throw;
  }
  std::error_code error;
  fs::rename(temporary, target, error);
  if(error) {
    fs::remove(temporary, ignored);
    throw Input_error(path, 0, "cannot replace the file: " + error.message());
  }
}

void write_vtu_data(Text_writer& w, const std::vector<Data_array>& arrays)
{
  for(const Data_array& a : arrays) {
    w << "        <DataArray type=\"Float64\" Name=\"" << xml_escape(a.name) << "\" NumberOfComponents=\""
      << a.components << "\" format=\"ascii\">\n";
    const std::size_t m = static_cast<std::size_t>(a.components);
    write_lines(w, a.values.size() / m, [&a, m](Text_writer& to, std::size_t i) {
      to << "         ";
      for(std::size_t c = 0; c < m; ++c)
        to << ' ' << a.values[i * m + c];
      to << '\n';
    });
    w << "        </DataArray>\n";
  }
}

} // namespace

template <int D>
void write_medit(const Indexed_mesh<D>& mesh, std::ostream& out)
{
  check_mesh(mesh);
  Text_writer w(out);
  w << "MeshVersionFormatted 2\n\nDimension " << D << "\n";
  for(const auto& [label, name] : mesh.label_names) {
    std::string line = name;
    for(char& c : line)
      if(c == '\n' || c == '\r')
        c = ' ';
    w << "# label " << label << ": " << line << '\n';
  }

  w << "\nVertices\n" << mesh.points.size() << '\n';
  write_lines(w, mesh.points.size(), [&mesh](Text_writer& to, std::size_t i) {
    for(int k = 0; k < D; ++k)
      to << mesh.points[i][static_cast<std::size_t>(k)] << ' ';
    to << "0\n";
  });

  const auto write_simplices = [&w](const char* keyword, const auto& simplices, const std::vector<int>& labels) {
    w << '\n' << keyword << '\n' << simplices.size() << '\n';
    write_lines(w, simplices.size(), [&simplices, &labels](Text_writer& to, std::size_t i) {
      for(std::uint32_t v : simplices[i])
        to << (v + std::int64_t(1)) << ' ';
      to << (labels.empty() ? 0 : labels[i]) << '\n';
    });
  };
  write_simplices(D == 2 ? "Triangles" : "Tetrahedra", mesh.elements, mesh.element_labels);
  if(!mesh.boundary_facets.empty())
    write_simplices(D == 2 ? "Edges" : "Triangles", mesh.boundary_facets, mesh.boundary_labels);
  w << "\nEnd\n";
}

template <int D>
void write_medit(const Indexed_mesh<D>& mesh, const std::string& path)
{
  check_mesh(mesh);
  write_atomically(path, [&mesh](std::ostream& out) { write_medit(mesh, out); });
}

template <int D>
void write_vtu(const Indexed_mesh<D>& mesh, std::ostream& out, const std::vector<Data_array>& point_data,
               const std::vector<Data_array>& cell_data)
{
  check_mesh(mesh);
  check_data(point_data, mesh.points.size(), "point");
  check_data(cell_data, mesh.elements.size(), "cell");
  constexpr int vtk_cell_type = D == 2 ? 5 : 10; // VTK_TRIANGLE, VTK_TETRA

  Text_writer w(out);
  w << "<?xml version=\"1.0\"?>\n"
       "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
       "  <UnstructuredGrid>\n"
       "    <Piece NumberOfPoints=\"" << mesh.points.size() << "\" NumberOfCells=\"" << mesh.elements.size()
    << "\">\n";
  if(!point_data.empty()) {
    w << "      <PointData>\n";
    write_vtu_data(w, point_data);
    w << "      </PointData>\n";
  }
  if(!cell_data.empty()) {
    w << "      <CellData>\n";
    write_vtu_data(w, cell_data);
    w << "      </CellData>\n";
  }
  w << "      <Points>\n"
       "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  // p[D - 1], not p[2]: the 2D instantiation must compile too.
  write_lines(w, mesh.points.size(), [&mesh](Text_writer& to, std::size_t i) {
    const auto& p = mesh.points[i];
    to << "          " << p[0] << ' ' << p[1] << ' ' << (D == 3 ? p[D - 1] : 0.0) << '\n';
  });
  w << "        </DataArray>\n"
       "      </Points>\n"
       "      <Cells>\n"
       "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  write_lines(w, mesh.elements.size(), [&mesh](Text_writer& to, std::size_t t) {
    to << "         ";
    for(std::uint32_t v : mesh.elements[t])
      to << ' ' << v;
    to << '\n';
  });
  w << "        </DataArray>\n"
       "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  for(std::size_t i = 0; i < mesh.elements.size(); ++i)
    w << "          " << (i + 1) * (D + 1) << '\n';
  w << "        </DataArray>\n"
       "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
  for(std::size_t i = 0; i < mesh.elements.size(); ++i)
    w << "          " << vtk_cell_type << '\n';
  w << "        </DataArray>\n"
       "      </Cells>\n"
       "    </Piece>\n"
       "  </UnstructuredGrid>\n"
       "</VTKFile>\n";
}

template <int D>
void write_vtu(const Indexed_mesh<D>& mesh, const std::string& path, const std::vector<Data_array>& point_data,
               const std::vector<Data_array>& cell_data)
{
  // Check before creating anything, so a bad call leaves no trace on disk.
  check_mesh(mesh);
  check_data(point_data, mesh.points.size(), "point");
  check_data(cell_data, mesh.elements.size(), "cell");
  write_atomically(path, [&](std::ostream& out) { write_vtu(mesh, out, point_data, cell_data); });
}

namespace {

std::string one_line(const std::string& text)
{
  std::string line = text;
  for(char& c : line)
    if(c == '\n' || c == '\r')
      c = ' ';
  return line;
}

// Runs of consecutive simplices with the same label: the blocks of a Gmsh
// 4.1 file, which keep the simplices in their order.
struct Run
{
  std::size_t first, end;
  int label;
};

template <class Simplices>
std::vector<Run> label_runs(const Simplices& simplices, const std::vector<int>& labels)
{
  std::vector<Run> runs;
  for(std::size_t i = 0; i < simplices.size(); ++i) {
    const int label = labels.empty() ? 0 : labels[i];
    if(runs.empty() || runs.back().label != label)
      runs.push_back({i, i, label});
    runs.back().end = i + 1;
  }
  return runs;
}

std::vector<int> distinct_labels(const std::vector<Run>& runs)
{
  std::set<int> labels;
  for(const Run& r : runs)
    labels.insert(r.label);
  return std::vector<int>(labels.begin(), labels.end());
}

// Whether a label name can stand as an SU2 marker tag as it is: one word,
// which must not read back as a number (a number is a label without a name).
bool usable_marker_tag(const std::string& name)
{
  if(name.empty())
    return false;
  for(char c : name)
    if(c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '%' || c == '=')
      return false;
  std::int64_t ignored = 0;
  return !io_internal::parse_integer(name, ignored);
}

} // namespace

namespace {

// The numbers of a Gmsh 4.1 file, as text (separated by blanks, one entry
// per line) or in binary (int: 4 bytes, size_t and double: 8 bytes, in the
// machine's byte order, as gmsh writes them).
class Gmsh_emitter
{
public:
  Gmsh_emitter(Text_writer& w, bool binary) : w_(w), binary_(binary) {}

  void text(const std::string& t)
  {
    w_ << t;
    fresh_line_ = true;
  }
  void int32(std::int64_t v) { number(v, 4); }
  void size(std::size_t v) { number(static_cast<std::int64_t>(v), 8); }
  void real(double v)
  {
    if(binary_) {
      raw(&v, 8);
      return;
    }
    separate();
    w_ << v;
  }
  void end_line()
  {
    if(!binary_)
      w_ << '\n';
    fresh_line_ = true;
  }
  // Binary data end with a newline before the closing keyword.
  void end_section(const std::string& keyword) { text(std::string(binary_ ? "\n" : "") + keyword + "\n"); }

private:
  void number(std::int64_t v, int bytes)
  {
    if(binary_) {
      if(bytes == 4) {
        const std::int32_t i = static_cast<std::int32_t>(v);
        raw(&i, 4);
      } else {
        const std::uint64_t u = static_cast<std::uint64_t>(v);
        raw(&u, 8);
      }
      return;
    }
    separate();
    w_ << v;
  }
  void separate()
  {
    if(!fresh_line_)
      w_ << ' ';
    fresh_line_ = false;
  }
  void raw(const void* p, std::size_t n) { w_ << std::string(static_cast<const char*>(p), n); }

  Text_writer& w_;
  bool binary_;
  bool fresh_line_ = true;
};

} // namespace

template <int D>
void write_gmsh(const Indexed_mesh<D>& mesh, std::ostream& out, Gmsh_encoding encoding)
{
  check_mesh(mesh);
  const bool binary = encoding == Gmsh_encoding::binary;
  const std::vector<Run> facet_runs = label_runs(mesh.boundary_facets, mesh.boundary_labels);
  const std::vector<Run> element_runs = label_runs(mesh.elements, mesh.element_labels);
  // One entity per label and dimension, tagged 1, 2, ... in label order,
  // in the physical group of that label (none for label 0).
  const std::vector<int> facet_labels = distinct_labels(facet_runs);
  const std::vector<int> element_labels = distinct_labels(element_runs);
  const auto entity_of = [](const std::vector<int>& labels, int label) {
    return static_cast<std::int64_t>(std::lower_bound(labels.begin(), labels.end(), label) - labels.begin()) + 1;
  };

  Text_writer w(out);
  Gmsh_emitter e(w, binary);
  e.text(binary ? "$MeshFormat\n4.1 1 8\n" : "$MeshFormat\n4.1 0 8\n");
  if(binary) {
    e.int32(1); // tells the reader the byte order
    e.text("\n");
  }
  e.text("$EndMeshFormat\n");
  // Names of the labels in use, for each dimension that uses them (text in
  // binary files too).
  std::vector<std::pair<int, int>> named; // (dimension, label)
  for(int label : facet_labels)
    if(mesh.label_names.count(label) != 0)
      named.push_back({D - 1, label});
  for(int label : element_labels)
    if(mesh.label_names.count(label) != 0)
      named.push_back({D, label});
  if(!named.empty()) {
    w << "$PhysicalNames\n" << named.size() << '\n';
    for(const auto& [dimension, label] : named)
      w << dimension << ' ' << label << " \"" << one_line(mesh.label_names.at(label)) << "\"\n";
    w << "$EndPhysicalNames\n";
  }

  // Bounding boxes of the entities, from the vertices of their simplices.
  const auto write_entities = [&](const auto& simplices, const std::vector<int>& simplex_labels,
                                  const std::vector<int>& labels) {
    for(std::size_t k = 0; k < labels.size(); ++k) {
      std::array<double, 3> low{0, 0, 0}, high{0, 0, 0};
      bool first = true;
      for(std::size_t i = 0; i < simplices.size(); ++i) {
        if((simplex_labels.empty() ? 0 : simplex_labels[i]) != labels[k])
          continue;
        for(std::uint32_t v : simplices[i])
          for(std::size_t c = 0; c < std::size_t(D); ++c) {
            const double x = mesh.points[v][c];
            low[c] = first ? x : std::min(low[c], x);
            high[c] = first ? x : std::max(high[c], x);
          }
        first = false;
      }
      e.int32(static_cast<std::int64_t>(k + 1));
      for(double x : low)
        e.real(x);
      for(double x : high)
        e.real(x);
      e.size(labels[k] != 0 ? 1 : 0);
      if(labels[k] != 0)
        e.int32(labels[k]);
      e.size(0); // no bounding entities
      e.end_line();
    }
  };
  e.text("$Entities\n");
  e.size(0);
  e.size(D == 2 ? facet_labels.size() : 0);
  e.size(D == 2 ? element_labels.size() : facet_labels.size());
  e.size(D == 3 ? element_labels.size() : 0);
  e.end_line();
  write_entities(mesh.boundary_facets, mesh.boundary_labels, facet_labels);
  write_entities(mesh.elements, mesh.element_labels, element_labels);
  e.end_section("$EndEntities");

  // All nodes in one block, on the first entity of the mesh's dimension
  // (gmsh needs an entity; any will do).
  const std::size_t n = mesh.points.size();
  e.text("$Nodes\n");
  e.size(n > 0 ? 1 : 0);
  e.size(n);
  e.size(n > 0 ? 1 : 0);
  e.size(n);
  e.end_line();
  if(n > 0) {
    e.int32(D);
    e.int32(1);
    e.int32(0);
    e.size(n);
    e.end_line();
    for(std::size_t i = 0; i < n; ++i) {
      e.size(i + 1);
      e.end_line();
    }
    for(const auto& p : mesh.points) {
      e.real(p[0]);
      e.real(p[1]);
      e.real(D == 3 ? p[D - 1] : 0.0);
      e.end_line();
    }
  }
  e.end_section("$EndNodes");

  const std::size_t count = mesh.boundary_facets.size() + mesh.elements.size();
  e.text("$Elements\n");
  e.size(facet_runs.size() + element_runs.size());
  e.size(count);
  e.size(count > 0 ? 1 : 0);
  e.size(count);
  e.end_line();
  std::size_t tag = 0;
  const auto write_blocks = [&](const auto& simplices, const std::vector<Run>& runs, const std::vector<int>& labels,
                                int dimension, int type) {
    for(const Run& r : runs) {
      e.int32(dimension);
      e.int32(entity_of(labels, r.label));
      e.int32(type);
      e.size(r.end - r.first);
      e.end_line();
      for(std::size_t i = r.first; i < r.end; ++i) {
        e.size(++tag);
        for(std::uint32_t v : simplices[i])
          e.size(std::size_t(v) + 1);
        e.end_line();
      }
    }
  };
  // Gmsh types: 1 line, 2 triangle, 4 tetrahedron.
  write_blocks(mesh.boundary_facets, facet_runs, facet_labels, D - 1, D == 2 ? 1 : 2);
  write_blocks(mesh.elements, element_runs, element_labels, D, D == 2 ? 2 : 4);
  e.end_section("$EndElements");
}

template <int D>
void write_gmsh(const Indexed_mesh<D>& mesh, const std::string& path, Gmsh_encoding encoding)
{
  check_mesh(mesh);
  write_atomically(path, [&mesh, encoding](std::ostream& out) { write_gmsh(mesh, out, encoding); });
}

template <int D>
void write_su2(const Indexed_mesh<D>& mesh, std::ostream& out)
{
  check_mesh(mesh);
  Text_writer w(out);
  w << "% SU2 mesh written by SpringMotion\n";
  for(const auto& [label, name] : mesh.label_names)
    w << "% label " << label << ": " << one_line(name) << '\n';
  w << "NDIME= " << D << "\nNELEM= " << mesh.elements.size() << '\n';
  std::size_t index = 0;
  for(const auto& e : mesh.elements) {
    w << (D == 2 ? 5 : 10); // VTK_TRIANGLE, VTK_TETRA
    for(std::uint32_t v : e)
      w << ' ' << v;
    w << ' ' << index++ << '\n';
  }
  w << "NPOIN= " << mesh.points.size() << '\n';
  index = 0;
  for(const auto& p : mesh.points) {
    for(std::size_t k = 0; k < std::size_t(D); ++k)
      w << p[k] << ' ';
    w << index++ << '\n';
  }
  // One marker per boundary label, in label order.
  std::map<int, std::vector<std::size_t>> markers;
  for(std::size_t f = 0; f < mesh.boundary_facets.size(); ++f)
    markers[mesh.boundary_labels.empty() ? 0 : mesh.boundary_labels[f]].push_back(f);
  w << "NMARK= " << markers.size() << '\n';
  for(const auto& [label, facets] : markers) {
    const auto name = mesh.label_names.find(label);
    if(name != mesh.label_names.end() && usable_marker_tag(name->second))
      w << "MARKER_TAG= " << name->second << '\n';
    else
      w << "MARKER_TAG= " << label << '\n';
    w << "MARKER_ELEMS= " << facets.size() << '\n';
    for(std::size_t f : facets) {
      w << (D == 2 ? 3 : 5); // VTK_LINE, VTK_TRIANGLE
      for(std::uint32_t v : mesh.boundary_facets[f])
        w << ' ' << v;
      w << '\n';
    }
  }
}

template <int D>
void write_su2(const Indexed_mesh<D>& mesh, const std::string& path)
{
  check_mesh(mesh);
  write_atomically(path, [&mesh](std::ostream& out) { write_su2(mesh, out); });
}

template <int D>
void write_mesh(const std::string& path, const Indexed_mesh<D>& mesh, const std::vector<Data_array>& point_data,
                const std::vector<Data_array>& cell_data)
{
  if(has_extension(path, ".vtu")) {
    write_vtu(mesh, path, point_data, cell_data);
    return;
  }
  if(has_extension(path, ".mesh")) {
    write_medit(mesh, path);
    return;
  }
  if(has_extension(path, ".msh")) {
    write_gmsh(mesh, path);
    return;
  }
  if(has_extension(path, ".su2")) {
    write_su2(mesh, path);
    return;
  }
  const std::string extension = fs::path(path).extension().string();
  throw Input_error(path, 0, (extension.empty() ? std::string("no file extension")
                                                : "unknown output extension '" + extension + "'")
                               + ": expected .vtu (VTK XML), .mesh (Medit ASCII), .msh (Gmsh 4.1 ASCII) or .su2 (SU2)");
}

void write_mesh(const std::string& path, const Mesh_file& file, const std::vector<Data_array>& point_data,
                const std::vector<Data_array>& cell_data)
{
  if(file.dimension == 2)
    write_mesh(path, file.mesh_2, point_data, cell_data);
  else if(file.dimension == 3)
    write_mesh(path, file.mesh_3, point_data, cell_data);
  else
    throw Error("write_mesh: Mesh_file::dimension is " + std::to_string(file.dimension)
                                + ", expected 2 or 3");
}

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write)
{
  write_atomically(path, write);
}

void write_pvd(const std::string& path, const std::vector<Pvd_entry>& entries)
{
  write_atomically(path, [&entries](std::ostream& out) {
    Text_writer w(out);
    w << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "  <Collection>\n";
    for(const Pvd_entry& e : entries)
      w << "    <DataSet timestep=\"" << e.time << "\" group=\"\" part=\"0\" file=\"" << xml_escape(e.file)
        << "\"/>\n";
    w << "  </Collection>\n"
         "</VTKFile>\n";
  });
}

Pvd_writer::Pvd_writer(std::string path) : path_(std::move(path)) {}

void Pvd_writer::add(double time, const std::string& vtu_path)
{
  const fs::path directory = fs::path(path_).parent_path();
  const fs::path file(vtu_path);
  fs::path stored = file;
  if(!directory.empty()) {
    fs::path relative = file.lexically_relative(directory);
    if(relative.empty()) {
      // One path absolute, the other relative: compare them both absolute.
      std::error_code error;
      const fs::path absolute_file = fs::absolute(file, error).lexically_normal();
      const fs::path absolute_directory = fs::absolute(directory, error).lexically_normal();
      if(!error)
        relative = absolute_file.lexically_relative(absolute_directory);
    }
    if(!relative.empty())
      stored = relative;
  }
  entries_.push_back({time, stored.generic_string()});
  write_pvd(path_, entries_);
}

template void write_medit<2>(const Indexed_mesh<2>&, std::ostream&);
template void write_medit<3>(const Indexed_mesh<3>&, std::ostream&);
template void write_medit<2>(const Indexed_mesh<2>&, const std::string&);
template void write_medit<3>(const Indexed_mesh<3>&, const std::string&);
template void write_gmsh<2>(const Indexed_mesh<2>&, std::ostream&, Gmsh_encoding);
template void write_gmsh<3>(const Indexed_mesh<3>&, std::ostream&, Gmsh_encoding);
template void write_gmsh<2>(const Indexed_mesh<2>&, const std::string&, Gmsh_encoding);
template void write_gmsh<3>(const Indexed_mesh<3>&, const std::string&, Gmsh_encoding);
template void write_su2<2>(const Indexed_mesh<2>&, std::ostream&);
template void write_su2<3>(const Indexed_mesh<3>&, std::ostream&);
template void write_su2<2>(const Indexed_mesh<2>&, const std::string&);
template void write_su2<3>(const Indexed_mesh<3>&, const std::string&);
template void write_vtu<2>(const Indexed_mesh<2>&, std::ostream&, const std::vector<Data_array>&,
                           const std::vector<Data_array>&);
template void write_vtu<3>(const Indexed_mesh<3>&, std::ostream&, const std::vector<Data_array>&,
                           const std::vector<Data_array>&);
template void write_vtu<2>(const Indexed_mesh<2>&, const std::string&, const std::vector<Data_array>&,
                           const std::vector<Data_array>&);
template void write_vtu<3>(const Indexed_mesh<3>&, const std::string&, const std::vector<Data_array>&,
                           const std::vector<Data_array>&);
template void write_mesh<2>(const std::string&, const Indexed_mesh<2>&, const std::vector<Data_array>&,
                            const std::vector<Data_array>&);
template void write_mesh<3>(const std::string&, const Indexed_mesh<3>&, const std::vector<Data_array>&,
                            const std::vector<Data_array>&);

} // namespace spring_motion
