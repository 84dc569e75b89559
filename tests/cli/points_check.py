#!/usr/bin/python3
"""Checks that mesh files hold the same points, as doubles bit for bit, in the
same order: Medit .mesh, SU2 .su2 and Gmsh 4.1 ASCII .msh (the formats
spring-motion convert writes). 2D files may write z = 0 or no z at all.

usage: points_check.py FILE FILE...
"""
import sys


def medit_points(lines):
    i = next(k for k, l in enumerate(lines) if l.split()[:1] == ["Vertices"])
    n = int(lines[i + 1])
    return [[float(x) for x in l.split()[:-1]] for l in lines[i + 2:i + 2 + n]]


def su2_points(lines):
    dim = int(next(l for l in lines if l.startswith("NDIME=")).split("=")[1])
    i = next(k for k, l in enumerate(lines) if l.startswith("NPOIN="))
    n = int(lines[i].split("=")[1].split()[0])
    return [[float(x) for x in l.split()[:dim]] for l in lines[i + 1:i + 1 + n]]


def gmsh41_points(lines):
    i = lines.index("$Nodes")
    blocks, n = (int(x) for x in lines[i + 1].split()[:2])
    points, k = [], i + 2
    for _ in range(blocks):
        count = int(lines[k].split()[3])
        k += 1 + count  # the block header, then its tags
        points += [[float(x) for x in l.split()] for l in lines[k:k + count]]
        k += count
    if len(points) != n:
        sys.exit(f"$Nodes announces {n} nodes, the blocks hold {len(points)}")
    return points


def points(path):
    lines = [l.strip() for l in open(path)]
    lines = [l for l in lines if l and not l.startswith(("#", "%"))]
    if path.endswith(".mesh"):
        p = medit_points(lines)
    elif path.endswith(".su2"):
        p = su2_points(lines)
    elif path.endswith(".msh"):
        p = gmsh41_points(lines)
    else:
        sys.exit(f"{path}: unknown extension")
    # 2D: drop a z that is 0 everywhere, so files with and without one compare
    if p and all(len(q) == 3 and q[2] == 0.0 for q in p):
        p = [q[:2] for q in p]
    return p


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    first = points(sys.argv[1])
    if not first:
        sys.exit(f"{sys.argv[1]}: no points")
    for path in sys.argv[2:]:
        other = points(path)
        if other != first:
            diff = next((k for k, (a, b) in enumerate(zip(first, other)) if a != b), min(len(first), len(other)))
            sys.exit(f"{path}: {len(other)} points, {sys.argv[1]}: {len(first)}; first difference at point {diff}")
    print(f"{len(sys.argv) - 1} files hold the same {len(first)} points")
