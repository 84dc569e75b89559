// Copyright (c) 2026 SpringMotion developers.
#include "Displacement_file.h"

#include "Arguments.h"

#include <spring_motion/Error.h>
#include <spring_motion/Input_error.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unordered_map>

namespace spring_motion {
namespace cli {

template <int D>
Displacement_file<D> read_displacement_file(const std::string& path, const std::vector<std::int64_t>& vertex_ids)
{
  std::error_code error;
  if(std::filesystem::is_directory(path, error))
    throw Input_error(path, 0, "cannot read a directory: expected a displacement file");
  std::ifstream in(path);
  if(!in)
    throw Input_error(path, 0, std::string("cannot open file: ") + std::strerror(errno));
  std::unordered_map<std::int64_t, std::size_t> index_of;
  for(std::size_t i = 0; i < vertex_ids.size(); ++i)
    index_of.emplace(vertex_ids[i], i);
  const std::string expected = D == 2 ? "'ID DX DY'" : "'ID DX DY DZ'";
  Displacement_file<D> file;
  file.path = path;
  std::unordered_map<std::size_t, std::size_t> line_of; // vertex -> line
  std::string text;
  for(std::size_t line = 1; std::getline(in, text); ++line) {
    if(const auto hash = text.find('#'); hash != std::string::npos)
      text.erase(hash);
    std::istringstream words(text);
    std::vector<std::string> w;
    for(std::string word; words >> word;)
      w.push_back(word);
    if(w.empty())
      continue;
    if(w.size() != std::size_t(D + 1))
      throw Input_error(path, line, "found " + std::to_string(w.size()) + " values: expected " + expected +
                                      " (a vertex number and " + std::to_string(D) + " displacement components)");
    char* end = nullptr;
    errno = 0;
    const long long id = std::strtoll(w[0].c_str(), &end, 10);
    if(end != w[0].c_str() + w[0].size() || errno == ERANGE)
      throw Input_error(path, line, "'" + w[0] + "' is not a vertex number: expected " + expected);
    const auto it = index_of.find(id);
    if(it == index_of.end())
      throw Input_error(path, line, "vertex " + w[0] + " is not in the mesh: expected the number of a mesh vertex "
                                    "(Medit: 1-based index, Gmsh: node tag)");
    std::array<double, D> d;
    for(int c = 0; c < D; ++c)
      if(!parse_number(w[std::size_t(c) + 1], d[c]))
        throw Input_error(path, line, "'" + w[std::size_t(c) + 1] + "' is not a finite number: expected " + expected);
    if(const auto seen = line_of.find(it->second); seen != line_of.end())
      throw Input_error(path, line, "vertex " + w[0] + " is given twice (first on line " +
                                      std::to_string(seen->second) + "): expected one line per vertex");
    line_of.emplace(it->second, line);
    file.vertices.push_back(it->second);
    file.displacements.push_back(d);
    file.lines.push_back(line);
  }
  if(in.bad())
    throw Input_error(path, 0, std::string("read failed: ") + std::strerror(errno));
  if(file.vertices.empty())
    throw Input_error(path, 0, "no displacement given: expected one line " + expected + " per moving vertex");
  return file;
}

template <int D>
std::array<double, D> Displacement_motion<D>::operator()(const std::array<double, D>& p0, double t) const
{
  const auto it = by_point.find(p0);
  SPRING_MOTION_CHECK(it != by_point.end(), "no displacement for a moving vertex");
  std::array<double, D> q;
  for(int c = 0; c < D; ++c)
    q[c] = p0[c] + t * it->second[c];
  return q;
}

template struct Displacement_file<2>;
template struct Displacement_file<3>;
template struct Displacement_motion<2>;
template struct Displacement_motion<3>;
template Displacement_file<2> read_displacement_file<2>(const std::string&, const std::vector<std::int64_t>&);
template Displacement_file<3> read_displacement_file<3>(const std::string&, const std::vector<std::int64_t>&);

} // namespace cli
} // namespace spring_motion
