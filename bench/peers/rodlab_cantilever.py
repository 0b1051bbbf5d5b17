"""rodlab's side of the peer comparison (issue #17 item 4, docs/performance.md): the Table 2.1
cantilever released straight under gravity for 0.5 s (bench/peers/common.py: scene, reference,
error). Runs `variational` at its automatic step for each N, time rule and grid (the staggered
grid and the corrected one, docs/dynamics.md "The corrected grid"), and the implicit shooting
schemes at fixed steps; wall = the median over --repeats runs of the result's wall_time_s, one
core (taskset -c 1).

    python3 bench/peers/rodlab_cantilever.py [--viscosity 0] [--nodes 3,4,5,6,8,10,14,20,30,40]

The two ida references (N = 50 and 100) take about 15 s on one core (session 16: 4.2 and 10.9 s)
and are cached in --work (default out/peers); the points go to <work>/rodlab-<case>.csv for
bench/peers/side_by_side.py.
"""
import argparse
import os
import subprocess

import common


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--nodes", default="3,4,5,6,8,10,14,20,30,40")
    parser.add_argument("--rules", default="verlet,symplectic-euler")
    parser.add_argument("--grids", default="staggered,corrected", help="variational's grids")
    parser.add_argument("--implicit", default="implicit-midpoint,bdf-alpha")
    parser.add_argument("--implicit-nodes", default="6,8,10,14,20,30,40")
    parser.add_argument("--dts", default="1e-2,5e-3,3e-3,2e-3", help="the implicit schemes' steps")
    parser.add_argument("--viscosity", type=float, default=0.0, help="alpha [Pa s]")
    common.add_run_arguments(parser)
    a = parser.parse_args()
    os.makedirs(a.work, exist_ok=True)
    ref = common.reference(a.rodlab, a.work, a.viscosity)
    out = os.path.join(a.work, "rodlab-run.json")
    runs = [(f"variational {rule}, {grid} grid", n, None,
             ["--scheme", "variational", "--variational-step", rule, "--grid", grid])
            for grid in a.grids.split(",") for rule in a.rules.split(",")
            for n in (int(v) for v in a.nodes.split(","))]
    runs += [(f"{scheme}, {grid} grid", n, dt,
              ["--scheme", scheme, "--set", f"solver.grid={grid}", "--dt", dt])
             for scheme in a.implicit.split(",") if scheme for grid in ("staggered", "euler")
             for n in (int(v) for v in a.implicit_nodes.split(","))
             for dt in (float(v) for v in a.dts.split(","))]
    rows = []

    def run(n, args):
        try:
            t, x, r = common.run_rodlab(a.rodlab, out, a.viscosity, "--nodes", n, *args)
        except subprocess.CalledProcessError:
            return "did not reach the end: " + common.load_result(out)[2].get("reason", "")[:80]
        return r["wall_time_s"], t, x, r["steps"], r["dt"]

    for configuration, n, dt, args in runs:
        common.add_point(rows, f"{configuration}, N = {n}, dt {dt if dt else 'auto'}", "rodlab",
                         configuration, n, common.measure(lambda: run(n, args), a.repeats, ref))
    common.write_rows(os.path.join(a.work, f"rodlab-{common.case_name(a.viscosity)}.csv"), rows)


if __name__ == "__main__":
    main()
