"""bench/peers (docs/performance.md): the patching of Till's example, the error measure, the
side-by-side's table, and the scripts' contract with the rodlab command line.

References: hand-made inputs with known answers (a constant tip offset gives that offset as the
error; the least wall time at or below a level); the example's parameter block as it is in
github.com/JohnDTill/ContinuumRobotExamples (snapshot 064f593), abridged.
"""
import math
import os
import sys

import numpy as np
import pytest

SOURCE = os.environ.get("RODLAB_SOURCE_DIR",
                        os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
sys.path.insert(0, os.path.join(SOURCE, "bench", "peers"))

import common  # noqa: E402
import side_by_side  # noqa: E402
import till_cantilever  # noqa: E402

EXAMPLE = """#include <iostream>
const double E = 200e9;
const double G = 80e9;
const double rad = 0.001;
const double rho = 8000;
const Vector3d g = -9.81*Vector3d::UnitX();
const double L = 0.5;
const int N = 40; //Number of spatial points
const double dt = 2e-3; //Time step
const double alpha = -0.2;
const double T = 25; //Total simulation time
const double initial_tip_mass = 0.02;
const double Bs = 0;
const double Be = 0;
const double Bb = 0;
const double Bt = 0;
void cosseratRodOde(){
    n_s = -rhoAg;
}
void cosseratRodPDE(){
    n_s = rhoA*R*(q_t + w.cross(q)) - rhoAg;
}
int main(int, char**){
    return 0;
}
"""


def test_patched_source_sets_the_scene_and_a_straight_start():
    out = till_cantilever.patched_source(EXAMPLE, 20)
    for line in ("const double E = 1.0e6;", "const double G = 0.33e6;", "const double rad = 0.005;",
                 "const double rho = 1000;", "const double L = 0.1;", "const int N = 20;",
                 "const double T = 0.5;", "const double initial_tip_mass = 0;",
                 'const double dt = till_parameter("TILL_dt");',
                 'const double Bb = till_parameter("TILL_Bb");'):
        assert line in out, line
    assert "const double alpha = -0.2;" in out  # Till's time rule stays
    assert "const Vector3d g = -9.81*Vector3d::UnitX();" in out  # gravity stays in the dynamics
    assert out.count("n_s = -rhoAg;") == 0  # the initial statics has no gravity: straight start
    assert "n_s = rhoA*R*(q_t + w.cross(q)) - rhoAg;" in out
    assert out.count("int main(") == 1 and "steady_clock" in out and "return 0;\n}\n" in out


def test_patched_source_refuses_an_example_it_does_not_know():
    with pytest.raises(SystemExit, match="no parameter line for rho"):
        till_cantilever.patched_source(EXAMPLE.replace("const double rho = 8000;", ""), 20)
    with pytest.raises(SystemExit, match="rhoAg"):
        till_cantilever.patched_source(EXAMPLE.replace("    n_s = -rhoAg;\n", ""), 20)


def test_tip_error_is_the_largest_deviation_over_the_run():
    t_ref = np.linspace(0.0, 0.5, 1001)
    x_ref = np.stack([np.sin(t_ref), 0 * t_ref, 0.1 + 0 * t_ref], axis=1)
    t = np.linspace(0.01, 0.5, 50)
    x = np.stack([np.sin(t), 0 * t, 0.1 + 0 * t], axis=1)
    x[17, 1] += 3e-4  # one sample off in y
    x[30, 0] -= 1e-4
    assert common.tip_error(t, x, (t_ref, x_ref)) == pytest.approx(3e-4, abs=2e-6)
    late = np.append(t, 0.6)  # samples past the end are not compared
    assert common.tip_error(late, np.vstack([x, [9, 9, 9]]), (t_ref, x_ref)) == pytest.approx(
        3e-4, abs=2e-6)


def rows(code, points):
    return [dict(code=code, configuration="c", nodes=10, dt_s=1e-3, steps=500,
                 max_tip_error_m=e, wall_ms=w) for e, w in points]


def test_time_to_reach_front_and_table():
    ours = rows("rodlab", [(5e-3, 1.0), (2e-3, 2.0), (1e-3, 4.0), (3e-3, 5.0)])
    theirs = rows("Till", [(4e-3, 3.0), (1.9e-3, 40.0)])
    assert side_by_side.time_to_reach(ours, 2e-3) == 2.0
    assert side_by_side.time_to_reach(theirs, 2e-3) == 40.0
    assert math.isinf(side_by_side.time_to_reach(theirs, 1e-3))
    assert [r["wall_ms"] for r in side_by_side.front(ours)] == [1.0, 2.0, 4.0]  # (3e-3, 5) is dominated
    table = side_by_side.table({"rodlab": ours, "Till": theirs})
    assert "| 0.002 m | 2 ms | 40 ms | 20.0x |" in table
    assert "| 0.001 m | 4 ms | not reached | - |" in table


def test_rows_round_trip_through_the_csv(tmp_path):
    path = str(tmp_path / "rodlab-undamped.csv")
    common.write_rows(path, rows("rodlab", [(1.5e-3, 2.25)]))
    back = common.read_rows(path)
    assert back[0]["max_tip_error_m"] == 1.5e-3 and back[0]["wall_ms"] == 2.25
    assert back[0]["nodes"] == 10 and not os.path.exists(path + ".tmp")


def test_the_peer_scripts_skip_without_their_peer(tmp_path):
    """Without a checkout (and no installed package) each peer script says so and exits 0,
    writing nothing: CI machines have neither peer."""
    import subprocess
    env = dict(os.environ, PYTHONPATH="", TILL_EXAMPLES="", PYELASTICA="")
    for script, option in (("till_cantilever.py", "--till"), ("pyelastica_cantilever.py", "--pyelastica")):
        try:  # an installed elastica package would be used: nothing to check then
            if script.startswith("pyelastica"):
                import elastica  # noqa: F401
                continue
        except ImportError:
            pass
        p = subprocess.run([sys.executable, os.path.join(SOURCE, "bench", "peers", script), option,
                            str(tmp_path / "absent"), "--work", str(tmp_path / "work")],
                           capture_output=True, text=True, env=env, timeout=120)
        assert p.returncode == 0, p.stderr
        assert "skipped" in p.stdout, p.stdout
        assert not (tmp_path / "work").exists()


@pytest.mark.skipif(not os.environ.get("RODLAB_BINARY"), reason="needs the rodlab binary")
def test_the_scripts_contract_with_the_command_line(tmp_path):
    """The fields the scripts read (t, tip_position, dt, steps, wall_time_s) and the viscosity
    override, on a short coarse run of the scene."""
    out = str(tmp_path / "run.json")
    t, x, r = common.run_rodlab(os.environ["RODLAB_BINARY"], out, 300.0, "--scheme",
                                "variational", "--nodes", 6)
    assert t[-1] == pytest.approx(common.T_END) and x.shape == (len(t), 3)
    assert r["steps"] * r["dt"] == pytest.approx(common.T_END) and r["wall_time_s"] > 0
    _, _, undamped = common.run_rodlab(os.environ["RODLAB_BINARY"], out, 0.0, "--scheme",
                                       "variational", "--nodes", 6)
    assert r["dt"] < 0.5 * undamped["dt"]  # the viscous limit of the explicit step took over
