#!/usr/bin/env python3
"""Checks that a Medit file written by spring-motion holds exactly the mesh
of a Gmsh 2.2 file: the same coordinates (as doubles, bit for bit), the same
triangles in the same order with their physical tags, the same boundary
lines with theirs.

usage: roundtrip_check.py MESH_V22.msh WRITTEN.mesh
"""
import sys


def read_gmsh22(path):
    tokens = open(path).read().split("\n")
    i = tokens.index("$Nodes")
    n = int(tokens[i + 1])
    tag_index, points = {}, []
    for line in tokens[i + 2:i + 2 + n]:
        w = line.split()
        tag_index[int(w[0])] = len(points)
        points.append((float(w[1]), float(w[2])))
    i = tokens.index("$Elements")
    tris, edges = [], []
    seen = set()
    for line in tokens[i + 2:i + 2 + int(tokens[i + 1])]:
        w = [int(x) for x in line.split()]
        kind, ntags = w[1], w[2]
        label, nodes = (w[3] if ntags else 0), [tag_index[t] for t in w[3 + ntags:]]
        key = (kind, frozenset(nodes))
        if key in seen:  # an element in several physical groups: the first copy counts
            continue
        seen.add(key)
        if kind == 2:
            tris.append((tuple(nodes), label))
        elif kind == 1:
            edges.append((tuple(nodes), label))
    return points, tris, edges


def read_medit(path):
    words = []
    for line in open(path):
        words += line.split("#")[0].split()
    pos, points, tris, edges = 0, [], [], []
    while pos < len(words):
        key = words[pos]
        pos += 1
        if key == "Vertices":
            n = int(words[pos]); pos += 1
            for _ in range(n):
                points.append((float(words[pos]), float(words[pos + 1]))); pos += 3  # x y ref
        elif key in ("Triangles", "Edges"):
            n = int(words[pos]); pos += 1
            k = 3 if key == "Triangles" else 2
            for _ in range(n):
                v = [int(x) - 1 for x in words[pos:pos + k]]
                (tris if key == "Triangles" else edges).append((tuple(v), int(words[pos + k])))
                pos += k + 1
        elif key == "Dimension":
            if words[pos] != "2":
                sys.exit("expected a 2D Medit file")
            pos += 1
        elif key == "MeshVersionFormatted":
            pos += 1
    return points, tris, edges


g, m = read_gmsh22(sys.argv[1]), read_medit(sys.argv[2])
for name, a, b in zip(("points", "triangles", "edges"), g, m):
    if a != b:
        sys.exit("FAIL: %s differ (%d in the Gmsh file, %d in the Medit file)" % (name, len(a), len(b)))
print("same mesh: %d points, %d triangles, %d boundary edges, exactly" % tuple(len(x) for x in g))
