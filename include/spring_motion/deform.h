// Copyright (c) 2026 SpringMotion developers.
#ifndef SPRING_MOTION_DEFORM_H
#define SPRING_MOTION_DEFORM_H

// deform() and, for the users of this header, everything it takes:
// Deform_options and Default_deform_visitor (Deform_options.h) and the
// stateful Network_deformer (Network_deformer.h).
#include <spring_motion/Deform_options.h>
#include <spring_motion/Deform_report.h>
#include <spring_motion/Network_deformer.h>
#include <spring_motion/Spring_network.h>
#include <spring_motion/Vertex_role.h>
#include <spring_motion/Vertex_role_map.h>
#include <spring_motion/mesh_traits/Simplicial_mesh_traits.h>

namespace spring_motion {

/// Moves the interior of `mesh` while the motion carries its moving vertices
/// through `options.number_of_steps` increments (docs/method.md, "Time stepping and substepping"), and
/// writes the final positions (the last valid state if a step inverted an
/// element) back into the mesh.
///
/// `role` maps each vertex (`Vertex_info<D>`) to its Vertex_role, for
/// instance `moving_boundary_where(pred)`, `Moving_boundary_labels{{1}}` or
/// `Boundary_label_roles`; or it reads the roles from property maps over the
/// mesh's vertex handles: `vertex_role_map(map)`,
/// `constrained_vertex_maps(moving, is_constrained)` (Vertex_role_map.h);
/// `motion` is a `Motion`, `model` an edge or element stiffness model.
///
/// After deform() a triangulation is a valid simplicial mesh but in general
/// no longer Delaunay: do not `insert()` into it or `locate()` in it.
template <class Mesh, class Role_function, class Motion, class Model, class Visitor = Default_deform_visitor,
          class Traits = Simplicial_mesh_traits<Mesh>>
Deform_report deform(Mesh& mesh, const Role_function& role, const Motion& motion, const Model& model,
                     const Deform_options& options = {}, Visitor visitor = {})
{
  constexpr int D = Traits::dimension;
  auto extracted = extract_spring_network<Mesh, Traits>(mesh);
  auto roles = assign_roles(extracted, role);
  Network_deformer<D> deformer(std::move(extracted.network), std::move(roles));
  Deform_report report = deformer.run(motion, model, options, visitor);
  extracted.write_back(mesh, deformer.positions());
  return report;
}

} // namespace spring_motion

#endif
