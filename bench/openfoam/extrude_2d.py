#!/usr/bin/python3
# Copyright (c) 2026 SpringMotion developers.
"""Extrude a 2D Gmsh triangle mesh one cell deep, for gmshToFoam.

gmshToFoam reads only 3D meshes, so the 2D mesh (z = 0) becomes one layer of
prisms from z = 0 to z = DEPTH with the same nodes: node k of the input is
node k at z = 0 and node k + N at z = DEPTH. Every labelled boundary edge
becomes a quadrangle of the same physical group; the triangles at z = 0 and
z = DEPTH form the physical surface "frontAndBack" (an `empty` patch in
OpenFOAM). Written as ASCII Gmsh 2.2, the format gmshToFoam reads.

    /usr/bin/python3 extrude_2d.py IN.msh OUT.msh [--depth 0.1]
"""
import argparse

import gmsh


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("input")
    parser.add_argument("output")
    parser.add_argument("--depth", type=float, default=0.1)
    args = parser.parse_args()

    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.open(args.input)
    tags, coords, _ = gmsh.model.mesh.getNodes()
    xyz = {int(t): (coords[3 * i], coords[3 * i + 1], coords[3 * i + 2]) for i, t in enumerate(tags)}
    index = {t: i + 1 for i, t in enumerate(sorted(xyz))}  # 1-based, dense
    n = len(index)

    groups = []  # (dimension, tag, name, list of node tuples)
    for dim, ptag in gmsh.model.getPhysicalGroups():
        name = gmsh.model.getPhysicalName(dim, ptag)
        elems = []
        for entity in gmsh.model.getEntitiesForPhysicalGroup(dim, ptag):
            etypes, _, enodes = gmsh.model.mesh.getElements(dim, entity)
            for etype, nodes in zip(etypes, enodes):
                k = {1: 2, 2: 3}[int(etype)]  # lines, triangles only
                elems += [tuple(index[int(v)] for v in nodes[i:i + k]) for i in range(0, len(nodes), k)]
        groups.append((dim, ptag, name, elems))
    gmsh.finalize()

    for v in xyz.values():
        if abs(v[2]) > 0:
            raise SystemExit("extrude_2d.py: %s is not a 2D mesh (z != 0)" % args.input)

    pts = [None] * (n + 1)
    for t, i in index.items():
        pts[i] = xyz[t]

    def area2(tri):
        (ax, ay, _), (bx, by, _), (cx, cy, _) = (pts[v] for v in tri)
        return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)

    lines = []
    names = []
    next_tag = max(g[1] for g in groups) + 1
    front_back = next_tag
    for dim, ptag, name, elems in groups:
        if dim == 1:
            names.append((2, ptag, name))
            for a, b in elems:
                lines.append((3, ptag, (a, b, b + n, a + n)))
        elif dim == 2:
            names.append((3, ptag, name))
            for tri in elems:
                if area2(tri) < 0:  # prisms need the bottom triangle counter-clockwise
                    tri = (tri[0], tri[2], tri[1])
                lines.append((6, ptag, tri + tuple(v + n for v in tri)))
                lines.append((2, front_back, tri))
                lines.append((2, front_back, tuple(v + n for v in tri)))
    names.append((2, front_back, "frontAndBack"))

    with open(args.output, "w") as out:
        out.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n")
        out.write("$PhysicalNames\n%d\n" % len(names))
        for dim, tag, name in names:
            out.write('%d %d "%s"\n' % (dim, tag, name))
        out.write("$EndPhysicalNames\n$Nodes\n%d\n" % (2 * n))
        for layer, z in ((0, 0.0), (n, args.depth)):
            for i in range(1, n + 1):
                out.write("%d %.17g %.17g %.17g\n" % (i + layer, pts[i][0], pts[i][1], z))
        out.write("$EndNodes\n$Elements\n%d\n" % len(lines))
        for k, (etype, tag, nodes) in enumerate(lines, 1):
            out.write("%d %d 2 %d %d %s\n" % (k, etype, tag, tag, " ".join(map(str, nodes))))
        out.write("$EndElements\n")
    print("%s: %d nodes, %d prisms" % (args.output, 2 * n, sum(1 for e in lines if e[0] == 6)))


if __name__ == "__main__":
    main()
