# The per-time-step Deformer: its contract, a loop of move() calls against
# deform() with the same pitch schedule, rollback of an invalid step, the GIL,
# and sliding symmetry planes.
import math
import os
import subprocess

import numpy as np
import pytest

import spring_motion as sm

PLATE = "tests/data/cli/plate_v41.msh"   # 2D; boundary 1 'farfield', 2 'wing'
BOX = "tests/data/cli/box_hole_v41.msh"  # 3D; boundary 1 'body', 2 'outer'
NACA = "data/naca0012_2d.msh"


def rotation_displacement(points, angle_deg, center, axis=(0.0, 0.0, 1.0)):
    """Displacement of `points` turned by angle_deg about center (and axis, 3D; Rodrigues)."""
    a = math.radians(angle_deg)
    c, s = math.cos(a), math.sin(a)
    d = points - np.asarray(center, dtype=float)
    if points.shape[1] == 2:
        turned = np.stack([c * d[:, 0] - s * d[:, 1], s * d[:, 0] + c * d[:, 1]], axis=1)
    else:
        k = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
        turned = d * c + np.cross(k, d) * s + np.outer(d @ k, k) * (1 - c)
    return turned - d


def pitch_angle(amplitude, i, steps):
    """The quarter-sine schedule of deform(pitch=...): alpha(t) = A sin(pi t / 2), t = i / N."""
    return amplitude * math.sin(math.pi * (i / steps) / 2)


def test_the_contract(data):
    mesh = sm.read_mesh(data(PLATE))
    d = sm.Deformer(mesh, moving=["wing"], fixed=None, sliding=None, model="grid_scaled")
    wing = np.unique(mesh.boundary_facets[mesh.boundary_labels == 2])
    assert sorted(d.moving_vertices.tolist()) == wing.tolist()
    assert d.positions.shape == mesh.points.shape
    assert np.array_equal(d.positions, mesh.points)
    view = d.positions
    assert not view.flags.writeable
    with pytest.raises(ValueError):
        view[0, 0] = 1.0
    step = d.move(rotation_displacement(mesh.points[d.moving_vertices], 5, (1.5, 1)))
    assert step.valid and step.inverted == 0 and step.iterations > 0 and step.converged
    assert step.error_estimate <= 1e-6
    assert step.as_dict()["iterations"] == step.iterations
    # the view follows the deformer: no copy
    assert not np.array_equal(view, mesh.points)
    assert np.array_equal(view, d.positions)
    d.reset()
    assert np.array_equal(view, mesh.points)


def test_bad_displacements_raise_value_errors(data):
    mesh = sm.read_mesh(data(PLATE))
    d = sm.Deformer(mesh, moving="wing")
    n = len(d.moving_vertices)
    with pytest.raises(ValueError, match=r"expected an array of shape \(%d, 2\)" % n):
        d.move(np.zeros((n + 1, 2)))
    bad = np.zeros((n, 2))
    bad[3, 1] = np.nan
    with pytest.raises(ValueError, match="row 3 is not finite"):
        d.move(bad)
    with pytest.raises(sm.Input_error, match="unknown label 'keel'"):
        sm.Deformer(mesh, moving="keel")
    with pytest.raises(ValueError, match="unknown stiffness model"):
        sm.Deformer(mesh, moving="wing", model="rubber")


@pytest.mark.parametrize("mesh_name, moving, center, axis, model", [
    (NACA, "airfoil", (0.25, 0.0), None, "grid_scaled"),
    (BOX, "body", (1.0, 1.0, 1.0), (1.0, 1.0, 0.0), "grid_scaled"),
    (PLATE, "wing", (1.5, 1.0), None, "ball_vertex"),
])
def test_a_loop_of_moves_reproduces_deform(data, mesh_name, moving, center, axis, model):
    mesh = sm.read_mesh(data(mesh_name))
    steps, amplitude, tol = 12, 20.0, 1e-10
    kw = dict(axis=axis) if axis else {}
    expected, report = sm.deform(mesh, moving=moving, model=model, pitch=amplitude, center=center, steps=steps,
                                 tolerance=tol, **kw)
    assert report["completed"]
    d = sm.Deformer(mesh, moving=moving, model=model, tolerance=tol)
    p0 = mesh.points[d.moving_vertices]
    for i in range(1, steps + 1):
        step = d.move(rotation_displacement(p0, pitch_angle(amplitude, i, steps), center, axis or (0, 0, 1)))
        assert step.valid and step.converged
    # The same systems, solved the same way (the warm start extrapolates over
    # equal steps in both); they differ only by the rounding of the moving
    # vertices' rotation (numpy's here, the library's there), which the
    # solves carry into the interior at the level of the solver tolerance.
    assert np.abs(d.positions - expected).max() < 100 * tol


def test_an_invalid_step_is_rolled_back_and_reported(data):
    mesh = sm.read_mesh(data(PLATE))
    d = sm.Deformer(mesh, moving="wing")
    p0 = mesh.points[d.moving_vertices]
    assert d.move(rotation_displacement(p0, 10, (1.5, 1))).valid
    before = d.positions.copy()
    step = d.move(rotation_displacement(p0, 170, (1.5, 1)))  # in one step: inverts
    assert not step.valid
    assert step.inverted > 0 and len(step.inverted_elements) == step.inverted
    assert np.array_equal(d.positions, before)  # bit for bit the last valid state
    assert d.move(rotation_displacement(p0, 15, (1.5, 1))).valid


def test_move_releases_the_gil(data, ticks_in_the_middle):
    mesh = sm.read_mesh(data(NACA))
    d = sm.Deformer(mesh, moving="airfoil", threads=1, tolerance=1e-12)
    p0 = mesh.points[d.moving_vertices]

    def work(repeats):
        for i in range(1, 40 * repeats + 1):
            d.move(rotation_displacement(p0, 0.25 * i / repeats, (0.25, 0)))

    # with the GIL held through the moves this thread could not tick in their middle
    assert ticks_in_the_middle(work)


@pytest.fixture(scope="module")
def half_wing(source_dir, tmp_path_factory):
    """A coarse half wing on its symmetry plane z = 0 (Debian's python3-gmsh, through the repository's script)."""
    path = tmp_path_factory.mktemp("half_wing") / "half.msh"
    subprocess.run(["/usr/bin/python3", str(source_dir / "scripts" / "make_gmsh_wing.py"), str(path), "--half",
                    "--size-at-wing", "0.1", "--size-growth", "0.3"], check=True, stdout=subprocess.DEVNULL)
    return sm.read_mesh(path)


def test_sliding_plane_vertices_keep_z_and_slide(half_wing):
    mesh = half_wing
    names = {v: k for k, v in mesh.label_names.items()}
    plane = np.unique(mesh.boundary_facets[mesh.boundary_labels == names["symmetry"]])
    wing = np.unique(mesh.boundary_facets[mesh.boundary_labels == names["wing"]])
    plane_only = np.setdiff1d(plane, wing)
    d = sm.Deformer(mesh, moving="wing", sliding="symmetry", model="ball_vertex_p2")
    assert d.sliding_vertices > 0
    p0 = mesh.points[d.moving_vertices]
    steps = 10
    for i in range(1, steps + 1):
        assert d.move(rotation_displacement(p0, pitch_angle(15, i, steps), (0.5, 0, 0))).valid
    x = d.positions
    assert np.array_equal(x[plane_only, 2], mesh.points[plane_only, 2])  # on the plane, bit for bit
    assert np.abs(x[plane_only, :2] - mesh.points[plane_only, :2]).max() > 1e-2  # and they slid
    # with the plane fixed instead, its vertices stay where they are
    f = sm.Deformer(mesh, moving="wing", model="ball_vertex_p2")
    assert f.sliding_vertices == 0
    assert f.move(rotation_displacement(p0, 2, (0.5, 0, 0))).valid
    assert np.array_equal(f.positions[plane_only], mesh.points[plane_only])
