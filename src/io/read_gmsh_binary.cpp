// Copyright (c) 2026 SpringMotion developers.
// Binary Gmsh meshes (gmsh -bin, Mesh.Binary = 1), formats 2.2 and 4.1. The
// layout follows the Gmsh manual, "MSH file format": keywords, counts of the
// 2.2 sections and $PhysicalNames are text; the rest is binary (int: 4 bytes,
// size_t: 8 bytes, double: 8 bytes) in the byte order of the writing machine,
// which the integer 1 written after the format line tells.
#include "Byte_reader.h"
#include "Gmsh_common.h"
#include "Raw_mesh.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace spring_motion {
namespace io_internal {

namespace {

constexpr std::size_t max_count = std::numeric_limits<std::uint32_t>::max();

std::string format_double(double value)
{
  std::ostringstream out;
  out.precision(17);
  out << value;
  return out.str();
}

class Gmsh_binary_reader
{
public:
  Gmsh_binary_reader(std::istream& in, const std::string& name, std::size_t offset, int version)
    : reader_(in, name, offset), version_(version)
  {
    raw_.byte_offsets = true;
  }

  Mesh_file read();

private:
  void read_endianness();
  void expect_end(const std::string& section);
  void read_physical_names();
  void read_entities();
  void read_nodes_2();
  void read_nodes_4();
  void read_elements_2();
  void read_elements_4();

  std::size_t read_size(const char* what, std::size_t max);
  int to_label(std::int64_t physical, std::size_t at);
  void add_node(std::int64_t tag, const unsigned char* xyz, std::size_t at);
  std::uint32_t node_index(std::int64_t tag, std::size_t at);
  void add_element(std::int64_t type, const std::array<std::uint32_t, 4>& vertices, int label, std::size_t at);

  Byte_reader reader_;
  int version_;
  Raw_mesh raw_;
  Node_numbering nodes_;
  bool have_nodes_ = false;
  bool have_elements_ = false;
  std::map<std::pair<int, std::int64_t>, int> entity_labels_;
  std::vector<unsigned char> buffer_;
};

void Gmsh_binary_reader::read_endianness()
{
  const std::size_t at = reader_.offset();
  unsigned char bytes[4];
  // Read as raw bytes: the order is what is being found out.
  reader_.set_swap(false);
  const std::int32_t native = reader_.read_int32("the binary integer 1 after the format line");
  std::memcpy(bytes, &native, sizeof bytes);
  if(native == 1)
    return;
  reader_.set_swap(true);
  if(reader_.int32_at(bytes) == 1)
    return;
  reader_.fail_at(at, "expected the integer 1 in binary (little- or big-endian) after the format line, found "
                        "the bytes " + std::to_string(bytes[0]) + " " + std::to_string(bytes[1]) + " "
                        + std::to_string(bytes[2]) + " " + std::to_string(bytes[3]));
}

void Gmsh_binary_reader::expect_end(const std::string& section)
{
  const std::string end = "$End" + section.substr(1);
  std::size_t at = 0;
  const std::string word = reader_.expect_word(end.c_str(), at);
  if(word != end)
    reader_.fail_at(at, "expected " + end + ", found " + Token_reader::quote(word) + " (is a count in " + section
                          + " right?)");
}

std::size_t Gmsh_binary_reader::read_size(const char* what, std::size_t max)
{
  const std::size_t at = reader_.offset();
  const std::uint64_t value = reader_.read_uint64(what);
  if(value > max)
    reader_.fail_at(at, std::string("expected ") + what + ", found " + std::to_string(value) + ": more than the supported "
                          + std::to_string(max));
  return static_cast<std::size_t>(value);
}

int Gmsh_binary_reader::to_label(std::int64_t physical, std::size_t at)
{
  if(physical < std::numeric_limits<int>::min() || physical > std::numeric_limits<int>::max())
    reader_.fail_at(at, "expected a physical tag that fits in an int, found " + std::to_string(physical));
  return static_cast<int>(physical);
}

void Gmsh_binary_reader::read_physical_names()
{
  // Text even in binary files.
  const std::size_t count = reader_.expect_text_count("the number of physical names", max_count);
  for(std::size_t i = 0; i < count; ++i) {
    const std::size_t at = reader_.offset();
    const std::int64_t dimension = reader_.expect_text_integer("a physical dimension");
    if(dimension < 0 || dimension > 3)
      reader_.fail_at(at, "expected a physical dimension 0 to 3, found " + std::to_string(dimension));
    const int tag = to_label(reader_.expect_text_integer("a physical tag"), at);
    raw_.names[static_cast<std::size_t>(dimension)][tag] = reader_.expect_quoted("a physical name");
  }
  expect_end("$PhysicalNames");
}

void Gmsh_binary_reader::read_entities()
{
  std::array<std::size_t, 4> counts;
  for(std::size_t d = 0; d < 4; ++d)
    counts[d] = read_size("the number of entities", max_count);
  for(int d = 0; d < 4; ++d)
    for(std::size_t i = 0; i < counts[static_cast<std::size_t>(d)]; ++i) {
      const std::int64_t tag = reader_.read_int32("an entity tag");
      // A point has its coordinates, the others their bounding box.
      reader_.read_block(buffer_, d == 0 ? 3 : 6, 8, "entity coordinates");
      const std::size_t physical_count = read_size("the number of physical tags", max_count);
      reader_.read_block(buffer_, physical_count, 4, "physical tags");
      if(physical_count > 0)
        entity_labels_[{d, tag}] = reader_.int32_at(buffer_.data());
      if(d > 0) {
        const std::size_t bounding_count = read_size("the number of bounding entities", max_count);
        reader_.read_block(buffer_, bounding_count, 4, "bounding entity tags");
      }
    }
  expect_end("$Entities");
}

void Gmsh_binary_reader::add_node(std::int64_t tag, const unsigned char* xyz, std::size_t at)
{
  if(tag < 1)
    reader_.fail_at(at, "expected a positive node tag, found " + std::to_string(tag));
  double c[3];
  for(std::size_t k = 0; k < 3; ++k) {
    c[k] = reader_.double_at(xyz + 8 * k);
    if(!std::isfinite(c[k]))
      reader_.fail_at(at, "node " + std::to_string(tag) + " has the coordinate " + format_double(c[k])
                            + ": expected finite numbers");
  }
  if(!nodes_.add(tag))
    reader_.fail_at(at, "node tag " + std::to_string(tag) + " is used twice: expected distinct tags");
  raw_.add_point(c[0], c[1], c[2], at);
  raw_.point_ids.push_back(tag);
}

void Gmsh_binary_reader::read_nodes_2()
{
  const std::size_t count = reader_.expect_text_count("the number of nodes", max_count);
  reader_.end_line("the binary nodes");
  constexpr std::size_t entry = 4 + 3 * 8;
  const std::size_t start = reader_.offset();
  reader_.read_block(buffer_, count, entry, "nodes");
  raw_.points.reserve(count);
  for(std::size_t i = 0; i < count; ++i) {
    const unsigned char* p = buffer_.data() + i * entry;
    add_node(reader_.int32_at(p), p + 4, start + i * entry);
  }
  expect_end("$Nodes");
}

void Gmsh_binary_reader::read_nodes_4()
{
  const std::size_t block_count = read_size("the number of entity blocks", max_count);
  const std::size_t count = read_size("the number of nodes", max_count);
  read_size("the minimum node tag", std::numeric_limits<std::size_t>::max());
  read_size("the maximum node tag", std::numeric_limits<std::size_t>::max());
  std::size_t read = 0;
  std::vector<std::int64_t> tags;
  for(std::size_t b = 0; b < block_count; ++b) {
    const std::size_t block_at = reader_.offset();
    const std::int32_t entity_dimension = reader_.read_int32("an entity dimension");
    if(entity_dimension < 0 || entity_dimension > 3)
      reader_.fail_at(block_at, "expected an entity dimension 0 to 3, found " + std::to_string(entity_dimension));
    reader_.read_int32("an entity tag");
    const std::int32_t parametric = reader_.read_int32("the parametric flag (0 or 1)");
    if(parametric != 0 && parametric != 1)
      reader_.fail_at(block_at + 8, "expected the parametric flag 0 or 1, found " + std::to_string(parametric));
    const std::size_t size_at = reader_.offset();
    const std::size_t block_size = read_size("the number of nodes in the block", max_count);
    if(block_size > count - read)
      reader_.fail_at(size_at, "an entity block of " + std::to_string(block_size) + " nodes after "
                                 + std::to_string(read) + ": more than the " + std::to_string(count)
                                 + " nodes announced in the $Nodes header");
    reader_.read_block(buffer_, block_size, 8, "node tags");
    tags.resize(block_size);
    for(std::size_t i = 0; i < block_size; ++i) {
      const std::uint64_t tag = reader_.uint64_at(buffer_.data() + 8 * i);
      if(tag > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
        reader_.fail_at(reader_.offset() - 8 * (block_size - i), "node tag " + std::to_string(tag) + " too large");
      tags[i] = static_cast<std::int64_t>(tag);
    }
    const std::size_t entry = 8 * (3 + (parametric ? static_cast<std::size_t>(entity_dimension) : 0));
    const std::size_t start = reader_.offset();
    reader_.read_block(buffer_, block_size, entry, "node coordinates");
    for(std::size_t i = 0; i < block_size; ++i)
      add_node(tags[i], buffer_.data() + i * entry, start + i * entry);
    read += block_size;
  }
  if(read != count)
    reader_.fail("the $Nodes header announces " + std::to_string(count) + " nodes, its "
                 + std::to_string(block_count) + " entity blocks hold " + std::to_string(read));
  expect_end("$Nodes");
}

std::uint32_t Gmsh_binary_reader::node_index(std::int64_t tag, std::size_t at)
{
  std::uint32_t index = 0;
  if(!nodes_.find(tag, index))
    reader_.fail_at(at, "node " + std::to_string(tag) + " is not in $Nodes: expected a node tag of the file");
  return index;
}

void Gmsh_binary_reader::add_element(std::int64_t type, const std::array<std::uint32_t, 4>& vertices, int label,
                                     std::size_t at)
{
  const auto check_distinct = [&](std::size_t n) {
    for(std::size_t i = 0; i < n; ++i)
      for(std::size_t j = i + 1; j < n; ++j)
        if(vertices[i] == vertices[j])
          reader_.fail_at(at, "an element uses the same vertex twice: expected " + std::to_string(n)
                                + " distinct vertices");
  };
  switch(type) {
  case line_type:
    check_distinct(2);
    raw_.edges.push_back({vertices[0], vertices[1]});
    raw_.edge_labels.push_back(label);
    raw_.edge_lines.push_back(at);
    break;
  case triangle_type:
    check_distinct(3);
    raw_.triangles.push_back({vertices[0], vertices[1], vertices[2]});
    raw_.triangle_labels.push_back(label);
    raw_.triangle_lines.push_back(at);
    break;
  case tetrahedron_type:
    check_distinct(4);
    raw_.tetrahedra.push_back(vertices);
    raw_.tetrahedron_labels.push_back(label);
    raw_.tetrahedron_lines.push_back(at);
    break;
  default:
    break;
  }
}

void Gmsh_binary_reader::read_elements_2()
{
  const std::size_t count = reader_.expect_text_count("the number of elements", max_count);
  reader_.end_line("the binary elements");
  std::size_t read = 0;
  while(read < count) {
    // element-header-binary: type, number of elements that follow, number of tags
    const std::size_t header_at = reader_.offset();
    const std::int32_t type = reader_.read_int32("an element type");
    const std::int32_t following = reader_.read_int32("the number of elements of the header");
    const std::int32_t tag_count = reader_.read_int32("the number of element tags");
    const Element_type* t = find_element_type(type);
    if(t == nullptr)
      reader_.fail_at(header_at, "unknown element type " + std::to_string(type)
                                   + ": expected a Gmsh type 1 to 31 (the size of other types is not known)");
    if(following < 1 || static_cast<std::size_t>(following) > count - read)
      reader_.fail_at(header_at + 4, "an element header announces " + std::to_string(following) + " elements after "
                                       + std::to_string(read) + ": expected 1 to " + std::to_string(count - read)
                                       + " (the $Elements count is " + std::to_string(count) + ")");
    if(tag_count < 0 || tag_count > 1000)
      reader_.fail_at(header_at + 8, "expected 0 to 1000 element tags, found " + std::to_string(tag_count));
    const std::size_t ints = 1 + static_cast<std::size_t>(tag_count) + static_cast<std::size_t>(t->nodes);
    const std::size_t start = reader_.offset();
    reader_.read_block(buffer_, static_cast<std::size_t>(following), 4 * ints, "elements");
    if(t->dimension > 0 && type != line_type && type != triangle_type && type != tetrahedron_type)
      raw_.add_unsupported(t->dimension, describe_type(type), start, static_cast<std::size_t>(following));
    else if(t->dimension > 0)
      for(std::size_t i = 0; i < static_cast<std::size_t>(following); ++i) {
        const unsigned char* p = buffer_.data() + 4 * ints * i;
        const std::size_t at = start + 4 * ints * i;
        const int label = tag_count > 0 ? reader_.int32_at(p + 4) : 0;
        std::array<std::uint32_t, 4> vertices{};
        const unsigned char* nodes = p + 4 * (1 + static_cast<std::size_t>(tag_count));
        for(std::size_t k = 0; k < static_cast<std::size_t>(t->nodes); ++k)
          vertices[k] = node_index(reader_.int32_at(nodes + 4 * k), at);
        add_element(type, vertices, label, at);
      }
    read += static_cast<std::size_t>(following);
  }
  expect_end("$Elements");
  // An element in several physical groups is written once per group.
  remove_duplicate_simplices(raw_.tetrahedra, raw_.tetrahedron_labels, raw_.tetrahedron_lines);
  remove_duplicate_simplices(raw_.triangles, raw_.triangle_labels, raw_.triangle_lines);
  remove_duplicate_simplices(raw_.edges, raw_.edge_labels, raw_.edge_lines);
}

void Gmsh_binary_reader::read_elements_4()
{
  const std::size_t block_count = read_size("the number of entity blocks", max_count);
  const std::size_t count = read_size("the number of elements", max_count);
  read_size("the minimum element tag", std::numeric_limits<std::size_t>::max());
  read_size("the maximum element tag", std::numeric_limits<std::size_t>::max());
  std::size_t read = 0;
  for(std::size_t b = 0; b < block_count; ++b) {
    const std::size_t block_at = reader_.offset();
    const std::int32_t entity_dimension = reader_.read_int32("an entity dimension");
    if(entity_dimension < 0 || entity_dimension > 3)
      reader_.fail_at(block_at, "expected an entity dimension 0 to 3, found " + std::to_string(entity_dimension));
    const std::int32_t entity_tag = reader_.read_int32("an entity tag");
    const std::int32_t type = reader_.read_int32("an element type");
    const Element_type* t = find_element_type(type);
    if(t == nullptr)
      reader_.fail_at(block_at + 8, "unknown element type " + std::to_string(type)
                                      + ": expected a Gmsh type 1 to 31 (the size of other types is not known)");
    const std::size_t size_at = reader_.offset();
    const std::size_t block_size = read_size("the number of elements in the block", max_count);
    if(block_size > count - read)
      reader_.fail_at(size_at, "an entity block of " + std::to_string(block_size) + " elements after "
                                 + std::to_string(read) + ": more than the " + std::to_string(count)
                                 + " elements announced in the $Elements header");
    const auto it = entity_labels_.find({entity_dimension, entity_tag});
    const int label = it != entity_labels_.end() ? it->second : 0;
    const std::size_t entry = 8 * (1 + static_cast<std::size_t>(t->nodes));
    const std::size_t start = reader_.offset();
    reader_.read_block(buffer_, block_size, entry, "elements");
    if(t->dimension > 0 && type != line_type && type != triangle_type && type != tetrahedron_type)
      raw_.add_unsupported(t->dimension, describe_type(type), start, block_size);
    else if(t->dimension > 0)
      for(std::size_t i = 0; i < block_size; ++i) {
        const unsigned char* p = buffer_.data() + entry * i;
        const std::size_t at = start + entry * i;
        std::array<std::uint32_t, 4> vertices{};
        for(std::size_t k = 0; k < static_cast<std::size_t>(t->nodes); ++k) {
          const std::uint64_t tag = reader_.uint64_at(p + 8 * (k + 1));
          if(tag > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
            reader_.fail_at(at, "node " + std::to_string(tag) + " is not in $Nodes: expected a node tag of the file");
          vertices[k] = node_index(static_cast<std::int64_t>(tag), at);
        }
        add_element(type, vertices, label, at);
      }
    read += block_size;
  }
  if(read != count)
    reader_.fail("the $Elements header announces " + std::to_string(count) + " elements, its "
                 + std::to_string(block_count) + " entity blocks hold " + std::to_string(read));
  expect_end("$Elements");
}

Mesh_file Gmsh_binary_reader::read()
{
  read_endianness();
  expect_end("$MeshFormat");
  std::string section;
  std::size_t at = 0;
  while(reader_.next_word(section, at)) {
    if(section.size() < 2 || section.front() != '$')
      reader_.fail_at(at, "expected a section such as $Nodes or $Elements, found " + Token_reader::quote(section));
    if(section == "$MeshFormat")
      reader_.fail_at(at, "a second $MeshFormat section: expected one");
    else if(section == "$PhysicalNames")
      read_physical_names();
    else if(section == "$Entities" && version_ == 4) {
      reader_.end_line("the binary entities");
      read_entities();
    } else if(section == "$Nodes") {
      if(have_nodes_)
        reader_.fail_at(at, "a second $Nodes section: expected one");
      if(version_ == 2)
        read_nodes_2();
      else {
        reader_.end_line("the binary nodes");
        read_nodes_4();
      }
      have_nodes_ = true;
    } else if(section == "$Elements") {
      if(!have_nodes_)
        reader_.fail_at(at, "section $Elements before $Nodes: expected $Nodes first");
      if(have_elements_)
        reader_.fail_at(at, "a second $Elements section: expected one");
      if(version_ == 2)
        read_elements_2();
      else {
        reader_.end_line("the binary elements");
        read_elements_4();
      }
      have_elements_ = true;
    } else if(section.compare(0, 4, "$End") == 0)
      reader_.fail_at(at, "unexpected " + Token_reader::quote(section) + ": expected a section start");
    else if(!reader_.skip_past("$End" + section.substr(1)))
      reader_.fail_at(at, "unexpected end of file in section " + section + ": expected $End" + section.substr(1));
  }
  if(!have_nodes_)
    reader_.fail("no $Nodes section: expected a Gmsh mesh with $Nodes and $Elements");
  if(!have_elements_)
    reader_.fail("no $Elements section: expected a Gmsh mesh with $Nodes and $Elements");
  return finish_mesh(std::move(raw_), reader_);
}

} // namespace

Mesh_file read_gmsh_binary(std::istream& in, const std::string& name, std::size_t offset, int version)
{
  Gmsh_binary_reader reader(in, name, offset, version);
  return reader.read();
}

} // namespace io_internal
} // namespace spring_motion
