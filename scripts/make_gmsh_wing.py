#!/usr/bin/python3
# Copyright (c) 2026 SpringMotion developers.
"""The paper's 3D case as a Gmsh mesh: a NACA0012 wing in a sphere.

Wing: NACA0012 section with a closed trailing edge (the same y_t(x) as
data/naca0012_2d.geo), chord 1, span 2 (z from -1 to 1), flat tips. Far field:
the sphere of radius 15 centred at (0.5, 0, 0). The fluid volume between them
is meshed with tetrahedra of size h(p) = SIZE_AT_WING + SIZE_GROWTH d(p), d the
distance to the wing, which with the defaults gives about the paper's 57924
nodes and 308850 tetrahedra: 58170 nodes, 349335 tetrahedra, 3081 wing nodes,
smallest dihedral angle 6.4 degrees (--half: 31024 nodes, 176491 tetrahedra),
in about 30 s of CPU time. The numbers are printed.

Physical groups: surfaces "wing" (1) and "farfield" (2), volume "fluid" (10);
with --half the wing spans z from 0 to 1 in the half sphere z >= 0 and the
plane z = 0 is the surface group "symmetry" (3).

Written as ASCII Gmsh 4.1 (which spring-motion reads, docs/cli.md) unless
--format msh22 is given (gmshToFoam of older OpenFOAM versions wants 2.2).
Deterministic: one thread, fixed random seed and fixed algorithms, so two runs
write the same file.

Uses Debian 12's python3-gmsh (Gmsh 4.8):
    /usr/bin/python3 scripts/make_gmsh_wing.py wing.msh [--half] [--format msh22]
"""
import argparse
import math
import sys
import time

import gmsh

N_SECTION = 60  # points per surface, cosine spaced (the 2D .geo has 50)


def naca0012_half_thickness(x):
    # -0.1036: closed trailing edge, as in data/naca0012_2d.geo
    return 0.6 * (0.2969 * math.sqrt(x) - 0.1260 * x - 0.3516 * x**2
                  + 0.2843 * x**3 - 0.1036 * x**4)


def section_curves(occ, z):
    """Upper and lower splines of the section in the plane z, closed loop."""
    te = occ.addPoint(1, 0, z)
    le = occ.addPoint(0, 0, z)
    upper, lower = [te], [le]
    for i in range(1, N_SECTION):
        x = 0.5 * (1 + math.cos(math.pi * i / N_SECTION))  # trailing -> leading edge
        upper.append(occ.addPoint(x, naca0012_half_thickness(x), z))
    upper.append(le)
    for i in range(N_SECTION - 1, 0, -1):
        x = 0.5 * (1 + math.cos(math.pi * i / N_SECTION))  # leading -> trailing edge
        lower.append(occ.addPoint(x, -naca0012_half_thickness(x), z))
    lower.append(te)
    return occ.addCurveLoop([occ.addSpline(upper), occ.addSpline(lower)])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("output", help="the .msh file to write")
    parser.add_argument("--half", action="store_true",
                        help="half-span wing (z from 0 to 1) on the symmetry plane z = 0")
    parser.add_argument("--format", choices=["msh41", "msh22"], default="msh41")
    parser.add_argument("--size-at-wing", type=float, default=0.04)
    parser.add_argument("--size-growth", type=float, default=0.091)
    parser.add_argument("--size-max", type=float, default=2.5)
    args = parser.parse_args()

    start = time.time()
    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("General.NumThreads", 1)
    gmsh.option.setNumber("Mesh.MaxNumThreads1D", 1)
    gmsh.option.setNumber("Mesh.MaxNumThreads2D", 1)
    gmsh.option.setNumber("Mesh.MaxNumThreads3D", 1)
    gmsh.option.setNumber("Mesh.RandomSeed", 1)
    gmsh.model.add("naca0012_wing")
    occ = gmsh.model.occ

    z0, span = (0.0, 1.0) if args.half else (-1.0, 2.0)
    loop = section_curves(occ, z0)
    section = occ.addPlaneSurface([loop])
    wing = [e[1] for e in occ.extrude([(2, section)], 0, 0, span) if e[0] == 3]
    sphere = occ.addSphere(0.5, 0, 0, 15)
    if args.half:
        box = occ.addBox(-20, -20, 0, 40, 40, 20)
        far, _ = occ.intersect([(3, sphere)], [(3, box)])
        far = [e[1] for e in far]
    else:
        far = [sphere]
    fluid, _ = occ.cut([(3, t) for t in far], [(3, t) for t in wing])
    occ.synchronize()
    fluid = [e[1] for e in fluid]
    if len(fluid) != 1:
        sys.exit("make_gmsh_wing.py: expected one fluid volume, got %d" % len(fluid))

    # Classify the fluid's boundary: the sphere's surface lies at radius 15,
    # the symmetry plane at z = 0 with points far from the wing, the rest is wing.
    wing_s, far_s, sym_s = [], [], []
    for dim, tag in gmsh.model.getBoundary([(3, fluid[0])], oriented=False):
        xmin, ymin, zmin, xmax, ymax, zmax = gmsh.model.getBoundingBox(dim, tag)
        if xmax - xmin > 10:
            if args.half and zmax - zmin < 1e-6:
                sym_s.append(tag)
            else:
                far_s.append(tag)
        else:
            wing_s.append(tag)
    gmsh.model.addPhysicalGroup(2, wing_s, 1)
    gmsh.model.setPhysicalName(2, 1, "wing")
    gmsh.model.addPhysicalGroup(2, far_s, 2)
    gmsh.model.setPhysicalName(2, 2, "farfield")
    if args.half:
        gmsh.model.addPhysicalGroup(2, sym_s, 3)
        gmsh.model.setPhysicalName(2, 3, "symmetry")
    gmsh.model.addPhysicalGroup(3, fluid, 10)
    gmsh.model.setPhysicalName(3, 10, "fluid")

    # h = size_at_wing + size_growth * distance to the wing (the CGAL mesh of
    # src/naca0012_wing_mesh_3.cpp uses the same law); the distance is sampled
    # on the wing's curves and surfaces.
    field = gmsh.model.mesh.field
    dist = field.add("Distance")
    wing_curves = sorted({c[1] for c in gmsh.model.getBoundary([(2, s) for s in wing_s],
                                                              combined=False, oriented=False)})
    field.setNumbers(dist, "EdgesList", wing_curves)
    field.setNumbers(dist, "FacesList", wing_s)
    field.setNumber(dist, "NumPointsPerCurve", 200)
    size = field.add("MathEval")
    field.setString(size, "F", "min(%g, %g + %g * F%d)"
                    % (args.size_max, args.size_at_wing, args.size_growth, dist))
    field.setAsBackgroundMesh(size)
    gmsh.option.setNumber("Mesh.MeshSizeExtendFromBoundary", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
    gmsh.option.setNumber("Mesh.Algorithm", 6)    # Frontal-Delaunay surfaces
    gmsh.option.setNumber("Mesh.Algorithm3D", 1)  # Delaunay
    gmsh.option.setNumber("Mesh.Optimize", 1)
    gmsh.model.mesh.generate(3)

    gmsh.option.setNumber("Mesh.Binary", 0)
    gmsh.option.setNumber("Mesh.SaveAll", 0)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1 if args.format == "msh41" else 2.2)
    gmsh.write(args.output)

    tet_tags, tet_nodes = gmsh.model.mesh.getElementsByType(4)
    tets = len(tet_tags)
    nodes = len(set(tet_nodes))  # getNodes() would also count unused geometry-point nodes
    wing_nodes = set()
    for s in wing_s:
        wing_nodes.update(gmsh.model.mesh.getNodes(2, s, includeBoundary=True)[0])
    gmsh.finalize()
    print("%s: %d nodes, %d tetrahedra, %d wing nodes (paper: 57924 nodes, 308850 tetrahedra), %.1f s"
          % (args.output, nodes, tets, len(wing_nodes), time.time() - start))


if __name__ == "__main__":
    main()
