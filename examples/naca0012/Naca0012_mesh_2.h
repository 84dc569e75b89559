// Copyright (c) 2026 SpringMotion developers.
//
// The paper's 2D test domain, for the demos, the tests and the benchmark
// (library naca0012_domains, examples/naca0012/CMakeLists.txt). Not part of
// the installed SpringMotion library.
#ifndef SPRING_MOTION_EXAMPLES_NACA0012_MESH_2_H
#define SPRING_MOTION_EXAMPLES_NACA0012_MESH_2_H

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
/// chord 1, x in [0,1] (docs/method.md, "Test cases").
double naca0012_half_thickness(double x);

/// Parameters of the NACA0012-in-a-circle domain. Defaults reproduce the
/// paper's 2D grid size (3875 nodes, 7587 triangles, within 10%). Why each
/// default has its value: examples/naca0012/naca0012_mesh_2.cpp.
struct Naca0012_mesh_2_options
{
  /// Points of the initial airfoil polyline, cosine spaced in x, half on each
  /// surface (must be even, at least 8). The final mesh can have a few more if
  /// Mesh_2 would otherwise split a segment (see `max_meshing_rounds`).
  std::size_t airfoil_nodes = 130;
  /// Points of the initial far-field polyline, uniform in angle (at least 8).
  std::size_t far_field_nodes = 33;
  /// Far-field radius in chords (at least 1); the circle is centred at (0.5, 0).
  double far_field_radius = 15.0;
  /// Mesh_2 shape bound B: the squared sine of the smallest angle a triangle
  /// may have (0.125: about 20.7 degrees). In (0, 0.125].
  double shape_bound = 0.125;
  /// Size bound h(p) = size_at_airfoil + size_growth * distance(p, airfoil),
  /// never below 2 far-field spacings next to the circle.
  /// 0: twice the length of the airfoil segment closest to p, which
  /// follows the cosine spacing (recommended; a constant finer than the
  /// boundary spacing makes Mesh_2 split the airfoil).
  double size_at_airfoil = 0.0;
  /// Growth rate of the size bound with the distance (in chords per chord).
  /// 0: `default_size_growth`.
  double size_growth = 0.0;
  /// The growth rate used when `size_growth` is 0.
  static constexpr double default_size_growth = 0.17;
  /// A segment split by Mesh_2 would leave a vertex on the chord of the curve,
  /// not on it: the generator then adds the curve point to the polyline and
  /// meshes again. At most this many meshing rounds, then it throws.
  std::size_t max_meshing_rounds = 10;
  /// The 4x finer variant (about 15,000 nodes) for scaling work: twice the
  /// boundary nodes, half the growth rate.
  static Naca0012_mesh_2_options fine();
};

/// Fills `cdt` (cleared first) with the refined NACA0012 domain. Faces inside
/// the airfoil and outside the circle are not in the domain. Every boundary
/// vertex is a point computed on the airfoil curve or on the circle (no point
/// is moved after refinement). Deterministic: the same options give the same
/// triangulation, vertex for vertex. Throws spring_motion::Error on invalid
/// options.
void make_naca0012_mesh_2(Mesh_2_cdt& cdt, const Naca0012_mesh_2_options& options = {});

/// Whether a point of the domain's boundary lies on the airfoil (as opposed
/// to the far field): x in [0, 1] and |y| at most the half thickness, with a
/// 1e-6 tolerance. Valid for boundary points of the generated (undeformed)
/// mesh, whose far field is at least a chord away.
bool is_on_naca0012_airfoil(double x, double y);

} // namespace spring_motion

#endif
