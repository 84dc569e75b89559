// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_DOMAINS_NACA0012_MESH_2_H
#define SPRING_MOTION_DOMAINS_NACA0012_MESH_2_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>

#include <cstddef>

namespace spring_motion {

/// The triangulation type the 2D test domains are built in: a CGAL constrained
/// Delaunay triangulation refined by Mesh_2 (faces know `is_in_domain()`).
using Mesh_2_kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh_2_vertex_base = CGAL::Delaunay_mesh_vertex_base_2<Mesh_2_kernel>;
using Mesh_2_face_base = CGAL::Delaunay_mesh_face_base_2<Mesh_2_kernel>;
using Mesh_2_tds = CGAL::Triangulation_data_structure_2<Mesh_2_vertex_base, Mesh_2_face_base>;
using Mesh_2_cdt = CGAL::Constrained_Delaunay_triangulation_2<Mesh_2_kernel, Mesh_2_tds,
                                                              CGAL::Exact_predicates_tag>;

/// Half thickness of the NACA0012 section with a closed (sharp) trailing edge,
/// chord 1, x in [0,1] (METHOD.md section 6).
double naca0012_half_thickness(double x);

/// Parameters of the NACA0012-in-a-circle domain. Defaults reproduce the
/// paper's 2D grid size (3875 nodes, 7587 triangles, within 10%).
struct Naca0012_mesh_2_options
{
  std::size_t airfoil_nodes = 130;     // nodes on the airfoil contour
  std::size_t far_field_nodes = 33;    // nodes on the far-field circle
  double far_field_radius = 15.0;      // chords; circle centred at (0.5, 0)
  double shape_bound = 0.125;          // Mesh_2 criteria shape bound
  // size bound h(p) = size_at_airfoil + size_growth * distance(p, airfoil)
  double size_at_airfoil = 0.0;        // 0: derived from the airfoil spacing
  double size_growth = 0.0;            // 0: default grading
  /// The 4x finer variant (about 15,000 nodes) for scaling work.
  static Naca0012_mesh_2_options fine();
};

/// Fills `cdt` (cleared first) with the refined NACA0012 domain. Faces inside
/// the airfoil and outside the circle are not in the domain. Deterministic:
/// the same options give the same triangulation, vertex for vertex.
void make_naca0012_mesh_2(Mesh_2_cdt& cdt, const Naca0012_mesh_2_options& options = {});

/// Whether a point of the domain's boundary lies on the airfoil (as opposed
/// to the far field). Valid for points of the generated mesh.
bool is_on_naca0012_airfoil(double x, double y);

} // namespace spring_motion

#endif
