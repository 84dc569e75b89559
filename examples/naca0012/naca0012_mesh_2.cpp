// Copyright (c) 2026 SpringMotion developers.
//
// The 2D NACA0012 test domain of docs/method.md, "Test cases".
//
// Generation parameters, and why (numbers measured with CGAL 5.5.1):
//
// * Airfoil: `airfoil_nodes` = 130 points, cosine spacing in x
//   (x = (1 + cos t)/2, t uniform), the same number of intervals on both
//   surfaces: the leading edge (curvature radius 0.0158) and the sharp
//   trailing edge get the small cells the paper's pitching motion stresses
//   most, and the input is symmetric about the chord. 130 + 33 boundary nodes
//   is what 3875 nodes and 7587 triangles imply (triangles = 2 nodes -
//   boundary nodes for a domain with one hole).
// * Far field: `far_field_nodes` = 33 points uniform in angle from angle 0
//   (downstream), radius 15 chords around (0.5, 0) (docs/method.md, "Test cases").
// * Shape bound 0.125: Mesh_2's B is the squared sine of the smallest angle
//   (about 20.7 degrees); the paper's value, Mesh_2's default, and the largest
//   for which Mesh_2 guarantees termination.
// * Size bound h(p) = h_a + g d(p), d the distance from p (the centroid of the
//   triangle) to the airfoil polyline, compared with the longest edge as in
//   CGAL's Delaunay_mesh_size_criteria_2. h_a is the constant
//   `size_at_airfoil` or, by default, kSize_to_spacing (2) times the length
//   of the airfoil segment closest to p, so that h follows the cosine spacing:
//   a uniform h_a would be either coarser than the trailing edge (no grading
//   there) or finer than mid-chord segments, and a triangle on a segment
//   longer than h makes Mesh_2 split the segment. With a factor of 1.5 the
//   fine variant still had trailing-edge segments split; 2 gives no split for
//   the default and fine options.
// * Near the circle, h is at least kSize_to_spacing far-field spacings (2 pi R
//   / n): the growth alone gives h of about 2.5 there, below the 2.85 of the
//   33 far-field segments, and Mesh_2 then split 21 of the 33 segments.
// * g = `size_growth` = 0.17 (`default_size_growth`): with the settings above
//   it gives 3844 nodes and 7525 triangles for the defaults (count ~ 1/g^2:
//   0.16 gives 4254 nodes, 0.18 gives 3499). `fine()` halves every length:
//   twice the boundary nodes, half the growth rate; 16095 nodes (4.2x).
// * Splits: should Mesh_2 still split a constrained segment (a circumcentre
//   encroaching it), its midpoint would lie on the chord of the curve, off
//   the curve. The generator then adds the curve point at the parameter
//   midpoint of that segment to the input polyline and meshes again from
//   scratch, until nothing is split. So every boundary vertex is a point
//   computed on the curve or circle, nothing is moved after refinement (which
//   could invert triangles), and the result stays deterministic; the boundary
//   node counts can end above the requested ones (never for the default and
//   fine options).
// * No Lloyd/ODT smoothing: it would move boundary vertices off the curve.

#include <naca0012/Naca0012_mesh_2.h>

#include <spring_motion/Error.h>

#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Mesh_2/Face_badness.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <utility>
#include <vector>

namespace spring_motion {

double naca0012_half_thickness(double x)
{
  // Clamped to the chord: the coefficients sum to zero, so x = 1 closes the
  // trailing edge exactly, but rounding would leave about 1e-17.
  if(!(x > 0.0))
    return 0.0;
  if(x >= 1.0)
    return 0.0;
  return 0.6 * (0.2969 * std::sqrt(x)
                + x * (-0.1260 + x * (-0.3516 + x * (0.2843 + x * (-0.1036)))));
}

Naca0012_mesh_2_options Naca0012_mesh_2_options::fine()
{
  Naca0012_mesh_2_options options;
  options.airfoil_nodes = 260;
  options.far_field_nodes = 66;
  options.size_growth = 0.5 * default_size_growth;
  return options;
}

bool is_on_naca0012_airfoil(double x, double y)
{
  // Generous tolerances: the far field is at least one chord away from the
  // airfoil, so only the airfoil's own points can pass.
  const double tolerance = 1e-6;
  return x >= -tolerance && x <= 1.0 + tolerance
         && std::abs(y) <= naca0012_half_thickness(std::clamp(x, 0.0, 1.0)) + tolerance;
}

namespace {

using Point = Mesh_2_kernel::Point_2;
using Vertex_handle = Mesh_2_cdt::Vertex_handle;
using Face_handle = Mesh_2_cdt::Face_handle;

constexpr double kPi = 3.14159265358979323846;

// See the top of the file.
constexpr double kSize_to_spacing = 2.0;

// Airfoil point at parameter t in [0, 2 pi): t = 0 is the trailing edge,
// t = pi the leading edge, the upper surface first. Uniform t is cosine
// spacing in x.
Point airfoil_point(double t)
{
  if(t == 0.0)
    return Point(1.0, 0.0);
  if(t == kPi)
    return Point(0.0, 0.0);
  const double x = 0.5 * (1.0 + std::cos(t));
  const double y = naca0012_half_thickness(x);
  return Point(x, t < kPi ? y : -y);
}

Point far_field_point(double phi, double radius)
{
  if(phi == 0.0)
    return Point(0.5 + radius, 0.0);
  return Point(0.5 + radius * std::cos(phi), radius * std::sin(phi));
}

// The graded size bound of the top of the file, evaluated by brute force over
// the airfoil segments (a few hundred: cheaper than building a search tree
// for every meshing round).
class Size_field
{
public:
  Size_field(const std::vector<Point>& airfoil, double size_at_airfoil, double growth,
             double far_field_radius, double far_field_spacing)
    : size_at_airfoil_(size_at_airfoil), growth_(growth), far_field_radius_(far_field_radius),
      far_field_size_(kSize_to_spacing * far_field_spacing)
  {
    for(std::size_t i = 0; i < airfoil.size(); ++i) {
      const Point& a = airfoil[i];
      const Point& b = airfoil[(i + 1) % airfoil.size()];
      segments_.push_back({a.x(), a.y(), b.x() - a.x(), b.y() - a.y(),
                           std::sqrt(CGAL::squared_distance(a, b))});
    }
  }

  double operator()(double x, double y) const
  {
    double best_squared_distance = std::numeric_limits<double>::infinity();
    double best_length = 0.0;
    for(const Segment& s : segments_) {
      const double px = x - s.ax, py = y - s.ay;
      const double t = std::clamp((px * s.dx + py * s.dy) / (s.length * s.length), 0.0, 1.0);
      const double ex = px - t * s.dx, ey = py - t * s.dy;
      const double squared_distance = ex * ex + ey * ey;
      if(squared_distance < best_squared_distance) {
        best_squared_distance = squared_distance;
        best_length = s.length;
      }
    }
    const double at_airfoil = size_at_airfoil_ > 0.0 ? size_at_airfoil_
                                                     : kSize_to_spacing * best_length;
    const double h = at_airfoil + growth_ * std::sqrt(best_squared_distance);
    const double to_circle = far_field_radius_ - std::hypot(x - 0.5, y);
    if(to_circle < far_field_size_)
      return std::max(h, far_field_size_);
    return h;
  }

private:
  struct Segment
  {
    double ax, ay, dx, dy, length;
  };
  std::vector<Segment> segments_;
  double size_at_airfoil_;
  double growth_;
  double far_field_radius_;
  double far_field_size_;
};

// Mesh_2 criteria: the shape bound of Delaunay_mesh_criteria_2 plus a size
// bound that varies in space, modelled on Delaunay_mesh_size_criteria_2 (whose
// Quality type, and thus refinement order, it reuses).
class Graded_criteria
{
public:
  using Face_handle = Mesh_2_cdt::Face_handle;
  using Quality = CGAL::Delaunay_mesh_size_criteria_2<Mesh_2_cdt>::Quality;

  Graded_criteria(double shape_bound, const Size_field& size) : shape_bound_(shape_bound), size_(&size) {}

  class Is_bad
  {
  public:
    Is_bad(double shape_bound, const Size_field* size) : shape_bound_(shape_bound), size_(size) {}

    CGAL::Mesh_2::Face_badness operator()(const Quality& q) const
    {
      if(q.size() > 1.0)
        return CGAL::Mesh_2::IMPERATIVELY_BAD;
      if(q.sine() < shape_bound_)
        return CGAL::Mesh_2::BAD;
      return CGAL::Mesh_2::NOT_BAD;
    }

    CGAL::Mesh_2::Face_badness operator()(const Face_handle& fh, Quality& q) const
    {
      const Point& pa = fh->vertex(0)->point();
      const Point& pb = fh->vertex(1)->point();
      const Point& pc = fh->vertex(2)->point();
      const double a = CGAL::squared_distance(pb, pc);
      const double b = CGAL::squared_distance(pc, pa);
      const double c = CGAL::squared_distance(pa, pb);
      double longest = a, second = b;
      if(second > longest)
        std::swap(longest, second);
      if(c > longest) {
        second = longest;
        longest = c;
      } else if(c > second) {
        second = c;
      }

      const double h = (*size_)((pa.x() + pb.x() + pc.x()) / 3.0, (pa.y() + pb.y() + pc.y()) / 3.0);
      q.second = longest / (h * h);
      if(q.size() > 1.0) {
        q.first = 1.0; // the sine does not matter any more
        return CGAL::Mesh_2::IMPERATIVELY_BAD;
      }
      const double twice_area = 2.0 * CGAL::area(pa, pb, pc);
      q.first = twice_area * twice_area / (longest * second); // squared sine of the smallest angle
      return operator()(q);
    }

  private:
    double shape_bound_;
    const Size_field* size_;
  };

  Is_bad is_bad_object() const { return Is_bad(shape_bound_, size_); }

private:
  double shape_bound_;
  const Size_field* size_;
};

// One boundary loop: sorted curve parameters and the vertices they became.
struct Boundary_loop
{
  std::vector<double> parameters;
  std::vector<Vertex_handle> vertices;
};

template <class Point_at>
void insert_loop(Mesh_2_cdt& cdt, Boundary_loop& loop, Point_at point_at)
{
  loop.vertices.clear();
  for(double t : loop.parameters)
    loop.vertices.push_back(cdt.insert(point_at(t)));
  const std::size_t n = loop.vertices.size();
  for(std::size_t i = 0; i < n; ++i)
    cdt.insert_constraint(loop.vertices[i], loop.vertices[(i + 1) % n]);
}

// Adds the parameter midpoint of every segment Mesh_2 split; returns how many.
std::size_t add_midpoints_of_split_segments(const Mesh_2_cdt& cdt, Boundary_loop& loop,
                                            double period)
{
  const std::size_t n = loop.parameters.size();
  std::vector<double> refined;
  refined.reserve(2 * n);
  std::size_t splits = 0;
  for(std::size_t i = 0; i < n; ++i) {
    refined.push_back(loop.parameters[i]);
    if(!cdt.is_edge(loop.vertices[i], loop.vertices[(i + 1) % n])) {
      const double next = i + 1 < n ? loop.parameters[i + 1] : period;
      refined.push_back(0.5 * (loop.parameters[i] + next));
      ++splits;
    }
  }
  loop.parameters = std::move(refined);
  return splits;
}

} // namespace

void make_naca0012_mesh_2(Mesh_2_cdt& cdt, const Naca0012_mesh_2_options& options)
{
  SPRING_MOTION_CHECK(options.airfoil_nodes >= 8 && options.airfoil_nodes % 2 == 0,
                      "Naca0012_mesh_2_options::airfoil_nodes must be even and at least 8, got "
                          << options.airfoil_nodes);
  SPRING_MOTION_CHECK(options.far_field_nodes >= 8,
                      "Naca0012_mesh_2_options::far_field_nodes must be at least 8, got "
                          << options.far_field_nodes);
  SPRING_MOTION_CHECK(options.far_field_radius >= 1.0,
                      "Naca0012_mesh_2_options::far_field_radius must be at least one chord, got "
                          << options.far_field_radius);
  SPRING_MOTION_CHECK(options.shape_bound > 0.0 && options.shape_bound <= 0.125,
                      "Naca0012_mesh_2_options::shape_bound must be in (0, 0.125] (Mesh_2 may not "
                      "terminate above), got " << options.shape_bound);
  SPRING_MOTION_CHECK(options.size_at_airfoil >= 0.0 && options.size_growth >= 0.0,
                      "Naca0012_mesh_2_options: size_at_airfoil and size_growth must not be "
                      "negative");
  SPRING_MOTION_CHECK(options.max_meshing_rounds >= 1,
                      "Naca0012_mesh_2_options::max_meshing_rounds must be at least 1");

  const double growth = options.size_growth > 0.0 ? options.size_growth
                                                  : Naca0012_mesh_2_options::default_size_growth;
  const double radius = options.far_field_radius;

  Boundary_loop airfoil, far_field;
  for(std::size_t i = 0; i < options.airfoil_nodes; ++i)
    airfoil.parameters.push_back(2.0 * kPi * double(i) / double(options.airfoil_nodes));
  for(std::size_t i = 0; i < options.far_field_nodes; ++i)
    far_field.parameters.push_back(2.0 * kPi * double(i) / double(options.far_field_nodes));
  const double far_field_spacing = 2.0 * radius * std::sin(kPi / double(options.far_field_nodes));

  for(std::size_t round = 1;; ++round) {
    cdt.clear();
    insert_loop(cdt, airfoil, airfoil_point);
    insert_loop(cdt, far_field, [radius](double phi) { return far_field_point(phi, radius); });

    std::vector<Point> airfoil_points;
    for(Vertex_handle v : airfoil.vertices)
      airfoil_points.push_back(v->point());
    const Size_field size(airfoil_points, options.size_at_airfoil, growth, radius,
                          far_field_spacing);

    // The seed marks the airfoil's interior as outside the domain.
    const Point seeds[] = {Point(0.5, 0.0)};
    CGAL::refine_Delaunay_mesh_2(cdt, std::begin(seeds), std::end(seeds),
                                 Graded_criteria(options.shape_bound, size));

    const std::size_t splits = add_midpoints_of_split_segments(cdt, airfoil, 2.0 * kPi)
                               + add_midpoints_of_split_segments(cdt, far_field, 2.0 * kPi);
    if(splits == 0)
      return;
    SPRING_MOTION_CHECK(round < options.max_meshing_rounds,
                        "make_naca0012_mesh_2: Mesh_2 still split " << splits
                            << " boundary segments after " << round
                            << " rounds; refine the boundary or lower size_growth");
  }
}

} // namespace spring_motion
