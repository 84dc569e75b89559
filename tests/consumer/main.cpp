// Moves the centre vertex of a fan of four triangles through the installed
// package and checks where it lands: the exit code says whether it worked.
#include <spring_motion/spring_motion.h>

#include <cmath>
#include <iostream>

int main()
{
  spring_motion::Indexed_mesh<2> mesh;
  mesh.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}, {0.5, 0.0}};
  mesh.elements = {{0, 5, 4}, {5, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  // vertex 5 on the bottom edge moves up by 0.1; the centre is free
  auto roles = [](const spring_motion::Vertex_info<2>& v) {
    if(v.index == 5) return spring_motion::Vertex_role::moving;
    return v.on_boundary ? spring_motion::Vertex_role::fixed : spring_motion::Vertex_role::free;
  };
  const auto report = spring_motion::deform(mesh, roles, spring_motion::Translation_motion<2>{{0, 0.1}},
                                            spring_motion::Grid_scaled_stiffness{});
  spring_motion::write_report_json(report, std::cout);
  const bool moved_up = mesh.points[4][1] > 0.5 && mesh.points[5][1] == 0.1;
  return report.completed && moved_up ? 0 : 1;
}
