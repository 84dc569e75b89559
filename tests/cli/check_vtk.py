#!/usr/bin/env python3
"""Validates VTK XML files written by spring-motion with xml.etree.

usage: check_vtk.py FILE.vtu|FILE.pvd --points N --cells M [--cell-type T]
                    [--frames F] [--arrays]

A .vtu must be a well-formed UnstructuredGrid with one Piece of N points and
M cells; every DataArray must hold exactly (number of tuples) x
NumberOfComponents finite numbers (points: 3 components; connectivity
(D+1) M; offsets M, increasing by D+1; types M, all T). With --arrays the
point array 'displacement' and the cell arrays 'skewness' (in [0, 1]),
'valid' (0 or 1) and 'label' must be present, and each cell's skewness must
be its R (Eq. 13) recomputed here from the written points: interior angles
by the law of cosines (triangles), dihedral angles between face normals
(tetrahedra). A .pvd must be a Collection
of F DataSets with increasing timesteps, each file a valid .vtu as above.
"""
import argparse
import math
import os
import sys
import xml.etree.ElementTree as ET


def fail(msg):
    sys.exit("check_vtk.py: " + msg)


def numbers(array, path):
    try:
        return [float(x) for x in (array.text or "").split()]
    except ValueError:
        fail("%s: non-numeric value in DataArray %s" % (path, array.get("Name")))


def sub(p, q):
    return [p[0] - q[0], p[1] - q[1], p[2] - q[2]]


def dot(u, v):
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]


def cross(u, v):
    return [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]


def angle(u, v):
    c = dot(u, v) / math.sqrt(dot(u, u) * dot(v, v))
    return math.acos(max(-1.0, min(1.0, c)))


def skewness(corners):
    """R of a triangle (interior angles) or a tetrahedron (dihedral angles)."""
    if len(corners) == 3:
        angles = [angle(sub(corners[(k + 1) % 3], corners[k]), sub(corners[(k + 2) % 3], corners[k]))
                  for k in range(3)]
        ideal = math.pi / 3
    else:
        angles = []
        for i in range(4):
            for j in range(i + 1, 4):
                # at edge e = (k, l): e x u turns the part of u across e by a
                # right angle about e, so the angle between e x (j - k) and
                # e x (i - k) is the one between the half-planes through j and i
                k, l = (v for v in range(4) if v not in (i, j))
                e = sub(corners[l], corners[k])
                angles.append(angle(cross(e, sub(corners[j], corners[k])), cross(e, sub(corners[i], corners[k]))))
        ideal = math.acos(1 / 3)
    r = max((max(angles) - ideal) / (math.pi - ideal), (ideal - min(angles)) / ideal)
    return min(1.0, max(0.0, r))


def check_skewness(path, points, connectivity, per, written):
    for t, r in enumerate(written):
        corners = [points[3 * int(v):3 * int(v) + 3] for v in connectivity[per * t:per * (t + 1)]]
        expected = skewness(corners)
        if abs(r - expected) > 1e-7:
            fail("%s: cell %d has skewness %r, its points give %r" % (path, t, r, expected))


def check_vtu(path, a):
    root = ET.parse(path).getroot()
    if root.tag != "VTKFile" or root.get("type") != "UnstructuredGrid":
        fail("%s: expected <VTKFile type=\"UnstructuredGrid\">" % path)
    pieces = root.findall("./UnstructuredGrid/Piece")
    if len(pieces) != 1:
        fail("%s: expected one Piece, found %d" % (path, len(pieces)))
    piece = pieces[0]
    n, m = int(piece.get("NumberOfPoints")), int(piece.get("NumberOfCells"))
    if n != a.points or m != a.cells:
        fail("%s: NumberOfPoints %d, NumberOfCells %d; expected %d and %d" % (path, n, m, a.points, a.cells))
    pts = piece.find("./Points/DataArray")
    if pts is None or int(pts.get("NumberOfComponents")) != 3:
        fail("%s: expected a 3-component Points DataArray" % path)
    p = numbers(pts, path)
    if len(p) != 3 * n or not all(math.isfinite(x) for x in p):
        fail("%s: Points holds %d values, expected %d finite ones" % (path, len(p), 3 * n))
    cells = {d.get("Name"): d for d in piece.findall("./Cells/DataArray")}
    for name in ("connectivity", "offsets", "types"):
        if name not in cells:
            fail("%s: Cells lacks the %s array" % (path, name))
    conn, offs, types = (numbers(cells[k], path) for k in ("connectivity", "offsets", "types"))
    per = 4 if a.cell_type == 10 else 3
    if len(conn) != per * m or len(offs) != m or len(types) != m:
        fail("%s: connectivity/offsets/types sizes %d/%d/%d, expected %d/%d/%d"
             % (path, len(conn), len(offs), len(types), per * m, m, m))
    if any(o != per * (i + 1) for i, o in enumerate(offs)):
        fail("%s: offsets are not %d, %d, ..." % (path, per, 2 * per))
    if any(t != a.cell_type for t in types):
        fail("%s: cell types other than %d" % (path, a.cell_type))
    if any(not (0 <= c < n) or c != int(c) for c in conn):
        fail("%s: connectivity index out of range" % path)
    found = {}
    for kind, count in (("PointData", n), ("CellData", m)):
        for d in piece.findall("./%s/DataArray" % kind):
            comps = int(d.get("NumberOfComponents", "1"))
            v = numbers(d, path)
            if len(v) != comps * count:
                fail("%s: %s array %s holds %d values, expected %d x %d"
                     % (path, kind, d.get("Name"), len(v), count, comps))
            found[(kind, d.get("Name"))] = v
    if a.arrays:
        for key in (("PointData", "displacement"), ("CellData", "skewness"), ("CellData", "valid"),
                    ("CellData", "label")):
            if key not in found:
                fail("%s: missing %s array '%s'" % (path, key[0], key[1]))
        if any(not (0 <= r <= 1) for r in found[("CellData", "skewness")]):
            fail("%s: skewness outside [0, 1]" % path)
        check_skewness(path, p, conn, per, found[("CellData", "skewness")])
        if any(v not in (0.0, 1.0) for v in found[("CellData", "valid")]):
            fail("%s: valid is not 0 or 1" % path)
    return found


def main():
    p = argparse.ArgumentParser()
    p.add_argument("file")
    p.add_argument("--points", type=int, required=True)
    p.add_argument("--cells", type=int, required=True)
    p.add_argument("--cell-type", type=int, default=5)
    p.add_argument("--frames", type=int)
    p.add_argument("--arrays", action="store_true")
    a = p.parse_args()
    if a.file.endswith(".pvd"):
        root = ET.parse(a.file).getroot()
        if root.tag != "VTKFile" or root.get("type") != "Collection":
            fail("%s: expected <VTKFile type=\"Collection\">" % a.file)
        sets = root.findall("./Collection/DataSet")
        if a.frames is not None and len(sets) != a.frames:
            fail("%s: %d DataSets, expected %d" % (a.file, len(sets), a.frames))
        times = [float(s.get("timestep")) for s in sets]
        if any(t1 <= t0 for t0, t1 in zip(times, times[1:])):
            fail("%s: timesteps do not increase: %s" % (a.file, times))
        for s in sets:
            check_vtu(os.path.join(os.path.dirname(a.file), s.get("file")), a)
        print("%s: valid Collection of %d UnstructuredGrid files, %d points and %d cells each"
              % (a.file, len(sets), a.points, a.cells))
    else:
        check_vtu(a.file, a)
        print("%s: valid UnstructuredGrid, %d points, %d cells" % (a.file, a.points, a.cells))


main()
