#!/usr/bin/python3
"""Writes a copy of a little-endian binary Gmsh 4.1 mesh whose first node
inside a surface (2D) or volume (3D) entity is moved to (X, Y, Z): a mesh with
inverted elements, for the errors that name binary offsets.

usage: displace_binary_node.py IN.msh OUT.msh X,Y,Z
"""
import struct
import sys

data = bytearray(open(sys.argv[1], "rb").read())
target = [float(v) for v in sys.argv[3].split(",")]
if not data[data.index(b"$MeshFormat\n") + 12:].startswith(b"4.1 1 8"):
    sys.exit("expected a binary Gmsh 4.1 file with 8-byte size_t")
at = data.index(b"$Nodes\n") + len(b"$Nodes\n")
blocks, nodes, _, _ = struct.unpack_from("<4Q", data, at)
at += 32
# the dimension of the mesh is the largest entity dimension holding nodes
entities, k = [], at
for _ in range(blocks):
    edim, _, parametric, n = struct.unpack_from("<iiiQ", data, k)
    if parametric:
        sys.exit("parametric nodes are not handled")
    entities.append((edim, k + 20 + 8 * n, n))
    k += 20 + 8 * n + 24 * n
top = max(e[0] for e in entities)
for edim, coordinates, n in entities:
    if edim == top and n > 0:
        struct.pack_into("<3d", data, coordinates, *target)
        break
else:
    sys.exit("no node inside the domain")
open(sys.argv[2], "wb").write(data)
