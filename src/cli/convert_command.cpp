// Copyright (c) 2026 SpringMotion developers.
// spring-motion convert: a mesh file in another format.
#include "Arguments.h"
#include "commands.h"
#include "output_files.h"

#include <spring_motion/Input_error.h>
#include <spring_motion/io/read_mesh.h>
#include <spring_motion/io/write_mesh.h>

#include <ostream>

namespace spring_motion {
namespace cli {

namespace {
template <int D>
std::vector<Data_array> label_array(const Indexed_mesh<D>& mesh)
{
  Data_array label{"label", 1, {}};
  for(std::size_t t = 0; t < mesh.elements.size(); ++t)
    label.values.push_back(t < mesh.element_labels.size() ? mesh.element_labels[t] : 0);
  return {label};
}
} // namespace

int convert_command(const std::vector<std::string>& arguments, std::ostream& out, std::ostream&)
{
  const Arguments a(arguments, {{"help", false}});
  if(a.has("help")) {
    out << convert_help();
    return exit_success;
  }
  if(a.operands().size() != 2)
    throw Usage_error("expected a mesh file and an output file (MESH OUT)");
  const std::string& in = a.operands()[0];
  const Output_file output = classify_output(a.operands()[1]);
  if(output.kind == Output_file::Kind::pvd)
    throw Input_error(output.path, 0, "a .pvd is a time series: expected .vtu, .mesh, .msh or .su2 for one mesh");
  check_outputs({in}, {output}, "");
  const Mesh_file file = read_mesh(in);
  if(file.dimension == 2)
    write_mesh(output.path, file.mesh_2, {}, label_array(file.mesh_2));
  else
    write_mesh(output.path, file.mesh_3, {}, label_array(file.mesh_3));
  out << "wrote " << output.path << "\n";
  return exit_success;
}

} // namespace cli
} // namespace spring_motion
