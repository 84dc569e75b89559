#!/usr/bin/python3
# Copyright (c) 2026 SpringMotion developers.
"""Writes the benchmark's box as a Medit mesh, for runs of `spring-motion`
on it outside the benchmark (which writes it, runs the program twice and
deletes it: a few hundred MB).

    bench/box_mesh.py N OUT.mesh

The unit cube cut into N^3 cells of six tetrahedra each, without the cells
of a centred block of side about N/4 (the moving body): the vertices, the
tetrahedra and their numbering as the benchmark's box case makes them, the
block's surface labelled 1 and the cube's faces 2. For instance
(N = 100: 5.9 million tetrahedra, about a minute):

    bench/box_mesh.py 100 box.mesh
    spring-motion deform box.mesh --moving 1 --pitch 1 --center 0.5,0.5,0.5 --steps 6 --report r.json
"""
import os
import sys

import numpy as np


def box(n):
    m = n + 1
    lo = (3 * n) // 8
    hi = lo + max(1, n // 4)
    # grid points with i fastest, then j, then k, as the benchmark numbers them
    k, j, i = (a.ravel() for a in np.meshgrid(np.arange(m), np.arange(m), np.arange(m), indexing="ij"))
    inside = (i > lo) & (i < hi) & (j > lo) & (j < hi) & (k > lo) & (k < hi)
    ids = np.full(m ** 3, -1, dtype=np.int64)
    ids[~inside] = np.arange(np.count_nonzero(~inside))
    points = np.stack([i[~inside], j[~inside], k[~inside]], 1) / n
    ck, cj, ci = (a.ravel() for a in np.meshgrid(np.arange(n), np.arange(n), np.arange(n), indexing="ij"))
    block = (ci >= lo) & (ci < hi) & (cj >= lo) & (cj < hi) & (ck >= lo) & (ck < hi)
    cells = [ci[~block], cj[~block], ck[~block]]
    # each cell's six tetrahedra: paths from its corner (i, j, k) along the
    # axes in every order, the odd permutations' last two corners swapped so
    # that every tetrahedron is positively oriented
    paths = [((0, 1, 2), False), ((0, 2, 1), True), ((1, 0, 2), True), ((1, 2, 0), False), ((2, 0, 1), False),
             ((2, 1, 0), True)]
    tets = []
    for order, odd in paths:
        v = [c.copy() for c in cells]
        corners = [ids[(v[2] * m + v[1]) * m + v[0]]]
        for axis in order:
            v[axis] = v[axis] + 1
            corners.append(ids[(v[2] * m + v[1]) * m + v[0]])
        if odd:
            corners[2], corners[3] = corners[3], corners[2]
        tets.append(np.stack(corners, 1))
    tets = np.stack(tets, 1).reshape(-1, 4)  # a cell's six together, cells in order
    # boundary facets: those of one tetrahedron only
    faces = np.concatenate([tets[:, [1, 2, 3]], tets[:, [0, 3, 2]], tets[:, [0, 1, 3]], tets[:, [0, 2, 1]]])
    _, inverse, count = np.unique(np.sort(faces, 1), axis=0, return_inverse=True, return_counts=True)
    facets = faces[count[inverse] == 1]
    centre = points[facets].mean(1)
    eps = 0.25 / n
    outer = ((centre < eps) | (centre > 1 - eps)).any(1)
    return points, tets, facets, np.where(outer, 2, 1)


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: box_mesh.py N OUT.mesh")
    n = int(sys.argv[1])
    if n < 4:
        sys.exit("box_mesh.py: N must be at least 4, got %d" % n)
    points, tets, facets, labels = box(n)
    out = sys.argv[2]
    part = out + ".part"  # renamed once complete: no half-written mesh under the name asked for
    with open(part, "w") as f:
        f.write("MeshVersionFormatted 2\n\nDimension 3\n\n# label 1: the block, 2: the cube's faces\n")
        f.write("\nVertices\n%d\n" % len(points))
        np.savetxt(f, np.c_[points, np.zeros(len(points))], fmt="%.17g %.17g %.17g %d")
        f.write("\nTetrahedra\n%d\n" % len(tets))
        np.savetxt(f, np.c_[tets + 1, np.full(len(tets), 10)], fmt="%d")
        f.write("\nTriangles\n%d\n" % len(facets))
        np.savetxt(f, np.c_[facets + 1, labels], fmt="%d")
        f.write("\nEnd\n")
    os.replace(part, out)
    print("%s: %d vertices, %d tetrahedra, %d boundary triangles (%d on the block)"
          % (out, len(points), len(tets), len(facets), np.count_nonzero(labels == 1)))


if __name__ == "__main__":
    main()
