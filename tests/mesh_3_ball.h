// A small Mesh_3 ball for the tests. make_mesh_3 lives in its own
// translation unit: instantiated next to Boost Graph's headers (which the
// solver includes), CGAL 5.5's mutable_queue finds two down_heap overloads.
#ifndef SPRING_MOTION_TESTS_MESH_3_BALL_H
#define SPRING_MOTION_TESTS_MESH_3_BALL_H

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_triangulation_3.h>

namespace spring_motion_test {

using Ball_kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Ball_domain = CGAL::Labeled_mesh_domain_3<Ball_kernel>;
using Ball_tr = CGAL::Mesh_triangulation_3<Ball_domain>::type;
using Ball_c3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Ball_tr>;

/// The unit ball meshed by Mesh_3 from its implicit function (weighted
/// points, far vertices and cells outside the complex included), a few
/// hundred tetrahedra with `size` 0.35.
Ball_c3t3 make_ball_c3t3(double size = 0.35);

} // namespace spring_motion_test

#endif
