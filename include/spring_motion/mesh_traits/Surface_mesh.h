// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_MESH_TRAITS_SURFACE_MESH_H
#define SPRING_MOTION_MESH_TRAITS_SURFACE_MESH_H

#include <spring_motion/Error.h>
#include <spring_motion/mesh_traits/Simplicial_mesh_traits.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/number_utils.h>

#include <array>
#include <cmath>
#include <cstddef>

namespace spring_motion {

/// A triangle `CGAL::Surface_mesh` read as a 2D domain, through its vertex
/// point property map. Points may be 2D, or 3D lying in one plane: then the
/// mesh is moved inside that plane. When every z is the same the plane frame
/// is simply (x, y), so no rounding is introduced; otherwise an orthonormal
/// frame from the face normals is used and a point farther than 1e-9 times the
/// bounding-box diagonal from the plane is an error.
template <class P>
struct Simplicial_mesh_traits<CGAL::Surface_mesh<P>>
{
  static constexpr int dimension = 2;
  using Mesh = CGAL::Surface_mesh<P>;
  using Vertex_handle = typename Mesh::Vertex_index;
  using Kernel = typename CGAL::Kernel_traits<P>::Kernel;
  static constexpr bool is_3d = (CGAL::Ambient_dimension<P>::value == 3);

  explicit Simplicial_mesh_traits(const Mesh& mesh) : mesh_(mesh)
  {
    if constexpr(is_3d)
      fit_plane();
  }

  template <class F>
  void for_each_vertex(F f) const
  {
    for(Vertex_handle v : mesh_.vertices())
      f(v);
  }

  template <class F>
  void for_each_element(F f) const
  {
    for(auto fc : mesh_.faces()) {
      std::array<Vertex_handle, 3> t;
      std::size_t k = 0;
      for(auto v : CGAL::vertices_around_face(mesh_.halfedge(fc), mesh_)) {
        SPRING_MOTION_CHECK(k < 3, "Surface_mesh face " << std::size_t(fc) << " is not a triangle");
        t[k++] = v;
      }
      SPRING_MOTION_CHECK(k == 3, "Surface_mesh face " << std::size_t(fc) << " has " << k << " vertices");
      f(t);
    }
  }

  std::array<double, 2> point(Vertex_handle v) const
  {
    const P& p = mesh_.point(v);
    if constexpr(!is_3d) {
      return {CGAL::to_double(p.x()), CGAL::to_double(p.y())};
    } else {
      const std::array<double, 3> q{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
      if(flat_z_)
        return {q[0], q[1]};
      std::array<double, 2> uv{0, 0};
      for(int c = 0; c < 3; ++c) {
        uv[0] += (q[c] - origin_[c]) * e1_[c];
        uv[1] += (q[c] - origin_[c]) * e2_[c];
      }
      return uv;
    }
  }

  void set_point(Mesh& mesh, Vertex_handle v, const std::array<double, 2>& uv) const
  {
    if constexpr(!is_3d) {
      mesh.point(v) = P(uv[0], uv[1]);
    } else if(flat_z_) {
      mesh.point(v) = P(uv[0], uv[1], z_);
    } else {
      // Mapping back from the plane's frame rounds: a vertex that did not
      // move (a fixed one) keeps its point bitwise instead.
      if(point(v) == uv)
        return;
      std::array<double, 3> q;
      for(int c = 0; c < 3; ++c)
        q[c] = origin_[c] + uv[0] * e1_[c] + uv[1] * e2_[c];
      mesh.point(v) = P(q[0], q[1], q[2]);
    }
  }

private:
  void fit_plane()
  {
    SPRING_MOTION_CHECK(mesh_.number_of_vertices() > 0, "Surface_mesh has no vertices");
    const P& p0 = mesh_.point(*mesh_.vertices().begin());
    z_ = CGAL::to_double(p0.z());
    flat_z_ = true;
    for(Vertex_handle v : mesh_.vertices())
      if(CGAL::to_double(mesh_.point(v).z()) != z_) {
        flat_z_ = false;
        break;
      }
    if(flat_z_)
      return;
    // Newell's normal: the sum of the face normals, robust for any orientation.
    std::array<double, 3> n{0, 0, 0}, lo, hi;
    origin_ = {CGAL::to_double(p0.x()), CGAL::to_double(p0.y()), z_};
    lo = hi = origin_;
    for(auto fc : mesh_.faces()) {
      std::array<std::array<double, 3>, 3> t;
      std::size_t k = 0;
      for(auto v : CGAL::vertices_around_face(mesh_.halfedge(fc), mesh_))
        if(k < 3) {
          const P& p = mesh_.point(v);
          t[k++] = {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
        }
      if(k < 3)
        continue;
      const std::array<double, 3> a{t[1][0] - t[0][0], t[1][1] - t[0][1], t[1][2] - t[0][2]};
      const std::array<double, 3> b{t[2][0] - t[0][0], t[2][1] - t[0][1], t[2][2] - t[0][2]};
      n[0] += a[1] * b[2] - a[2] * b[1];
      n[1] += a[2] * b[0] - a[0] * b[2];
      n[2] += a[0] * b[1] - a[1] * b[0];
    }
    const double nn = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    SPRING_MOTION_CHECK(nn > 0, "Surface_mesh: cannot find the plane of a degenerate mesh");
    for(double& c : n)
      c /= nn;
    // e1: the coordinate axis most orthogonal to n, made orthogonal to it.
    int axis = 0;
    for(int c = 1; c < 3; ++c)
      if(std::abs(n[c]) < std::abs(n[axis]))
        axis = c;
    std::array<double, 3> e{0, 0, 0};
    e[axis] = 1;
    const double en = e[0] * n[0] + e[1] * n[1] + e[2] * n[2];
    for(int c = 0; c < 3; ++c)
      e1_[c] = e[c] - en * n[c];
    const double l1 = std::sqrt(e1_[0] * e1_[0] + e1_[1] * e1_[1] + e1_[2] * e1_[2]);
    for(double& c : e1_)
      c /= l1;
    e2_ = {n[1] * e1_[2] - n[2] * e1_[1], n[2] * e1_[0] - n[0] * e1_[2], n[0] * e1_[1] - n[1] * e1_[0]};
    double max_off = 0;
    for(Vertex_handle v : mesh_.vertices()) {
      const P& p = mesh_.point(v);
      const std::array<double, 3> q{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
      double off = 0;
      for(int c = 0; c < 3; ++c) {
        off += (q[c] - origin_[c]) * n[c];
        lo[c] = std::min(lo[c], q[c]);
        hi[c] = std::max(hi[c], q[c]);
      }
      max_off = std::max(max_off, std::abs(off));
    }
    const double diag = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                  (hi[2] - lo[2]) * (hi[2] - lo[2]));
    SPRING_MOTION_CHECK(max_off <= 1e-9 * diag, "Surface_mesh with 3D points is not planar: a vertex lies "
                                                    << max_off << " from the best plane (diagonal " << diag << ")");
  }

  const Mesh& mesh_;
  bool flat_z_ = true;
  double z_ = 0;
  std::array<double, 3> origin_{}, e1_{}, e2_{};
};

} // namespace spring_motion

#endif
