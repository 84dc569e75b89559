// Copyright (c) 2026 SpringMotion developers.
// Convenience header: the whole public API.
#ifndef SPRING_MOTION_SPRING_MOTION_H
#define SPRING_MOTION_SPRING_MOTION_H

#include <spring_motion/Boundary_plane.h>
#include <spring_motion/Deform_report.h>
#include <spring_motion/Error.h>
#include <spring_motion/Spring_network.h>
#include <spring_motion/Vertex_role.h>
#include <spring_motion/Vertex_role_map.h>
#include <spring_motion/deform.h>
#include <spring_motion/mesh_traits/Indexed_mesh.h>
#include <spring_motion/mesh_traits/Mesh_complex_3_in_triangulation_3.h>
#include <spring_motion/mesh_traits/Surface_mesh.h>
#include <spring_motion/mesh_traits/Triangulation_2.h>
#include <spring_motion/mesh_traits/Triangulation_3.h>
#include <spring_motion/motion/Pitch_motion.h>
#include <spring_motion/skewness.h>
#include <spring_motion/stiffness/Ball_vertex_stiffness.h>
#include <spring_motion/stiffness/Blom_semi_torsional_stiffness.h>
#include <spring_motion/stiffness/Grid_scaled_stiffness.h>
#include <spring_motion/stiffness/Lineal_stiffness.h>
#include <spring_motion/stiffness/Torsional_stiffness.h>
#include <spring_motion/stiffness/With_ball_vertex.h>
#include <spring_motion/stiffness/Zeng_Ethier_semi_torsional_stiffness.h>
#include <spring_motion/validity.h>

#endif
