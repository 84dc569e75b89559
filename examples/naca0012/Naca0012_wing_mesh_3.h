// Copyright (c) 2026 SpringMotion developers.
//
// The paper's 3D test domain, for the demos, the tests and the benchmark
// (library naca0012_domains, examples/naca0012/CMakeLists.txt). Not part of
// the installed SpringMotion library.
#ifndef SPRING_MOTION_EXAMPLES_NACA0012_WING_MESH_3_H
#define SPRING_MOTION_EXAMPLES_NACA0012_WING_MESH_3_H

#include <spring_motion/Indexed_mesh.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polyhedral_mesh_domain_with_features_3.h>
#include <CGAL/Surface_mesh.h>

#include <cstddef>
#include <string>

namespace spring_motion {

/// The types the 3D test domains are built with: CGAL Mesh_3 on a polyhedral
/// domain whose sharp edges are given as protected polyline features. The
/// surface patch index of a boundary facet is the patch id of the input
/// surface: 1 for the body (wing, inner box), 2 for the outer boundary.
using Mesh_3_kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh_3_surface = CGAL::Surface_mesh<Mesh_3_kernel::Point_3>;
using Mesh_3_domain = CGAL::Polyhedral_mesh_domain_with_features_3<Mesh_3_kernel, Mesh_3_surface>;
using Mesh_3_triangulation = CGAL::Mesh_triangulation_3<Mesh_3_domain>::type;
using Mesh_3_c3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Mesh_3_triangulation, Mesh_3_domain::Corner_index,
                                                            Mesh_3_domain::Curve_index>;

/// Patch ids (boundary labels) of the 3D test domains.
constexpr int body_patch = 1;
constexpr int outer_patch = 2;

/// Parameters of the NACA0012 wing in a sphere (docs/method.md, "Test cases"): chord
/// 1 from x = 0 to 1, span 2 (z in [-1, 1]), flat tips, sharp trailing edge;
/// sphere of radius `far_field_radius` centred at (0.5, 0, 0). Defaults give
/// the paper's 57924 nodes and 308850 tetrahedra within 10%; why each default
/// has its value: examples/naca0012/naca0012_wing_mesh_3.cpp.
struct Naca0012_wing_mesh_3_options
{
  std::size_t section_intervals = 100; ///< input polyline intervals per surface (upper, lower), cosine spaced
  std::size_t span_intervals = 40;     ///< input intervals along the span
  std::size_t sphere_subdivisions = 4; ///< the input sphere is an icosahedron subdivided this many times
  double far_field_radius = 15;
  double size_at_wing = 0.04;          ///< Mesh_3 facet and cell size at the wing
  double size_at_trailing_edge = 0.035; ///< Mesh_3 edge size along the trailing edge and the tip edges
  double size_growth = 0.091;          ///< size grows by this much per chord of distance from the wing
  double facet_distance = 0.004;       ///< Mesh_3 facet distance bound near the wing (curvature)
  double facet_angle = 25;             ///< Mesh_3 facet angle bound (degrees)
  double cell_radius_edge_ratio = 3;   ///< Mesh_3 radius-edge bound
  /// the smallest dihedral angle (degrees) Mesh_3's sliver perturbation and
  /// exudation aim for. Alone it does not remove the slivers that limit the
  /// wing's motion: those have an edge on a tip feature curve, whose vertices
  /// neither optimiser moves; ODT and the pass below reach them
  /// (docs/naca0012_3d/README.md).
  double sliver_bound = 20;
  /// iterations of Mesh_3's ODT smoothing before perturbation (0: none); ODT
  /// moves the vertices next to the tip outline before the optimisers run
  std::size_t odt_iterations = 10;
  /// After Mesh_3 (in `naca0012_wing_mesh_3()`, not in the complex), the
  /// interior vertices of every tetrahedron with a dihedral angle below this
  /// bound (degrees; 0: no such pass) move to raise the smallest dihedral
  /// angle around them, in up to `sliver_smoothing_sweeps` sweeps; boundary
  /// vertices stay. It reaches slivers next to the tip outline that Mesh_3's
  /// optimisers leave. With ODT and the bounds of 20 degrees the paper's
  /// grid-scaled model completes +30 and -30 degrees; without ODT and this
  /// pass (the first defaults: no ODT, bound 10, no pass) it stops at 20.5
  /// and -18.0 (docs/naca0012_3d/README.md).
  double sliver_smoothing_bound = 20;
  std::size_t sliver_smoothing_sweeps = 5;
  /// Then every tetrahedron with all four vertices on the wing, two facets
  /// on it and a dihedral angle below this bound (degrees; 0: none) is given
  /// to the wing (`absorb_body_slivers()`). Mesh_3 leaves three at the
  /// leading edge with 7.55 to 7.70 degrees, which no vertex motion can
  /// change (docs/naca0012_3d/README.md).
  double wing_sliver_bound = 20;
  /// A short text listing every parameter, used to name the cache file.
  std::string key() const;
};

/// Meshes the wing domain into `c3t3` (cleared first). Deterministic: Mesh_3
/// runs sequentially with its random generator seeded by a constant (0),
/// so the same options give the same mesh. Throws spring_motion::Error on
/// invalid options.
void make_naca0012_wing_mesh_3(Mesh_3_c3t3& c3t3, const Naca0012_wing_mesh_3_options& options = {});

/// The wing mesh as an `Indexed_mesh<3>`: boundary facets labelled
/// `body_patch` (wing) or `outer_patch` (sphere), element labels the Mesh_3
/// subdomain index. If `cache_dir` is not empty the mesh is read from
/// `cache_dir/naca0012_wing_cache_file_name(options)` when that file exists
/// (the file also holds `options.key()` in a comment) and written
/// there (atomically, through a temporary file and a rename) after meshing.
/// `generated` (if given) tells whether the mesh was generated rather than read,
/// `seconds` how long generation or reading took.
Indexed_mesh<3> naca0012_wing_mesh_3(const Naca0012_wing_mesh_3_options& options = {},
                                     const std::string& cache_dir = "", bool* generated = nullptr,
                                     double* seconds = nullptr);

/// Gives to the body (boundary label `body`) every tetrahedron of `m` whose
/// four vertices lie on the body, two of whose facets are body facets and
/// whose smallest dihedral angle is below `bound_deg` degrees, unless that
/// would make the body's surface non-manifold or leave a facet of the
/// tetrahedron unshared: the tetrahedron leaves `m.elements`, its two body
/// facets leave `m.boundary_facets`, its two other facets join them with
/// label `body` (a flip of the surface edge the body facets share). Points
/// are unchanged. Returns how many tetrahedra were given to the body.
std::size_t absorb_body_slivers(Indexed_mesh<3>& m, int body, double bound_deg);

/// The name (no folder) of the file in which `naca0012_wing_mesh_3()` caches
/// the mesh of these options: naca0012_wing_<hash of options.key()>.mesh.
std::string naca0012_wing_cache_file_name(const Naca0012_wing_mesh_3_options& options);

/// Whether a boundary point of the generated (undeformed) wing mesh lies on
/// the wing rather than on the far-field sphere.
bool is_on_naca0012_wing(double x, double y, double z);

/// A box with a box-shaped hole, for tests: outer box [-outer, outer]^3,
/// hole [-inner, inner]^3, all twelve box edges protected features; Mesh_3
/// with uniform size `size`. Facets on the hole have patch `body_patch`,
/// those on the outer box `outer_patch`. Deterministic like the wing.
struct Box_with_hole_mesh_3_options
{
  double outer = 1.0;
  double inner = 0.35;
  double size = 0.25;
};
void make_box_with_hole_mesh_3(Mesh_3_c3t3& c3t3, const Box_with_hole_mesh_3_options& options = {});

} // namespace spring_motion

#endif
