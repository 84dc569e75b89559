#!/usr/bin/python3
# Copyright (c) 2026 SpringMotion developers.
"""The tetrahedra with the smallest dihedral angles among those touching a
body, and how many of their vertices lie on the body.

    /usr/bin/python3 scripts/near_wall_angles.py MESH --body LABEL [--deformed OUT.vtu] [--count N] [--below DEG]

MESH: a Medit .mesh or Gmsh .msh (what `spring-motion deform` reads); LABEL:
the body's boundary label (Medit reference or Gmsh physical tag, a number).
With --deformed, the angles are those of a `spring-motion deform --output
OUT.vtu` result of that mesh (its points in the input's order), each printed
beside its value in MESH. A tetrahedron whose four vertices are all on the
body moves rigidly with it: no mesh motion changes its angles, so they bound
what any model can keep next to the body. Prints the N (default 10)
smallest, and how many touching tetrahedra are below DEG (default 8), with
and without those rigid ones.
"""
import argparse
import sys

import meshio
import numpy as np


def dihedral_angles(points, tets):
    """The six dihedral angles (degrees) of each tetrahedron, from its face normals."""
    x = points[tets]
    normals = []
    for face, opposite in (((1, 2, 3), 0), ((0, 2, 3), 1), ((0, 1, 3), 2), ((0, 1, 2), 3)):
        p, q, r = (x[:, i] for i in face)
        n = np.cross(q - p, r - p)
        # outward: away from the opposite vertex
        n *= -np.sign(np.einsum("ij,ij->i", n, x[:, opposite] - p))[:, None]
        normals.append(n / np.linalg.norm(n, axis=1)[:, None])
    pairs = [(i, j) for i in range(4) for j in range(i + 1, 4)]
    return np.stack([180 - np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", normals[i], normals[j]), -1, 1)))
                     for i, j in pairs], axis=1)


def body_vertices(mesh, label):
    on = np.zeros(len(mesh.points), bool)
    keys = ("medit:ref", "gmsh:physical")
    for k, block in enumerate(mesh.cells):
        if block.type != "triangle":
            continue
        tags = next((mesh.cell_data[key][k] for key in keys if key in mesh.cell_data), None)
        if tags is None:
            raise SystemExit("near_wall_angles.py: the mesh's triangles carry no labels")
        on[block.data[np.asarray(tags) == label].ravel()] = True
    if not on.any():
        raise SystemExit(f"near_wall_angles.py: no boundary triangle has label {label}")
    return on


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("mesh")
    ap.add_argument("--body", type=int, required=True)
    ap.add_argument("--deformed")
    ap.add_argument("--count", type=int, default=10)
    ap.add_argument("--below", type=float, default=8.0)
    args = ap.parse_args()

    mesh = meshio.read(args.mesh)
    tets = np.concatenate([b.data for b in mesh.cells if b.type == "tetra"])
    on = body_vertices(mesh, args.body)
    on_count = on[tets].sum(axis=1)
    touching = np.nonzero(on_count > 0)[0]
    initial = dihedral_angles(mesh.points, tets[touching])
    angles = initial
    if args.deformed:
        out = meshio.read(args.deformed)
        if len(out.points) != len(mesh.points):
            raise SystemExit(f"near_wall_angles.py: {args.deformed} has {len(out.points)} points, "
                             f"{args.mesh} {len(mesh.points)}")
        angles = dihedral_angles(out.points, tets[touching])
    smallest = angles.min(axis=1)
    rigid = on_count[touching] == 4
    print(f"{len(touching)} tetrahedra touch label {args.body}; {int(rigid.sum())} have all four vertices on it")
    print(f"below {args.below:g} degrees: {int((smallest < args.below).sum())}, of which "
          f"{int((smallest[rigid] < args.below).sum())} with all four vertices on the body; smallest without "
          f"those: {smallest[~rigid].min():.2f}" if (~rigid).any() else "")
    print(f"{'tet':>8} {'min deg':>8} {'initial':>8} {'on body':>7}  centroid")
    for i in np.argsort(smallest)[:args.count]:
        c = mesh.points[tets[touching[i]]].mean(axis=0)
        print(f"{touching[i]:8d} {smallest[i]:8.2f} {initial[i].min():8.2f} {on_count[touching[i]]:7d}  "
              f"({c[0]:.3f}, {c[1]:.3f}, {c[2]:.3f})")


if __name__ == "__main__":
    sys.exit(main())
