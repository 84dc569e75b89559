#!/usr/bin/env python3
"""Reads spring-motion's VTU / PVD output with VTK's own XML reader (the one
ParaView uses; Debian package python3-vtk9) and checks what it sees.

usage: check_vtk_reader.py FILE.vtu|FILE.pvd --points N --cells M

Fails if VTK reports any error or warning while reading, or if a file does
not have N points, M cells, and the arrays displacement (3 components),
skewness, valid and label. A .pvd is read as ParaView does: each DataSet's
file, relative to the .pvd's directory.
"""
import argparse
import os
import sys
import xml.etree.ElementTree as ET

import vtk


class Errors:
    def __init__(self):
        self.messages = []

    def __call__(self, caller, event):
        self.messages.append(event)


def read(path, a):
    reader = vtk.vtkXMLUnstructuredGridReader()
    errors = Errors()
    reader.AddObserver("ErrorEvent", errors)
    reader.AddObserver("WarningEvent", errors)
    reader.SetFileName(path)
    reader.Update()
    if errors.messages or reader.GetErrorCode() != 0:
        sys.exit("%s: VTK reported %s (error code %d)" % (path, errors.messages, reader.GetErrorCode()))
    grid = reader.GetOutput()
    if grid.GetNumberOfPoints() != a.points or grid.GetNumberOfCells() != a.cells:
        sys.exit("%s: VTK read %d points, %d cells; expected %d and %d"
                 % (path, grid.GetNumberOfPoints(), grid.GetNumberOfCells(), a.points, a.cells))
    d = grid.GetPointData().GetArray("displacement")
    if d is None or d.GetNumberOfComponents() != 3 or d.GetNumberOfTuples() != a.points:
        sys.exit("%s: no 3-component point array 'displacement' of %d tuples" % (path, a.points))
    for name in ("skewness", "valid", "label"):
        c = grid.GetCellData().GetArray(name)
        if c is None or c.GetNumberOfTuples() != a.cells:
            sys.exit("%s: no cell array '%s' of %d tuples" % (path, name, a.cells))
    r = grid.GetCellData().GetArray("skewness").GetRange()
    if r[0] < 0 or r[1] > 1:
        sys.exit("%s: skewness range %s outside [0, 1]" % (path, r))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("file")
    p.add_argument("--points", type=int, required=True)
    p.add_argument("--cells", type=int, required=True)
    a = p.parse_args()
    if a.file.endswith(".pvd"):
        sets = ET.parse(a.file).getroot().findall("./Collection/DataSet")
        for s in sets:
            read(os.path.join(os.path.dirname(a.file), s.get("file")), a)
        print("%s: VTK %s read %d frames of %d points and %d cells"
              % (a.file, vtk.vtkVersion.GetVTKVersion(), len(sets), a.points, a.cells))
    else:
        read(a.file, a)
        print("%s: VTK %s read %d points and %d cells" % (a.file, vtk.vtkVersion.GetVTKVersion(), a.points, a.cells))


main()
