"""Till's Cosserat rod PDE example on the peer scene (issue #17 item 4, docs/performance.md).

J. Till, V. Aloi, C. Rucker, "Real-time dynamics of soft and continuum robots based on Cosserat
rod models", IJRR 38(6), 2019; code: github.com/JohnDTill/ContinuumRobotExamples,
02_Dynamics/00_Cosserat_Rod_PDE/Cpp/main.cpp (BDF-alpha in time, alpha = -0.2; explicit Euler
in arclength; Levenberg-Marquardt shooting on the base wrench). Not vendored, not downloaded:

    git clone https://github.com/JohnDTill/ContinuumRobotExamples /path/to/ContinuumRobotExamples
    python3 bench/peers/till_cantilever.py --till /path/to/ContinuumRobotExamples

(or set TILL_EXAMPLES). Without the checkout the script says so and exits 0 (skipped).

The script copies the example's model and shooting functions unchanged and sets what the
scene needs, each a line of the example's parameter block or one statement:
- the Table 2.1 rod (E, G, rad, rho, L), T = 0.5 s, N (one build each), dt per run, the viscosity alpha as
  Till's damping constants (Bb = 3 alpha I, Bt = alpha 2 I, Bs = alpha A, Be = 3 alpha A: rodlab's
  Kelvin-Voigt V);
- the straight start: no tip mass, and the initial statics without gravity (its n_s = -rho A g
  becomes zero; the example starts from the sag under a tip mass);
- its own main(): the same time loop, the tip recorded after every step, wall time by
  steady_clock around the loop (the example's clock() measured CPU time), the shooting
  tolerance as a parameter (the example's default: squared residual norm 1e-12 N^2).
Built with the flags of rodlab's Release build (g++ -O3 -DNDEBUG, no -march) against the Eigen
the example ships. Each configuration runs --repeats times on core 1; wall = the median.
Points go to <work>/till-<case>.csv for bench/peers/side_by_side.py.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile

import numpy as np

import common

EXAMPLE = os.path.join("02_Dynamics", "00_Cosserat_Rod_PDE", "Cpp", "main.cpp")

MAIN = r"""
int main(int, char**){
    Vector6d guess = Vector6d::Zero();
    Vector6d reaction_wrench = solveLevenbergMarquardt<objFunc<false> >(guess);
    TimeManagerBdfAlpha time_scheme(Z, Z_h, dt, alpha);
    F = Vector3d::Zero();
    const int M = static_cast<int>(std::lround(T/dt));
    MatrixXd tip(M, 3);
    const auto start = std::chrono::steady_clock::now();
    for(int i = 0; i < M; i++){
        time_scheme.advanceTime();
        reaction_wrench = solveLevenbergMarquardt<objFunc<true> >(reaction_wrench, SOS_TOL);
        tip.row(i) = Y.block<3,1>(0, N-1).transpose();
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("wall %.9g\n", wall);
    for(int i = 0; i < M; i++) std::printf("%.17g %.17g %.17g %.17g\n", (i + 1)*dt, tip(i,0), tip(i,1), tip(i,2));
    return 0;
}
"""


RUNTIME = ("dt", "Bs", "Be", "Bb", "Bt")  # read from the environment: one build per N


def patched_source(text, nodes):
    """The example with the scene's parameters, a straight start and MAIN; dt, the damping
    constants and the shooting tolerance come from the environment (run())."""
    values = {"E": "1.0e6", "G": "0.33e6", "rad": "0.005", "rho": "1000", "L": "0.1",
              "N": str(nodes), "T": repr(common.T_END), "initial_tip_mass": "0"}
    values.update({name: f'till_parameter("TILL_{name}")' for name in RUNTIME})
    for name, value in values.items():
        text, n = re.subn(rf"^(const (?:double|int) {name} = )[^;]*;", rf"\g<1>{value};", text,
                          count=1, flags=re.M)
        if n != 1:
            raise SystemExit(f"till_cantilever: the example has no parameter line for {name}")
    text, n = re.subn(r"n_s = -rhoAg;", "n_s = Vector3d::Zero();  // straight start", text, count=1)
    if n != 1:
        raise SystemExit("till_cantilever: the example's statics ODE has no `n_s = -rhoAg;`")
    head, sep, _ = text.partition("int main(")
    if not sep:
        raise SystemExit("till_cantilever: the example has no main()")
    return ("#include <chrono>\n#include <cmath>\n#include <cstdio>\n#include <cstdlib>\n"
            "static double till_parameter(const char* name) { return std::atof(std::getenv(name)); }\n"
            + head + 'const double SOS_TOL = till_parameter("TILL_SOS_TOL");\n' + MAIN)


def build(till, work, nodes):
    text = open(os.path.join(till, EXAMPLE)).read()
    source = os.path.join(work, f"till_main{nodes}.cpp")
    binary = os.path.join(work, f"till_main{nodes}")
    open(source, "w").write(patched_source(text, nodes))
    subprocess.run(["g++", "-std=c++17", "-O3", "-DNDEBUG", "-w", "-I",
                    os.path.join(till, "Library"), source, "-o", binary], check=True)
    return binary


def run(binary, dt, viscosity, sos_tol):
    """One run on core 1: (wall [s], t, tip, steps, dt) for common.measure, or why there is none
    (the example's Levenberg-Marquardt throws after 500 iterations: the step has no solution it
    can find)."""
    A, I = np.pi * 0.005 ** 2, np.pi * 0.005 ** 4 / 4
    env = dict(os.environ, TILL_dt=repr(dt), TILL_Bs=repr(viscosity * A),
               TILL_Be=repr(3 * viscosity * A), TILL_Bb=repr(3 * viscosity * I),
               TILL_Bt=repr(viscosity * 2 * I), TILL_SOS_TOL=repr(sos_tol))
    p = subprocess.run(common.pinned([binary]), capture_output=True, text=True, timeout=600,
                       env=env)
    lines = p.stdout.split("\n")
    if p.returncode != 0 or not lines[0].startswith("wall "):
        return "Levenberg-Marquardt gave up"
    data = np.array([[float(v) for v in line.split()] for line in lines[1:] if line.strip()])
    return float(lines[0].split()[1]), data[:, 0], data[:, 1:4], len(data), dt


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--till", default=os.environ.get("TILL_EXAMPLES", ""),
                        help="a checkout of github.com/JohnDTill/ContinuumRobotExamples")
    parser.add_argument("--nodes", default="10,20,40,80,160")
    parser.add_argument("--dts", default="2e-2,1e-2,7e-3,5e-3,4e-3,3e-3,2e-3")
    parser.add_argument("--sos-tol", default="1e-12,1e-20",
                        help="shooting tolerances (the example's default first)")
    parser.add_argument("--viscosity", type=float, default=0.0, help="alpha [Pa s]")
    common.add_run_arguments(parser)
    a = parser.parse_args()
    if not a.till or not os.path.exists(os.path.join(a.till, EXAMPLE)):
        print("till_cantilever: skipped: no checkout of ContinuumRobotExamples (give --till DIR or "
              "set TILL_EXAMPLES; git clone https://github.com/JohnDTill/ContinuumRobotExamples)")
        return 0
    if shutil.which("g++") is None:
        print("till_cantilever: skipped: no g++")
        return 0
    os.makedirs(a.work, exist_ok=True)
    ref = common.reference(a.rodlab, a.work, a.viscosity)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for n in (int(v) for v in a.nodes.split(",")):
            binary = build(a.till, tmp, n)
            for sos in (float(v) for v in a.sos_tol.split(",")):
                for dt in (float(v) for v in a.dts.split(",")):
                    measured = common.measure(lambda: run(binary, dt, a.viscosity, sos),
                                              a.repeats, ref)
                    common.add_point(rows, f"LM tol {sos:g}, N = {n}, dt {dt:g}", "Till",
                                     f"BDF-alpha, LM tol {sos:g}", n, measured)
    common.write_rows(os.path.join(a.work, f"till-{common.case_name(a.viscosity)}.csv"), rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
