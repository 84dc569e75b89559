#!/usr/bin/python3
"""Writes a structured tetrahedral box with a cubic hole as a Medit file, for
benchmarks at a million vertices (bench/petsc_scaling.sh): the unit cube cut
into N^3 cubes of six tetrahedra each (Kuhn's subdivision, all around the
cube's main diagonal), without the cubes of the hole [0.4, 0.6]^3. The hole's
surface is labelled 1 (the body that moves), the outer surface 2.

    make_box_mesh.py N OUT.mesh       (N = 100: 1.03 million vertices, 5.95 million tetrahedra)
"""
import os
import sys

import numpy as np


def main():
    n, out = int(sys.argv[1]), sys.argv[2]
    if n < 5 or n % 5:
        sys.exit("make_box_mesh.py: expected N a multiple of 5 (the hole's faces on grid planes), got %d" % n)
    lo, hi = 2 * n // 5, 3 * n // 5  # the hole: cubes [lo, hi)^3
    m = n + 1
    i, j, k = np.meshgrid(np.arange(n), np.arange(n), np.arange(n), indexing="ij")
    keep = ~((i >= lo) & (i < hi) & (j >= lo) & (j < hi) & (k >= lo) & (k < hi))
    i, j, k = i[keep], j[keep], k[keep]

    def corner(b):
        return ((k + ((b >> 2) & 1)) * m + (j + ((b >> 1) & 1))) * m + (i + (b & 1))

    tets = []
    for p in ((0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)):
        a = 1 << p[0]
        b = a | (1 << p[1])
        tets.append(np.stack([corner(0), corner(a), corner(b), corner(7)], axis=1))
    tets = np.concatenate(tets)
    # vertices some tetrahedron uses, numbered from 1 in grid order
    used = np.zeros(m ** 3, dtype=bool)
    used[tets.ravel()] = True
    number = np.cumsum(used)
    g = np.nonzero(used)[0]
    pts = np.stack([g % m, (g // m) % m, g // (m * m)], axis=1) / n

    # boundary triangles: each square face split along its diagonal from the
    # smallest to the largest corner, as the tetrahedra split it
    def squares(axis, plane, u0, u1, v0, v1):
        u, v = np.meshgrid(np.arange(u0, u1), np.arange(v0, v1), indexing="ij")
        u, v = u.ravel(), v.ravel()
        axes = [a for a in range(3) if a != axis]

        def vid(du, dv):
            c = [None] * 3
            c[axis] = np.full(u.shape, plane)
            c[axes[0]], c[axes[1]] = u + du, v + dv
            return (c[2] * m + c[1]) * m + c[0]

        s, e, a, b = vid(0, 0), vid(1, 1), vid(1, 0), vid(0, 1)
        return np.concatenate([np.stack([s, a, e], axis=1), np.stack([s, b, e], axis=1)])

    outer = np.concatenate([squares(ax, pl, 0, n, 0, n) for ax in range(3) for pl in (0, n)])
    hole = np.concatenate([squares(ax, pl, lo, hi, lo, hi) for ax in range(3) for pl in (lo, hi)])
    tmp = out + ".part"
    with open(tmp, "w") as f:
        f.write("MeshVersionFormatted 2\nDimension 3\nVertices\n%d\n" % len(pts))
        np.savetxt(f, np.column_stack([pts, np.zeros(len(pts))]), fmt="%.17g %.17g %.17g %d")
        f.write("Triangles\n%d\n" % (len(outer) + len(hole)))
        for tri, ref in ((hole, 1), (outer, 2)):
            np.savetxt(f, np.column_stack([number[tri], np.full(len(tri), ref)]), fmt="%d")
        f.write("Tetrahedra\n%d\n" % len(tets))
        np.savetxt(f, np.column_stack([number[tets], np.zeros(len(tets), dtype=int)]), fmt="%d")
        f.write("End\n")
    os.replace(tmp, out)
    print("%s: %d vertices, %d tetrahedra, %d hole triangles" % (out, len(pts), len(tets), len(hole)))


if __name__ == "__main__":
    main()
