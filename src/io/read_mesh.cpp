// Copyright (c) 2026 SpringMotion developers.
#include <spring_motion/io/read_mesh.h>

#include "Token_reader.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

namespace spring_motion {

Mesh_file read_mesh(const std::string& path)
{
  const std::string extension = std::filesystem::path(path).extension().string();
  const bool is_medit = io_internal::equal_ignoring_case(extension, ".mesh");
  const bool is_gmsh = io_internal::equal_ignoring_case(extension, ".msh");
  const bool is_su2 = io_internal::equal_ignoring_case(extension, ".su2");
  if(!is_medit && !is_gmsh && !is_su2)
    throw Input_error(path, 0, (extension.empty() ? std::string("no file extension")
                                                  : "unknown mesh file extension '" + extension + "'")
                                 + ": expected .mesh (Medit ASCII) or .msh (Gmsh 2.2 or 4.1, ASCII or binary) or .su2 (SU2 native)");

  std::error_code error;
  // A directory opens as a stream on Linux and then reads as empty.
  if(std::filesystem::is_directory(path, error))
    throw Input_error(path, 0, "cannot read a directory: expected a mesh file");
  std::ifstream in(path, std::ios::binary);
  if(!in)
    throw Input_error(path, 0, std::string("cannot open file: ") + std::strerror(errno));
  if(is_su2)
    return read_su2(in, path);
  return is_medit ? read_medit(in, path) : read_gmsh(in, path);
}

} // namespace spring_motion
