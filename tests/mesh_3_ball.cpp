#include "mesh_3_ball.h"

#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/make_mesh_3.h>

namespace spring_motion_test {

Ball_c3t3 make_ball_c3t3(double size)
{
  namespace p = CGAL::parameters;
  auto ball = [](const Ball_kernel::Point_3& q) { return q.x() * q.x() + q.y() * q.y() + q.z() * q.z() - 1.0; };
  Ball_domain domain =
      Ball_domain::create_implicit_mesh_domain(ball, Ball_kernel::Sphere_3(CGAL::ORIGIN, 4.0));
  CGAL::Mesh_criteria_3<Ball_tr> criteria(p::facet_angle = 25, p::facet_size = size, p::facet_distance = size / 7,
                                          p::cell_radius_edge_ratio = 3, p::cell_size = size);
  return CGAL::make_mesh_3<Ball_c3t3>(domain, criteria, p::no_perturb(), p::no_exude());
}

} // namespace spring_motion_test
