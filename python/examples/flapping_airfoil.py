#!/usr/bin/python3
"""A flapping NACA0012 airfoil: its surface bends with a prescribed mode
shape, A sin(2 pi t / T) * ((x - x_le) / c)^2 normal to the chord, and the
mesh follows; written as a ParaView time series (.pvd + one .vtu per frame).

A flow solver's loop: one `spring_motion.Deformer` is built once, and each
frame (time step) gives it the surface's displacement from its initial
position; the mesh moves from the previous frame's state, a step that would
invert an element is retried in up to 2^`--substep-halvings` substeps, and
the positions are read without a copy (python/README.md).

    PYTHONPATH=build/python /usr/bin/python3 python/examples/flapping_airfoil.py --out flapping
    paraview flapping/flapping.pvd
"""
import argparse
import math
import os
import pathlib
import sys
import xml.etree.ElementTree as ET

import numpy as np

import spring_motion as sm


def write_pvd(path, entries):
    """A ParaView collection listing (time, file) pairs, files relative to the .pvd."""
    root = ET.Element("VTKFile", type="Collection", version="0.1")
    collection = ET.SubElement(root, "Collection")
    for time, name in entries:
        ET.SubElement(collection, "DataSet", timestep=repr(time), part="0", file=name)
    tmp = str(path) + ".tmp"
    ET.ElementTree(root).write(tmp, xml_declaration=True, encoding="utf-8")
    os.replace(tmp, path)


def main(argv=None):
    repository = pathlib.Path(__file__).resolve().parents[2]
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--mesh", default=str(repository / "data" / "naca0012_2d.msh"))
    p.add_argument("--surface", default="airfoil", help="label (number or name) of the flapping surface")
    p.add_argument("--amplitude", type=float, default=0.08, help="tip displacement, in chords")
    p.add_argument("--frames", type=int, default=24, help="frames per period")
    p.add_argument("--substep-halvings", type=int, default=4,
                   help="an inverting frame is retried in 2, 4, ... 2^K substeps")
    p.add_argument("--out", default="flapping", help="output directory")
    args = p.parse_args(argv)

    mesh = sm.read_mesh(args.mesh)
    label = int(args.surface) if args.surface.lstrip("-").isdigit() else args.surface
    number = next((n for n, name in mesh.label_names.items() if name == label), label)
    surface = np.unique(mesh.boundary_facets[mesh.boundary_labels == number])
    if surface.size == 0:
        sys.exit("%s: no boundary facet labelled %r" % (args.mesh, args.surface))
    x = mesh.points[surface, 0]
    leading, chord = x.min(), x.max() - x.min()
    mode = np.zeros_like(mesh.points)
    mode[surface, 1] = ((x - leading) / chord) ** 2  # first bending mode, clamped at the leading edge

    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    deformer = sm.Deformer(mesh, moving=label, max_substep_halvings=args.substep_halvings)
    moving = deformer.moving_vertices
    entries = []
    for frame in range(args.frames + 1):
        time = frame / args.frames  # one period
        displacement = args.amplitude * chord * math.sin(2 * math.pi * time) * mode
        if frame > 0:
            step = deformer.move(displacement[moving])
            if not step.valid:
                sys.exit("frame %d inverted %d element(s) even in %d substeps; try a smaller --amplitude"
                         % (frame, step.inverted, step.substeps))
            print("frame %d/%d: %d iterations, worst R %.3f near the surface, min size ratio %.3f" % (
                frame, args.frames, step.iterations, step.max_skewness_moving, step.min_size_ratio))
        positions = deformer.positions  # a read-only view: no copy
        name = "flapping_%04d.vtu" % frame
        sm.write_mesh(out / name, mesh, positions, point_data={"displacement": positions - mesh.points})
        entries.append((time, name))
        write_pvd(out / "flapping.pvd", entries)  # valid after every frame
    print("wrote %s (%d frames)" % (out / "flapping.pvd", len(entries)))


if __name__ == "__main__":
    main()
