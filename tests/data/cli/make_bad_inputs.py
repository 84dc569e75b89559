#!/usr/bin/env python3
"""Writes the small malformed inputs of the CLI tests (tests/cli) into this
directory. Each is a variation of a 3 x 3 grid of vertices on the unit square
(8 triangles; edge references 1 bottom, 2 right, 3 top, 4 left) or of the
Gmsh files beside it, with one thing wrong. Run: python3 make_bad_inputs.py"""

GRID = [(0, 0), (0.5, 0), (1, 0), (0, 0.5), (0.5, 0.5), (1, 0.5), (0, 1), (0.5, 1), (1, 1)]
TRIS = [(1, 2, 5), (1, 5, 4), (2, 3, 6), (2, 6, 5), (4, 5, 8), (4, 8, 7), (5, 6, 9), (5, 9, 8)]
EDGES = [(1, 2, 1), (2, 3, 1), (3, 6, 2), (6, 9, 2), (9, 8, 3), (8, 7, 3), (7, 4, 4), (4, 1, 4)]


def medit(points=GRID, tris=TRIS, edges=EDGES, vertex_text=None, tri_count=None, extra=""):
    out = ["MeshVersionFormatted 2", "Dimension 2", "Vertices", str(len(points))]
    out += vertex_text or ["%s %s 0" % (x, y) for x, y in points]
    out += ["Triangles", str(len(tris) if tri_count is None else tri_count)]
    out += ["%d %d %d 10" % t for t in tris]
    out += ["Edges", str(len(edges))] + ["%d %d %d" % e for e in edges]
    return "\n".join(out) + "\n" + extra + "End\n"


def write(name, text):
    with open(name, "w") as f:
        f.write(text)


# a valid base, for label and displacement errors
write("grid.mesh", medit())
# the file stops in the middle of the Triangles section
write("bad_truncated.mesh", "\n".join(medit().split("\n")[:17]) + "\n")
# Triangles announces 9 entries but holds 8 (the count is wrong)
write("bad_count.mesh", medit(tri_count=9))
# a triangle uses vertex 12 of 9
write("bad_index.mesh", medit(tris=TRIS[:3] + [(2, 12, 5)] + TRIS[4:]))
# a coordinate that is not a number
write("bad_nonnumeric.mesh", medit(vertex_text=["%s %s 0" % p for p in GRID[:4]] + ["0.5 zero 0"]
                                   + ["%s %s 0" % p for p in GRID[5:]]))
# an infinite coordinate
write("bad_inf.mesh", medit(vertex_text=["%s %s 0" % p for p in GRID[:4]] + ["inf 0.5 0"]
                            + ["%s %s 0" % p for p in GRID[5:]]))
# vertex 5 on the segment from 1 to 2: triangle 1 2 5 has zero area
write("bad_degenerate.mesh", medit(points=GRID[:4] + [(0.25, 0)] + GRID[5:]))
# vertex 5 pushed below the bottom edge: triangles 1 2 5 and 2 6 5 flip
write("bad_inverted.mesh", medit(points=GRID[:4] + [(0.6, -0.2)] + GRID[5:]))
# triangle 2 6 5 listed clockwise: oriented against the other seven, which is allowed (it overlaps nothing)
write("mixed_orientation.mesh", medit(tris=TRIS[:3] + [(2, 5, 6)] + TRIS[4:]))
# two more triangles below the bottom edge 1-2, which three triangles then share (not a manifold)
write("bad_nonmanifold.mesh", medit(points=GRID + [(0.5, -0.5), (0.5, -1)], tris=TRIS + [(2, 1, 10), (2, 1, 11)]))
# two separate squares: the second one touches no moving or fixed boundary when --fixed names only label 4
pts2 = GRID + [(x + 2, y) for x, y in GRID]
tris2 = TRIS + [(a + 9, b + 9, c + 9) for a, b, c in TRIS]
edges2 = EDGES + [(a + 9, b + 9, 5) for a, b, _ in EDGES]
write("two_parts.mesh", medit(points=pts2, tris=tris2, edges=edges2))
# the same, after a first vertex that no triangle uses: the file's vertex numbers are one more than
# the spring network's, so a message must name a vertex as the file does (vertex 11 at (2, 0))
write("two_parts_unused_vertex.mesh", medit(points=[(9, 9)] + pts2, tris=[(a + 1, b + 1, c + 1) for a, b, c in tris2],
                                            edges=[(a + 1, b + 1, r) for a, b, r in edges2]))
# Gmsh 2.2: a NaN coordinate
write("bad_nan.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 nan 1 0\n4 0 1 0\n"
      "$EndNodes\n$Elements\n2\n1 2 2 10 1 1 2 3\n2 2 2 10 1 1 3 4\n$EndElements\n")
# Gmsh 2.2: quadrangles only (type 3)
write("bad_quads.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n"
      "$EndNodes\n$Elements\n1\n1 3 2 10 1 1 2 3 4\n$EndElements\n")
# Gmsh 2.2: a tetrahedron and a triangle that shares no vertex with it
write("bad_mixed.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n7\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n"
      "5 5 5 5\n6 6 5 5\n7 5 6 5\n$EndNodes\n$Elements\n2\n1 4 2 10 1 1 2 3 4\n2 2 2 3 2 5 6 7\n$EndElements\n")
# displacement files for grid.mesh, whose bottom edge (label 1) has vertices 1, 2, 3
write("grid_bottom.txt", "# vertex dx dy: the bottom edge (label 1) moves up\n1 0 0.1\n2 0 0.1\n3 0 0.1\n")
write("bad_displacement_id.txt", "1 0 0.1\n2 0 0.1\n42 0 0.1\n")
write("bad_displacement_values.txt", "1 0 0.1\n2 0.1\n3 0 0.1\n")
write("bad_displacement_missing.txt", "1 0 0.1\n3 0 0.1\n")
write("bad_extension.stl", "solid nothing\nendsolid nothing\n")
