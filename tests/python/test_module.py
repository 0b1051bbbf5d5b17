"""The Python module `rodlab` (python/rodlab_module.cpp, docs/python.md) against the command line
it is built from:

- a static and a dynamic solve give the command line's result files to the last bit (same
  scene, same options, the same option-resolution code);
- bad scenes raise SceneError carrying file, line, column, field and message; a bad `set`
  leaves the scene as it was;
- a result's arrays are views of the result's memory, not copies, and stay valid after the
  result is gone;
- `schemes()` is `rodlab schemes`; a Plant steps with held inputs and bends the rod toward the
  pulled cable;
- `study()` gives the command line's study.json (all but the wall times) and the schemes'
  observed orders on the gravity cantilever (rkmk-rk4: 4, rkmk-midpoint-explicit: 2, within 0.1);
- a Simulation stepped from Python repeats solve_dynamic's tips to the last bit, and steps the
  schemes without a plant (bdf-alpha, ida);
- examples/sweep_cable_tension.py runs and matches its closed form (the cable arc) to 1e-9 m;
- `cmake --install` puts the module on Debian python3's path.
"""
import gc
import json
import os
import subprocess

import numpy as np
import pytest

import rodlab

RODLAB = os.environ["RODLAB_BINARY"]
SOURCE = os.environ["RODLAB_SOURCE_DIR"]
SCENES = os.path.join(SOURCE, "scenes")


def cli(*args):
    p = subprocess.run([RODLAB, *args], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    return p.stdout


def test_static_equals_the_command_line(tmp_path):
    path = os.path.join(SCENES, "cable-driven.yaml")
    out = tmp_path / "s.json"
    cli("static", path, "--scheme", "rkmk-rk4", "--nodes", "30", "--set",
        "actuators.1.cable.tension=0.2", "--out", str(out))
    ref = json.loads(out.read_text())
    scene = rodlab.Scene.load(path)
    scene.set("actuators.1.cable.tension", 0.2)
    r = rodlab.solve_static(scene, scheme="rkmk-rk4", nodes=30)
    assert r.scheme == "rkmk-rk4" and r.converged and r.iterations == ref["iterations"]
    c = r.centerline
    assert c.positions.tolist() == [x["position"] for x in ref["centerline"]]
    assert c.rotations.tolist() == [x["rotation"] for x in ref["centerline"]]
    assert c.twists.tolist() == [x["twist"] for x in ref["centerline"]]
    assert r.base_wrench.tolist() == ref["base_wrench"]["moment"] + ref["base_wrench"]["force"]


def test_dynamic_equals_the_command_line(tmp_path):
    path = os.path.join(SCENES, "cantilever-gravity.yaml")
    out = tmp_path / "d.json"
    cli("dynamic", path, "--t-end", "0.03", "--output-every", "4", "--out", str(out))
    ref = json.loads(out.read_text())
    d = rodlab.solve_dynamic(rodlab.Scene.load(path), t_end=0.03, output_every=4)
    assert d.scheme == ref["scheme"] and d.dt == ref["dt"] and d.steps == ref["steps"]
    assert d.t.tolist() == ref["series"]["t"]
    assert d.tip_position.tolist() == ref["series"]["tip_position"]
    for name, values in d.energy.items():
        assert values.tolist() == ref["series"]["energy"][name]
    assert d.final_centerline.positions.tolist() == [
        x["position"] for x in ref["final"]["centerline"]]


def test_bad_scenes_raise_located_errors(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text(open(os.path.join(SCENES, "cable-driven.yaml")).read().replace(
        "E: 1.0e6", "E: -1.0e6"))
    with pytest.raises(rodlab.SceneError) as e:
        rodlab.Scene.load(str(bad))
    d = e.value.diagnostics[0]
    assert d["file"] == str(bad) and d["field"] == "rod.material.E" and d["line"] > 0
    assert d["column"] > 0 and "must be > 0" in d["message"]
    with pytest.raises(rodlab.SceneError):
        rodlab.Scene.from_yaml("schema: rodlab.scene/1\nrod: {length: 0}\n")
    scene = rodlab.Scene.load(os.path.join(SCENES, "cable-driven.yaml"))
    with pytest.raises(rodlab.SceneError) as e:
        scene.set("rod.length", -0.1)
    assert e.value.diagnostics[0]["file"] == "--set rod.length=-0.1"
    assert scene.length == 0.1  # unchanged
    with pytest.raises(ValueError):
        rodlab.solve_static(scene, scheme="variational")  # a dynamics scheme


def test_arrays_are_views_that_outlive_their_result():
    scene = rodlab.Scene.load(os.path.join(SCENES, "cable-driven.yaml"))
    r = rodlab.solve_static(scene)
    positions, rotations = r.centerline.positions, r.centerline.rotations
    expected = positions.copy()
    assert not positions.flags.owndata and positions.base is not None
    assert np.shares_memory(positions, r.centerline.positions)  # no copy per access
    del r
    gc.collect()
    rodlab.solve_static(scene, nodes=40)  # new allocations that would reuse freed memory
    assert positions.tolist() == expected.tolist()
    assert np.allclose(rotations @ rotations.transpose(0, 2, 1), np.eye(3), atol=1e-12)


def test_schemes_and_plant():
    names = [s["name"] for s in rodlab.schemes()]
    listed = cli("schemes")
    assert all(n in listed for n in names) and "variational" in names and "chebyshev" in names
    plant = rodlab.Plant(rodlab.Scene.load(os.path.join(SCENES, "control-cable.yaml")))
    assert plant.tip[2] == pytest.approx(0.1)
    plant.set_input([0.5, 0.0, 0.0, 0.0])  # pull the cable at +x
    for _ in range(4):
        plant.step()
    assert plant.time == pytest.approx(0.2)
    assert plant.tip[0] > 0.005  # bent toward the pulled cable
    assert plant.centerline().positions.shape == (20, 3)


def test_example_runs(tmp_path):
    out = tmp_path / "sweep.png"
    p = subprocess.run(["/usr/bin/python3",
                        os.path.join(SOURCE, "examples", "sweep_cable_tension.py"), str(out)],
                       capture_output=True, text=True, env=os.environ.copy())
    assert p.returncode == 0, p.stderr
    error = float(p.stdout.split("=")[1].split()[0])
    assert error < 1e-9
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_install_puts_the_module_on_the_path(tmp_path):
    p = subprocess.run(["cmake", "--install", os.environ["RODLAB_BUILD_DIR"]],
                       env={**os.environ, "DESTDIR": str(tmp_path)}, capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    installed = list(tmp_path.rglob("rodlab*.so"))
    assert len(installed) == 1
    where = "/" + str(installed[0].parent.relative_to(tmp_path))
    path = subprocess.run(["/usr/bin/python3", "-c", "import sys; print(sys.path)"],
                          capture_output=True, text=True, env={}).stdout
    assert repr(where) in path, (where, path)


def test_study_equals_the_command_line(tmp_path):
    path = os.path.join(SCENES, "cantilever-gravity.yaml")
    cli("study", "convergence", path, "--schemes", "rkmk-rk4,rkmk-midpoint-explicit", "--nodes",
        "5,9,17,33", "--out", str(tmp_path / "study"))
    ref = json.loads((tmp_path / "study" / "study.json").read_text())
    d = rodlab.study(rodlab.Scene.load(path), "convergence",
                     schemes=["rkmk-rk4", "rkmk-midpoint-explicit"], nodes=[5, 9, 17, 33])

    def untimed(rows):
        return [{k: v for k, v in r.items() if not k.startswith("wall_time")} for r in rows]

    assert untimed(d["rows"]) == untimed(ref["rows"])
    assert d["orders"] == ref["orders"] and d["settings"] == ref["settings"]
    orders = {o["scheme"]: o["observed_order"] for o in d["orders"]}
    assert orders["rkmk-rk4"] == pytest.approx(4, abs=0.1)
    assert orders["rkmk-midpoint-explicit"] == pytest.approx(2, abs=0.1)
    with pytest.raises(ValueError):
        rodlab.study(rodlab.Scene.load(path), "stability")


def test_dynamic_work_precision_equals_the_command_line(tmp_path):
    # both sweep the staggered and the corrected grid (the scene names no grid)
    path = os.path.join(SCENES, "viscous-cantilever.yaml")
    cli("study", "work-precision", path, "--schemes", "variational", "--nodes", "4",
        "--t-end", "0.02", "--repeats", "1", "--out", str(tmp_path / "wp"))
    ref = json.loads((tmp_path / "wp" / "study.json").read_text())
    d = rodlab.study(rodlab.Scene.load(path), "work-precision", schemes=["variational"],
                     nodes=[4], t_end=0.02, repeats=1)

    def untimed(rows):
        return [{k: v for k, v in r.items() if not k.startswith("wall_time") and k != "pareto"}
                for r in rows]

    assert d["settings"] == ref["settings"]
    assert d["settings"]["grids"] == ["staggered", "corrected"]
    assert untimed(d["rows"]) == untimed(ref["rows"])
    assert {r["grid"] for r in d["rows"]} == {"staggered", "corrected"}


def test_simulation_repeats_solve_dynamic():
    scene = rodlab.Scene.load(os.path.join(SCENES, "cantilever-gravity.yaml"))
    d = rodlab.solve_dynamic(scene, t_end=0.02)
    sim = rodlab.Simulation(scene, dt=d.dt)
    assert sim.scheme == d.scheme
    tips = [sim.tip.tolist()]
    for _ in range(d.steps):
        sim.step()
        tips.append(sim.tip.tolist())
    assert tips == d.tip_position.tolist()
    state = sim.state()
    assert state["centerline"].positions.tolist() == d.final_centerline.positions.tolist()
    assert state["velocities"].shape == (d.nodes, 6)
    assert state["energy"]["total"] == pytest.approx(d.energy["total"][-1], abs=0.0)
    for scheme, dt in (("bdf-alpha", 0.02), ("ida", 1e-3)):
        other = rodlab.Simulation(scene, scheme=scheme, nodes=10, dt=dt)
        for _ in range(3):
            other.step()
        assert other.time == pytest.approx(3 * dt) and other.tip[0] < 0.0  # falls under gravity
    # below single shooting's lower step bound (kappa 110 at 0.1 ms): the staggered grid steps by
    # multiple shooting, the thesis' Euler grid is refused up front
    below = rodlab.Simulation(scene, scheme="bdf-alpha", nodes=10, dt=1e-4)
    below.step()
    assert below.tip[0] < 0.0
    euler = rodlab.Scene.load(os.path.join(SCENES, "cantilever-gravity.yaml"))
    euler.set("solver.grid", "euler")
    with pytest.raises(ValueError, match="lower step bound"):
        rodlab.Simulation(euler, scheme="bdf-alpha", nodes=10, dt=1e-4)
