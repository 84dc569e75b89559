#!/usr/bin/python3
# Copyright (c) 2026 SpringMotion developers.
"""Minimum angle (2D) or dihedral angle (3D) and inverted elements of a mesh.

Reads either an OpenFOAM case written by gmshToFoam + moveDynamicMesh (ASCII
polyMesh) or a Medit .mesh written by `spring-motion deform --output`, so that
both tools' meshes are measured by the same code:

    mesh_quality.py foam CASE TIME [--2d]   # TIME's points, constant/polyMesh topology
    mesh_quality.py medit FILE.mesh [REFERENCE.mesh]

An OpenFOAM case of the 2D benchmark is one layer of prisms; its triangles are
the faces of the `empty` patch at z = 0. A 3D case holds only tetrahedra (the
cells gmshToFoam makes of Gmsh tetrahedra); each tetrahedron is rebuilt from
two of its faces. An element is inverted when the sign of its area (2D) or
volume (3D) differs from its sign in the initial mesh (constant/polyMesh, or
the REFERENCE .mesh with the same numbering) - floating point, not the exact
predicates spring-motion uses, which is enough for the inversions this
benchmark meets (they are not borderline). Prints one JSON object.
"""
import json
import re
import sys

import numpy as np


def _foam_body(path):
    """The text between the outermost '(' and ')' of an OpenFOAM list file."""
    with open(path) as f:
        text = f.read()
    # the list starts after the FoamFile header with "N\n(" on its own lines
    m = re.search(r"^\s*(\d+)\s*\n\s*\(\s*\n", text, re.M)
    if not m:
        raise SystemExit("mesh_quality.py: %s: no ASCII list (writeFormat binary?)" % path)
    end = text.rindex(")")
    return int(m.group(1)), text[m.end():end]


def foam_points(path):
    n, body = _foam_body(path)
    pts = np.array(body.replace("(", " ").replace(")", " ").split(), dtype=float).reshape(-1, 3)
    assert len(pts) == n, path
    return pts


def foam_labels(path):
    n, body = _foam_body(path)
    lab = np.array(body.split(), dtype=np.int64)
    assert len(lab) == n, path
    return lab


def foam_faces(path):
    n, body = _foam_body(path)
    faces = [list(map(int, line[line.index("(") + 1:line.rindex(")")].split()))
             for line in body.splitlines() if "(" in line]
    assert len(faces) == n, path
    return faces


def foam_patches(path):
    with open(path) as f:
        text = f.read()
    patches = {}
    for m in re.finditer(r"(\w+)\s*\{([^}]*)\}", text):
        body = m.group(2)
        start = re.search(r"startFace\s+(\d+);", body)
        count = re.search(r"nFaces\s+(\d+);", body)
        if start and count:
            patches[m.group(1)] = (int(start.group(1)), int(count.group(1)))
    return patches


def foam_elements(case, two_d):
    """Element connectivity (triangles at z = 0 or tetrahedra) of the polyMesh."""
    mesh = case + "/constant/polyMesh"
    faces = foam_faces(mesh + "/faces")
    p0 = foam_points(mesh + "/points")
    if two_d:
        start, count = foam_patches(mesh + "/boundary")["frontAndBack"]
        zmid = 0.5 * (p0[:, 2].min() + p0[:, 2].max())
        tris = [faces[f] for f in range(start, start + count) if p0[faces[f][0], 2] < zmid]
        return np.array(tris, dtype=np.int64), p0
    if any(len(f) != 3 for f in faces):
        raise SystemExit("mesh_quality.py: %s: not a tetrahedral mesh" % mesh)
    faces = np.array(faces, dtype=np.int64)
    owner = foam_labels(mesh + "/owner")
    neighbour = foam_labels(mesh + "/neighbour")
    cells = np.concatenate([owner, neighbour])
    face_of = np.concatenate([np.arange(len(owner)), np.arange(len(neighbour))])
    order = np.argsort(cells, kind="stable")
    cells, face_of = cells[order], face_of[order]
    first = np.searchsorted(cells, np.arange(cells[-1] + 1))
    fa, fb = faces[face_of[first]], faces[face_of[first + 1]]
    # the fourth node: the one of face b that face a lacks
    missing = (fb[:, :, None] != fa[:, None, :]).all(axis=2)
    apex = fb[np.arange(len(fb)), missing.argmax(axis=1)]
    return np.column_stack([fa, apex]), p0


def read_medit(path):
    with open(path) as f:
        tokens = f.read().split()
    pos, sections = 0, {}
    while pos < len(tokens):
        key = tokens[pos]
        if key in ("Vertices", "Triangles", "Tetrahedra"):
            n = int(tokens[pos + 1])
            width = {"Vertices": None, "Triangles": 4, "Tetrahedra": 5}[key]
            if key == "Vertices":
                width = sections["dim"] + 1
            data = np.array(tokens[pos + 2:pos + 2 + n * width], dtype=float).reshape(n, width)
            sections[key] = data
            pos += 2 + n * width
        elif key == "Dimension":
            sections["dim"] = int(tokens[pos + 1])
            pos += 2
        else:
            pos += 1
    pts = sections["Vertices"][:, :sections["dim"]]
    if pts.shape[1] == 2:
        pts = np.column_stack([pts, np.zeros(len(pts))])
    if "Tetrahedra" in sections:
        return sections["Tetrahedra"][:, :4].astype(np.int64) - 1, pts, False
    return sections["Triangles"][:, :3].astype(np.int64) - 1, pts, True


def signed_size(elems, pts):
    p = pts[elems]
    if elems.shape[1] == 3:
        a, b = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
        return a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]
    return np.einsum("ij,ij->i", np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), p[:, 3] - p[:, 0])


def min_angle_deg(elems, pts):
    """Smallest interior angle (triangles) or dihedral angle (tetrahedra), unsigned."""
    p = pts[elems]
    best = np.inf
    if elems.shape[1] == 3:
        for i in range(3):
            u = p[:, (i + 1) % 3] - p[:, i]
            v = p[:, (i + 2) % 3] - p[:, i]
            ang = np.arctan2(np.linalg.norm(np.cross(u, v), axis=1), np.einsum("ij,ij->i", u, v))
            best = min(best, ang.min())
    else:
        for i, j, k, l in ((0, 1, 2, 3), (0, 2, 1, 3), (0, 3, 1, 2), (1, 2, 0, 3), (1, 3, 0, 2), (2, 3, 0, 1)):
            e = p[:, j] - p[:, i]
            u = np.cross(e, p[:, k] - p[:, i])  # normals of the two faces at edge ij
            v = np.cross(e, p[:, l] - p[:, i])
            ang = np.arctan2(np.linalg.norm(np.cross(u, v), axis=1), np.einsum("ij,ij->i", u, v))
            best = min(best, ang.min())
    return float(np.degrees(best))


def measure(elems, pts, ref_pts):
    s, s0 = signed_size(elems, pts), signed_size(elems, ref_pts)
    inverted = int(np.count_nonzero(np.sign(s) != np.sign(s0)))
    return {"elements": int(len(elems)), "inverted": inverted, "min_angle_deg": min_angle_deg(elems, pts),
            "kind": "triangle angle" if elems.shape[1] == 3 else "dihedral angle"}


def main(argv):
    if len(argv) >= 3 and argv[0] == "foam":
        case, time = argv[1], argv[2]
        elems, p0 = foam_elements(case, "--2d" in argv)
        pts = foam_points("%s/%s/polyMesh/points" % (case, time)) if time != "0" else p0
        print(json.dumps(measure(elems, pts, p0)))
    elif len(argv) >= 2 and argv[0] == "medit":
        elems, pts, _ = read_medit(argv[1])
        ref = read_medit(argv[2])[1] if len(argv) > 2 else pts
        print(json.dumps(measure(elems, pts, ref)))
    else:
        raise SystemExit(__doc__)


if __name__ == "__main__":
    main(sys.argv[1:])
