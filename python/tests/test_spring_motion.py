# Tests of the Python module against the mesh files themselves (parsed here
# independently) and against the spring-motion executable of the same build.
import json
import math
import subprocess
import xml.etree.ElementTree as ET

import numpy as np
import pytest

import spring_motion as sm

# The same meshes in Gmsh's format (physical names) and Medit's (numbers only).
PLATE = "tests/data/cli/plate_v41.msh"        # 2D; boundary 1 'farfield', 2 'wing'; 10 'fluid' (triangles)
PLATE_MEDIT = "tests/data/cli/plate.mesh"
PLATE_V22 = "tests/data/cli/plate_v22.msh"
BOX = "tests/data/cli/box_hole_v41.msh"       # 3D; boundary 1 'body', 2 'outer'
BOX_MEDIT = "tests/data/cli/box_hole.mesh"
NACA = "data/naca0012_2d.msh"


# ---- independent readers ---------------------------------------------------------

def medit_sections(path):
    """{keyword: flat list of numbers} of a Medit ASCII file."""
    tokens = []
    for line in open(path):
        tokens += line.split("#", 1)[0].split()
    sections, i = {}, 0
    sizes = None
    while i < len(tokens):
        word = tokens[i]
        if word == "MeshVersionFormatted":
            i += 2
        elif word == "Dimension":
            dim = int(tokens[i + 1])
            sizes = {"Vertices": dim + 1, "Edges": 3, "Triangles": 4, "Tetrahedra": 5}
            i += 2
        elif word in ("Vertices", "Edges", "Triangles", "Tetrahedra"):
            count = int(tokens[i + 1])
            k = sizes[word]
            sections[word] = np.array([float(t) for t in tokens[i + 2:i + 2 + count * k]]).reshape(count, k)
            i += 2 + count * k
        elif word == "End":
            break
        else:
            raise AssertionError("unexpected section " + word)
    return sections


def gmsh41_nodes_and_triangles(path):
    lines = open(path).read().split("\n")
    start = lines.index("$Nodes")
    blocks, _, _, _ = map(int, lines[start + 1].split())
    i, tags, coords = start + 2, [], []
    for _ in range(blocks):
        _, _, _, n = map(int, lines[i].split())
        tags += [int(t) for t in lines[i + 1:i + 1 + n]]
        coords += [[float(x) for x in l.split()] for l in lines[i + 1 + n:i + 1 + 2 * n]]
        i += 1 + 2 * n
    start = lines.index("$Elements")
    blocks = int(lines[start + 1].split()[0])
    i, triangles = start + 2, []
    for _ in range(blocks):
        _, _, kind, n = map(int, lines[i].split())
        if kind == 2:
            triangles += [[int(t) for t in l.split()[1:]] for l in lines[i + 1:i + 1 + n]]
        i += 1 + n
    return np.array(tags), np.array(coords), np.array(triangles)


# ---- read_mesh --------------------------------------------------------------------

def test_read_medit_2d_matches_the_file(data):
    mesh = sm.read_mesh(data(PLATE_MEDIT))
    s = medit_sections(data(PLATE_MEDIT))
    assert mesh.dimension == 2
    assert mesh.points.dtype == np.float64 and mesh.points.shape == (133, 2)
    assert np.issubdtype(mesh.elements.dtype, np.integer) and mesh.elements.shape == (222, 3)
    assert np.array_equal(mesh.points, s["Vertices"][:, :2])        # z = 0 dropped, bit for bit
    assert np.array_equal(mesh.elements, s["Triangles"][:, :3] - 1)  # 0-based
    assert np.array_equal(mesh.element_labels, s["Triangles"][:, 3])
    assert np.array_equal(mesh.boundary_facets, s["Edges"][:, :2] - 1)
    assert np.array_equal(mesh.boundary_labels, s["Edges"][:, 2])
    assert np.array_equal(mesh.vertex_ids, np.arange(1, 134))


def test_read_medit_3d_matches_the_file(data):
    mesh = sm.read_mesh(str(data(BOX_MEDIT)))
    s = medit_sections(data(BOX_MEDIT))
    assert mesh.dimension == 3
    assert mesh.points.shape == (374, 3) and mesh.elements.shape == (1217, 4)
    assert np.array_equal(mesh.points, s["Vertices"][:, :3])
    assert np.array_equal(mesh.elements, s["Tetrahedra"][:, :4] - 1)
    assert mesh.boundary_facets.shape == (628, 3)


def test_read_gmsh_matches_the_file_and_has_names(data):
    mesh = sm.read_mesh(data(NACA))
    tags, coords, triangles = gmsh41_nodes_and_triangles(data(NACA))
    assert np.array_equal(mesh.vertex_ids, tags)
    assert np.array_equal(mesh.points, coords[:, :2])
    index = {t: i for i, t in enumerate(tags)}
    assert np.array_equal(mesh.elements, np.vectorize(index.get)(triangles))
    assert mesh.label_names == {1: "airfoil", 2: "farfield", 10: "fluid"}
    assert "naca0012_2d.msh" in repr(mesh)


def test_arrays_are_copies(data):
    mesh = sm.read_mesh(data(PLATE))
    p = mesh.points
    p[:] = 0
    assert mesh.points.any()


# ---- errors -----------------------------------------------------------------------

def test_error_classes():
    assert issubclass(sm.Error, Exception)
    assert issubclass(sm.Input_error, sm.Error)


@pytest.mark.parametrize("name, line", [("tests/data/cli/bad_truncated.mesh", None),
                                        ("tests/data/cli/bad_nonnumeric.mesh", None),
                                        ("tests/data/cli/bad_extension.stl", 0),
                                        ("tests/data/cli/no_such_file.mesh", 0)])
def test_bad_file_raises_input_error_naming_it(data, name, line):
    path = str(data(name))
    with pytest.raises(sm.Input_error) as e:
        sm.read_mesh(path)
    assert path in str(e.value)
    assert e.value.file == path
    assert isinstance(e.value, sm.Error)
    if line is not None:
        assert e.value.line == line
    else:
        assert e.value.line > 0 and str(e.value).startswith("%s:%d: " % (path, e.value.line))


def test_unknown_label_raises_and_lists_the_valid_ones(data):
    mesh = sm.read_mesh(data(PLATE))
    for bad in ["nope", 99, ["wing", "nope"]]:
        with pytest.raises(sm.Input_error) as e:
            sm.deform(mesh, moving=bad, pitch=5, center=(1.5, 1), steps=2)
        assert "unknown label" in str(e.value)
        assert "1 'farfield'" in str(e.value) and "2 'wing'" in str(e.value)
    with pytest.raises(sm.Input_error, match="label 'fluid' marks triangles, not boundary edges"):
        sm.deform(mesh, moving="fluid", pitch=5, center=(1.5, 1), steps=2)
    with pytest.raises(sm.Input_error, match="fixed: unknown label 'x'"):
        sm.deform(mesh, moving="wing", fixed="x", pitch=5, center=(1.5, 1), steps=2)


def test_bad_arguments_raise_value_error(data):
    mesh = sm.read_mesh(data(PLATE))
    with pytest.raises(ValueError, match="expected a motion"):
        sm.deform(mesh, moving="wing")
    with pytest.raises(ValueError, match="expected one motion"):
        sm.deform(mesh, moving="wing", pitch=5, center=(1, 1), translate=(1, 0))
    with pytest.raises(ValueError, match="unknown stiffness model 'springy'"):
        sm.deform(mesh, moving="wing", pitch=5, center=(1, 1), model="springy")
    with pytest.raises(ValueError, match=r"shape \(133, 2\)"):
        sm.deform(mesh, moving="wing", displacement=np.zeros((133, 3)))
    with pytest.raises(ValueError, match="the mesh is 2D"):
        sm.deform(mesh, moving="wing", pitch=5, center=(1, 1, 1))
    with pytest.raises(ValueError, match=r"shape \(133, 2\)"):
        sm.write_mesh("unused.vtu", mesh, np.zeros((132, 2)))


# ---- labels -----------------------------------------------------------------------

def test_labels_by_name_and_by_number_agree(data):
    mesh = sm.read_mesh(data(PLATE))
    runs = [sm.deform(mesh, moving=m, pitch=8, center=(1.5, 1), steps=3)
            for m in (["wing"], "wing", 2, [2], "2")]
    for positions, report in runs[1:]:
        assert np.array_equal(positions, runs[0][0])
        assert report["mesh"] == runs[0][1]["mesh"]
    # the wing moved, the farfield did not
    moved = np.linalg.norm(runs[0][0] - mesh.points, axis=1) > 0
    wing = np.unique(mesh.boundary_facets[mesh.boundary_labels == 2])
    farfield = np.unique(mesh.boundary_facets[mesh.boundary_labels == 1])
    assert moved[wing].all() and not moved[farfield].any()
    assert runs[0][1]["mesh"]["moving_vertices"] == len(wing)
    assert runs[0][1]["mesh"]["fixed_vertices"] == len(farfield)


def test_pitch_moves_the_wing_rigidly(data):
    mesh = sm.read_mesh(data(PLATE))
    positions, report = sm.deform(mesh, moving="wing", pitch=30, center=(1.5, 1), steps=10)
    assert report["completed"]
    wing = np.unique(mesh.boundary_facets[mesh.boundary_labels == 2])
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    d = mesh.points[wing] - (1.5, 1)
    expected = np.stack([1.5 + c * d[:, 0] - s * d[:, 1], 1 + s * d[:, 0] + c * d[:, 1]], axis=1)
    assert np.allclose(positions[wing], expected, rtol=0, atol=1e-12)


# ---- the same numbers as spring-motion deform --------------------------------------

def run_cli(cli, tmp_path, mesh, *options):
    out, rep = tmp_path / "cli.mesh", tmp_path / "cli.json"
    subprocess.run([cli, "deform", str(mesh), *options, "--output", str(out), "--report", str(rep), "--quiet"],
                   check=True)
    return sm.read_mesh(out).points, json.load(open(rep))


def without_times(report):
    """The report without its timings and the thread counts chosen by measuring them."""
    r = json.loads(json.dumps(report))
    del r["seconds_total"]
    for s in r["steps"]:
        del s["seconds"]
        del s["threads"]
    return r


CASES = [
    (PLATE, ["--moving", "wing", "--pitch", "25", "--center", "1.5,1", "--steps", "4"],
     dict(moving=["wing"], pitch=25, center=(1.5, 1), steps=4)),
    (PLATE_MEDIT, ["--moving", "2", "--pitch", "-20", "--center", "1.4,1.05,0", "--steps", "3", "--model", "torsional"],
     dict(moving=2, pitch=-20, center=(1.4, 1.05, 0), steps=3, model="torsional")),
    (PLATE_V22, ["--moving", "wing", "--fixed", "farfield", "--translate", "0.1,-0.05", "--steps", "2",
                 "--model", "blom", "--solver", "sor", "--omega", "1.5"],
     dict(moving="wing", fixed="farfield", translate=(0.1, -0.05), steps=2, model="blom", solver="sor", omega=1.5)),
    (BOX_MEDIT, ["--moving", "1", "--translate", "0.1,0.05,-0.1", "--steps", "2", "--model", "zeng_ethier"],
     dict(moving=[1], translate=(0.1, 0.05, -0.1), steps=2, model="zeng_ethier")),
    (BOX, ["--moving", "body", "--pitch", "12", "--center", "1,1,1", "--axis", "1,1,0", "--steps", "3"],
     dict(moving="body", pitch=12, center=(1, 1, 1), axis=(1, 1, 0), steps=3)),
]


@pytest.mark.parametrize("mesh_name, cli_options, kwargs", CASES)
def test_deform_equals_the_command(cli, data, tmp_path, mesh_name, cli_options, kwargs):
    expected_positions, expected_report = run_cli(cli, tmp_path, data(mesh_name), *cli_options)
    positions, report = sm.deform(sm.read_mesh(data(mesh_name)), **kwargs)
    assert positions.dtype == np.float64
    assert np.array_equal(positions, expected_positions)  # bit for bit
    assert without_times(report) == without_times(expected_report)


def test_displacement_equals_the_command(cli, data, tmp_path):
    mesh = sm.read_mesh(data(PLATE))
    wing = np.unique(mesh.boundary_facets[mesh.boundary_labels == 2])
    x = mesh.points[:, 0]
    d = np.zeros_like(mesh.points)
    d[wing, 1] = 0.1 * (x[wing] - 1.0) ** 2  # a bending mode of the plate
    d[0] = (5.0, 5.0)                        # not a moving vertex: ignored
    with open(tmp_path / "d.txt", "w") as f:
        for v in wing:
            f.write("%d %r %r\n" % (mesh.vertex_ids[v], d[v, 0], d[v, 1]))
    expected_positions, expected_report = run_cli(cli, tmp_path, data(PLATE), "--moving", "wing", "--displacement",
                                                  str(tmp_path / "d.txt"), "--steps", "3")
    positions, report = sm.deform(mesh, moving="wing", displacement=d, steps=3)
    assert np.array_equal(positions, expected_positions)
    assert without_times(report) == without_times(expected_report)
    assert np.array_equal(positions[wing], mesh.points[wing] + d[wing])


# ---- the report ------------------------------------------------------------------------

def test_report_fields(data):
    mesh = sm.read_mesh(data(PLATE))
    _, r = sm.deform(mesh, moving="wing", pitch=30, center=(0.5, 0, 0), axis=(0, 0, 1), steps=7)
    assert r["format"] == "spring_motion.report/1"
    assert r["mesh"]["dimension"] == 2
    assert r["mesh"]["vertices"] == 133 and r["mesh"]["elements"] == 222
    assert r["model"]["name"] == "grid_scaled"
    assert r["motion"]["kind"] == "pitch" and r["motion"]["amplitude_deg"] == 30 and r["motion"]["steps"] == 7
    assert r["motion"]["center"] == [0.5, 0, 0]
    assert [s["step"] for s in r["steps"]] == list(range(1, 8))
    assert r["completed"] is True and r["first_invalid"] is None and r["final_fraction"] == 1
    assert r["final_angle_deg"] == pytest.approx(30, abs=1e-12)
    assert r["quality"]["all"]["count"] == 222


def test_an_inverting_run_stops_at_the_last_valid_state(data):
    mesh = sm.read_mesh(data(PLATE))
    positions, r = sm.deform(mesh, moving="wing", translate=(2.2, 0), steps=4)
    assert r["completed"] is False
    assert r["first_invalid"]["step"] >= 1 and r["first_invalid"]["elements"]
    assert r["final_fraction"] == (r["first_invalid"]["step"] - 1) / 4
    wing = np.unique(mesh.boundary_facets[mesh.boundary_labels == 2])
    assert np.allclose(positions[wing, 0] - mesh.points[wing, 0], 2.2 * r["final_fraction"], rtol=0, atol=1e-12)


# ---- writing -----------------------------------------------------------------------

def test_write_vtu_parses(data, tmp_path):
    mesh = sm.read_mesh(data(PLATE))
    positions, _ = sm.deform(mesh, moving="wing", pitch=10, center=(1.5, 1), steps=2)
    path = tmp_path / "out.vtu"
    sm.write_mesh(path, mesh, positions, point_data={"displacement": positions - mesh.points},
                  cell_data={"label": mesh.element_labels})
    piece = ET.parse(path).getroot().find("UnstructuredGrid/Piece")
    assert int(piece.get("NumberOfPoints")) == 133 and int(piece.get("NumberOfCells")) == 222
    xyz = np.array(piece.find("Points/DataArray").text.split(), dtype=float).reshape(-1, 3)
    assert np.allclose(xyz[:, :2], positions, rtol=0, atol=1e-12) and not xyz[:, 2].any()
    names = [a.get("Name") for a in piece.iter("DataArray")]
    assert "displacement" in names and "label" in names


def test_write_medit_reads_back_bit_for_bit(data, tmp_path):
    mesh = sm.read_mesh(data(BOX))
    positions, _ = sm.deform(mesh, moving="outer", translate=(0.05, 0, 0), steps=1)
    sm.write_mesh(tmp_path / "out.mesh", mesh, positions)
    back = sm.read_mesh(tmp_path / "out.mesh")
    assert np.array_equal(back.points, positions)
    assert np.array_equal(back.elements, mesh.elements)
    sm.write_mesh(tmp_path / "same.mesh", mesh)  # no positions: the mesh as read
    assert np.array_equal(sm.read_mesh(tmp_path / "same.mesh").points, mesh.points)


def test_write_to_a_bad_path_raises(data, tmp_path):
    mesh = sm.read_mesh(data(PLATE))
    with pytest.raises(sm.Input_error):
        sm.write_mesh(tmp_path / "no_dir" / "out.vtu", mesh)
    with pytest.raises(sm.Input_error, match="out.stl"):
        sm.write_mesh(tmp_path / "out.stl", mesh)


# ---- threads -----------------------------------------------------------------------

def test_deform_releases_the_gil(data, ticks_in_the_middle):
    mesh = sm.read_mesh(data(NACA))

    def work(repeats):
        sm.deform(mesh, moving="airfoil", pitch=10, center=(0.25, 0), steps=40 * repeats, threads=1)

    # with the GIL held through the run this thread could not tick in its middle
    assert ticks_in_the_middle(work)


# ---- the example -------------------------------------------------------------------

def test_flapping_example_writes_a_time_series(source_dir, tmp_path):
    import os
    import sys
    env = dict(os.environ, PYTHONPATH=os.path.dirname(sm.__file__))
    subprocess.run([sys.executable, str(source_dir / "python" / "examples" / "flapping_airfoil.py"),
                    "--frames", "4", "--out", str(tmp_path / "series")], check=True, env=env,
                   stdout=subprocess.DEVNULL)
    pvd = ET.parse(tmp_path / "series" / "flapping.pvd").getroot()
    sets = pvd.findall("Collection/DataSet")
    assert [float(s.get("timestep")) for s in sets] == [0, 0.25, 0.5, 0.75, 1]
    mesh = sm.read_mesh(source_dir / "data" / "naca0012_2d.msh")
    surface = np.unique(mesh.boundary_facets[mesh.boundary_labels == 1])  # 'airfoil'
    tip = surface[np.argmax(mesh.points[surface, 0])]
    tips = []
    for s in sets:
        piece = ET.parse(tmp_path / "series" / s.get("file")).getroot().find("UnstructuredGrid/Piece")
        assert int(piece.get("NumberOfPoints")) == len(mesh.points)
        xyz = np.array(piece.find("Points/DataArray").text.split(), dtype=float).reshape(-1, 3)
        tips.append(xyz[tip, 1] - mesh.points[tip, 1])
    # the trailing edge follows A sin(2 pi t): up at t = 1/4, down at 3/4, back at 0, 1/2, 1
    assert abs(tips[0]) < 1e-12 and abs(tips[2]) < 1e-12 and abs(tips[4]) < 1e-12
    chord = np.ptp(mesh.points[surface, 0])
    assert tips[1] == pytest.approx(0.08 * chord, abs=1e-12) and abs(tips[1] + tips[3]) < 1e-12


def test_an_undetermined_region_is_named_as_the_file_numbers_it(data):
    # two grids side by side; labels 1..5 (Medit references) on their sides
    path = str(data("tests/data/cli/two_parts.mesh"))
    mesh = sm.read_mesh(path)
    with pytest.raises(sm.Input_error) as e:
        sm.deform(mesh, moving=1, fixed=1, translate=(0.1, 0), steps=2)
    v = int(str(e.value).split("for instance vertex ")[1].split()[0])
    assert str(e.value).startswith(path + ": 9 free vertices")
    assert v in mesh.vertex_ids  # the file's number, and the point printed is that vertex's
    x, y = mesh.points[list(mesh.vertex_ids).index(v)]
    assert "vertex %d at (%g, %g))" % (v, x, y) in str(e.value)


def test_version_is_the_projects(source_dir):
    import re
    text = (source_dir / "CMakeLists.txt").read_text()
    assert sm.__version__ == re.search(r"project\(SpringMotion VERSION ([0-9.]+)", text).group(1)
