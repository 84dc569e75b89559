// Copyright (c) 2026 SpringMotion developers.
// Private to src/io: what the ASCII and the binary Gmsh readers share (the
// element types of the MSH format, the renumbering of node tags). Not installed.
#ifndef SPRING_MOTION_SRC_IO_GMSH_COMMON_H
#define SPRING_MOTION_SRC_IO_GMSH_COMMON_H

#include <spring_motion/io/read_mesh.h>

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <iterator>
#include <string>
#include <unordered_map>

namespace spring_motion {
namespace io_internal {

// The fixed-size element types of the MSH format (Gmsh manual, "MSH file
// format"): knowing their node counts lets a reader step over elements it
// does not use. Types beyond this table are skipped to the end of the line in
// ASCII files, and are an error in binary ones (nothing tells their size).
struct Element_type
{
  int dimension;
  int nodes;
  const char* name;
};

inline const Element_type* find_element_type(std::int64_t type)
{
  static constexpr Element_type types[] = {
    {1, 2, "line"},                        // 1
    {2, 3, "triangle"},                    // 2
    {2, 4, "quadrangle"},                  // 3
    {3, 4, "tetrahedron"},                 // 4
    {3, 8, "hexahedron"},                  // 5
    {3, 6, "prism"},                       // 6
    {3, 5, "pyramid"},                     // 7
    {1, 3, "3-node line"},                 // 8
    {2, 6, "6-node triangle"},             // 9
    {2, 9, "9-node quadrangle"},           // 10
    {3, 10, "10-node tetrahedron"},        // 11
    {3, 27, "27-node hexahedron"},         // 12
    {3, 18, "18-node prism"},              // 13
    {3, 14, "14-node pyramid"},            // 14
    {0, 1, "point"},                       // 15
    {2, 8, "8-node quadrangle"},           // 16
    {3, 20, "20-node hexahedron"},         // 17
    {3, 15, "15-node prism"},              // 18
    {3, 13, "13-node pyramid"},            // 19
    {2, 9, "9-node triangle"},             // 20
    {2, 10, "10-node triangle"},           // 21
    {2, 12, "12-node triangle"},           // 22
    {2, 15, "15-node triangle"},           // 23
    {2, 15, "15-node incomplete triangle"},// 24
    {2, 21, "21-node triangle"},           // 25
    {1, 4, "4-node line"},                 // 26
    {1, 5, "5-node line"},                 // 27
    {1, 6, "6-node line"},                 // 28
    {3, 20, "20-node tetrahedron"},        // 29
    {3, 35, "35-node tetrahedron"},        // 30
    {3, 56, "56-node tetrahedron"},        // 31
  };
  if(type < 1 || type > static_cast<std::int64_t>(std::size(types)))
    return nullptr;
  return &types[type - 1];
}

inline constexpr std::int64_t line_type = 1, triangle_type = 2, tetrahedron_type = 4;

inline std::string describe_type(std::int64_t type)
{
  const Element_type* t = find_element_type(type);
  return std::string(t != nullptr ? t->name : "element") + " (Gmsh type " + std::to_string(type) + ")";
}

// Node tags are arbitrary positive numbers; most files number them 1..n in
// order, which needs no map at all.
class Node_numbering
{
public:
  std::size_t size() const { return size_; }

  // False if the tag was already used.
  bool add(std::int64_t tag)
  {
    if(contiguous_) {
      if(tag == static_cast<std::int64_t>(size_) + 1) {
        ++size_;
        return true;
      }
      if(tag >= 1 && tag <= static_cast<std::int64_t>(size_))
        return false;
      contiguous_ = false;
      map_.reserve(size_ + 1);
      for(std::size_t i = 0; i < size_; ++i)
        map_.emplace(static_cast<std::int64_t>(i) + 1, static_cast<std::uint32_t>(i));
    }
    if(!map_.emplace(tag, static_cast<std::uint32_t>(size_)).second)
      return false;
    ++size_;
    return true;
  }

  // The 0-based index of a tag, or false if the tag is not a node.
  bool find(std::int64_t tag, std::uint32_t& index) const
  {
    if(contiguous_) {
      if(tag < 1 || tag > static_cast<std::int64_t>(size_))
        return false;
      index = static_cast<std::uint32_t>(tag - 1);
      return true;
    }
    const auto it = map_.find(tag);
    if(it == map_.end())
      return false;
    index = it->second;
    return true;
  }

private:
  bool contiguous_ = true;
  std::size_t size_ = 0;
  std::unordered_map<std::int64_t, std::uint32_t> map_;
};

/// The rest of a binary Gmsh file (format 2.2 or 4.1, `version` 2 or 4),
/// from the byte after its format line, which is at `offset` in the file.
Mesh_file read_gmsh_binary(std::istream& in, const std::string& name, std::size_t offset, int version);

} // namespace io_internal
} // namespace spring_motion

#endif
