// Copyright (c) 2026 SpringMotion developers.
//
// Generates the 2D NACA0012 test domain (docs/method.md, "Test cases") with the default
// and the fine options and prints its size: nodes and triangles of the domain,
// boundary nodes on the airfoil and on the far field, and generation time.
// Writes no file.

#include <naca0012/Naca0012_mesh_2.h>

#include <chrono>
#include <cstddef>
#include <iostream>
#include <set>

namespace {

void print_stats(const char* name, const spring_motion::Naca0012_mesh_2_options& options)
{
  using Cdt = spring_motion::Mesh_2_cdt;

  Cdt cdt;
  const auto start = std::chrono::steady_clock::now();
  spring_motion::make_naca0012_mesh_2(cdt, options);
  const std::chrono::duration<double> seconds = std::chrono::steady_clock::now() - start;

  // Mesh_2 keeps the faces inside the airfoil: only the domain counts.
  std::set<Cdt::Vertex_handle> nodes, boundary;
  std::size_t triangles = 0;
  for(Cdt::Face_handle f : cdt.finite_face_handles()) {
    if(!f->is_in_domain())
      continue;
    ++triangles;
    for(int i = 0; i < 3; ++i) {
      nodes.insert(f->vertex(i));
      const Cdt::Face_handle n = f->neighbor(i);
      if(cdt.is_infinite(n) || !n->is_in_domain()) {
        boundary.insert(f->vertex(Cdt::cw(i)));
        boundary.insert(f->vertex(Cdt::ccw(i)));
      }
    }
  }
  std::size_t airfoil = 0;
  for(Cdt::Vertex_handle v : boundary)
    if(spring_motion::is_on_naca0012_airfoil(v->point().x(), v->point().y()))
      ++airfoil;

  std::cout << name << ": " << nodes.size() << " nodes, " << triangles << " triangles, "
            << airfoil << " airfoil nodes, " << boundary.size() - airfoil << " far-field nodes, "
            << seconds.count() << " s\n";
}

} // namespace

int main()
{
  std::cout << "NACA0012 domain (paper: 3875 nodes, 7587 triangles)\n";
  print_stats("default", spring_motion::Naca0012_mesh_2_options());
  print_stats("fine   ", spring_motion::Naca0012_mesh_2_options::fine());
  return 0;
}
