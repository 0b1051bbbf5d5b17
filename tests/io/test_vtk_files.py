"""ParaView output (`--vtk DIR`, docs/visualisation.md) read back by VTK's own XML reader (Debian's
python3-vtk9) and compared with the result file of the same run:

- static, the cable-driven rod (one cable, T = 0.5 N at r = 4 mm, free tip): the points are the
  result's centreline to the last bit; the frames are orthonormal and right-handed; the internal
  wrench in the body frame is the closed form of a rod bent by one full-length cable, a constant
  moment T r about d2 and an axial force -T (to 1e-8 of T r and T; the scheme converges to
  1e-10); each actuator path lies at its offset from the centreline;
- dynamic, the gravity cantilever: the .pvd lists one rod file per recorded time with the
  result's times, each file's TimeValue is its time, each tip is the result's tip to the last
  bit, the base does not move, and the last file is the result's final centreline;
- workspace: one point per converged sample, with its inputs;
- control: one collection per episode, starting at the rest state, then one file per control
  step whose tip is the result series' tip to the last bit;
- bad input (--vtk naming a file) is refused with exit status 2 and nothing written.
"""
import json
import math
import os
import subprocess
import xml.etree.ElementTree as ET

import vtk

RODLAB = os.environ["RODLAB_BINARY"]
SCENES = os.path.join(os.environ["RODLAB_SOURCE_DIR"], "scenes")


def run(*args, status=0):
    p = subprocess.run([RODLAB, *args], capture_output=True, text=True)
    assert p.returncode == status, p.stderr
    return p


def read_vtp(path):
    reader = vtk.vtkXMLPolyDataReader()
    reader.SetFileName(str(path))
    reader.Update()
    assert reader.GetErrorCode() == 0
    return reader.GetOutput()


def points(data):
    return [data.GetPoint(k) for k in range(data.GetNumberOfPoints())]


def array(data, name):
    a = data.GetPointData().GetArray(name)
    assert a is not None, name
    return [a.GetTuple(k) for k in range(a.GetNumberOfTuples())]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def test_static_rod_and_cables(tmp_path):
    out, vtk_dir = tmp_path / "s.json", tmp_path / "paraview"
    run("static", os.path.join(SCENES, "cable-driven.yaml"), "--out", str(out), "--vtk",
        str(vtk_dir))
    result = json.loads(out.read_text())
    rod = read_vtp(vtk_dir / "rod.vtp")
    assert rod.GetNumberOfLines() == 1
    assert points(rod) == [tuple(c["position"]) for c in result["centerline"]]
    assert rod.GetFieldData().GetArray("radius").GetValue(0) == 0.005
    d1, d2, d3 = array(rod, "d1"), array(rod, "d2"), array(rod, "d3")
    moment, force = array(rod, "moment"), array(rod, "force")
    T, r = 0.5, 0.004
    for j in range(rod.GetNumberOfPoints()):
        frame = (d1[j], d2[j], d3[j])
        for a in range(3):
            for b in range(3):
                assert abs(dot(frame[a], frame[b]) - (a == b)) < 1e-12
        cross = (d1[j][1] * d2[j][2] - d1[j][2] * d2[j][1],
                 d1[j][2] * d2[j][0] - d1[j][0] * d2[j][2],
                 d1[j][0] * d2[j][1] - d1[j][1] * d2[j][0])
        assert max(abs(x - y) for x, y in zip(cross, d3[j])) < 1e-12
        m_body = [dot(d, moment[j]) for d in frame]
        n_body = [dot(d, force[j]) for d in frame]
        assert max(abs(x - y) for x, y in zip(m_body, (0.0, T * r, 0.0))) < 1e-8 * T * r
        assert max(abs(x - y) for x, y in zip(n_body, (0.0, 0.0, -T))) < 1e-8 * T
    cables = read_vtp(vtk_dir / "actuators.vtp")
    assert cables.GetNumberOfLines() == 4
    which = array(cables, "actuator")
    centre = points(rod)
    n = rod.GetNumberOfPoints()
    for k, p in enumerate(points(cables)):
        assert abs(math.dist(p, centre[k % n]) - r) < 1e-12
        assert which[k][0] == k // n


def test_dynamic_series(tmp_path):
    out, vtk_dir = tmp_path / "d.json", tmp_path / "paraview"
    run("dynamic", os.path.join(SCENES, "cantilever-gravity.yaml"), "--t-end", "0.02",
        "--output-every", "5", "--out", str(out), "--vtk", str(vtk_dir))
    result = json.loads(out.read_text())
    series = result["series"]
    entries = ET.parse(vtk_dir / "rod.pvd").getroot().find("Collection").findall("DataSet")
    assert [float(e.get("timestep")) for e in entries] == series["t"]
    assert {e.get("part") for e in entries} == {"0"}  # no actuators in the scene
    base = None
    for e, t, tip in zip(entries, series["t"], series["tip_position"]):
        rod = read_vtp(vtk_dir / e.get("file"))
        assert rod.GetFieldData().GetArray("TimeValue").GetValue(0) == t
        p = points(rod)
        assert p[-1] == tuple(tip)
        base = base or p[0]
        assert p[0] == base
        assert array(rod, "velocity")[0] == (0.0, 0.0, 0.0)
    assert p == [tuple(c["position"]) for c in result["final"]["centerline"]]


def test_workspace_cloud(tmp_path):
    out, vtk_dir = tmp_path / "w.json", tmp_path / "paraview"
    run("workspace", os.path.join(SCENES, "cable-driven.yaml"), "--samples", "3", "--out",
        str(out), "--vtk", str(vtk_dir))
    result = json.loads(out.read_text())
    reached = [s for s in result["tips"] if s["converged"]]
    cloud = read_vtp(vtk_dir / "workspace.vtp")
    assert cloud.GetNumberOfVerts() == len(reached) > 0
    assert points(cloud) == [tuple(s["tip"]) for s in reached]
    assert [x[0] for x in array(cloud, "input_0")] == [s["inputs"][0] for s in reached]


def test_control_episodes(tmp_path):
    out, vtk_dir = tmp_path / "c.json", tmp_path / "paraview"
    run("control", os.path.join(SCENES, "control-cable.yaml"), "--controller", "lqr", "--task",
        "reach", "--targets", "2", "--out", str(out), "--vtk", str(vtk_dir))
    result = json.loads(out.read_text())
    series = result["series"]
    assert sorted(p.name for p in vtk_dir.iterdir()) == ["episode_000", "episode_001"]
    for e in range(2):
        entries = ET.parse(vtk_dir / f"episode_{e:03d}" / "rod.pvd").getroot()[0].findall("DataSet")
        rods = [x for x in entries if x.get("part") == "0"]
        rows = [k for k, i in enumerate(series["episode"]) if i == e]
        assert len(rods) == len(rows) + 1  # the rest state, then every control step
        assert float(rods[0].get("timestep")) == 0.0
        first = read_vtp(vtk_dir / f"episode_{e:03d}" / rods[0].get("file"))
        assert math.dist(points(first)[-1], (0.0, 0.0, 0.1)) < 1e-15  # straight at rest
        for x, k in zip(rods[1:], rows):
            assert float(x.get("timestep")) == series["t"][k]
            rod = read_vtp(vtk_dir / f"episode_{e:03d}" / x.get("file"))
            assert points(rod)[-1] == tuple(series["tip"][k])


def test_bad_directory_is_refused(tmp_path):
    taken = tmp_path / "taken"
    taken.write_text("a file")
    p = run("static", os.path.join(SCENES, "cable-driven.yaml"), "--vtk", str(taken), status=2)
    assert "--vtk" in p.stderr and "not a directory" in p.stderr
    assert taken.read_text() == "a file"
    assert sorted(x.name for x in tmp_path.iterdir()) == ["taken"]
