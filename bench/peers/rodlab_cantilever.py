"""rodlab's side of the peer comparison (issue #17 item 4, docs/performance.md): the Table 2.1
cantilever (scenes/cantilever-gravity.yaml) released straight under gravity, 0.5 s, undamped;
error = the largest tip deviation over the run from a converged reference (ida at N = 50 and
100, rtol = atol = 1e-10, Richardson-extrapolated in ds at second order; ida at N = 100 is
within 7e-6 m of it); wall = the median over 5 runs of the result's wall_time_s, one core.

    python3 bench/peers/rodlab_cantilever.py [--nodes 10,20,30,40] [--rodlab build/bin/rodlab]

The references take about 25 s (N = 100) on one core; they are cached in --work (default
out/peers). The peers' own scripts (PyElastica, Till's examples) are not in the repository yet:
docs/performance.md says where they stand.
"""
import argparse
import json
import os
import statistics
import subprocess

import numpy as np

SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENE = os.path.join(SOURCE, "scenes", "cantilever-gravity.yaml")


def load(path):
    r = json.load(open(path))
    return np.array(r["series"]["t"]), np.array(r["series"]["tip_position"]), r


def run(rodlab, out, *args):
    subprocess.run(["taskset", "-c", "1", rodlab, "dynamic", SCENE, "--t-end", "0.5", "--quiet",
                    "--out", out, *map(str, args)], check=True, capture_output=True)


def reference(rodlab, work):
    """The converged tip: ida at N = 50 and 100, Richardson in ds (second order)."""
    runs = {}
    for n in (50, 100):
        path = os.path.join(work, f"ida{n}.json")
        if not os.path.exists(path):
            run(rodlab, path, "--scheme", "ida", "--nodes", n, "--dt", 5e-4, "--rtol", 1e-10,
                "--atol", 1e-10)
        runs[n] = load(path)
    t, fine, _ = runs[100]
    coarse = runs[50][1]
    ratio = (99 / 49) ** 2
    return t, fine + (fine - coarse) / (ratio - 1)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--nodes", default="10,20,30,40")
    parser.add_argument("--rodlab", default=os.path.join(SOURCE, "build", "bin", "rodlab"))
    parser.add_argument("--work", default=os.path.join(SOURCE, "out", "peers"))
    a = parser.parse_args()
    os.makedirs(a.work, exist_ok=True)
    t_ref, ref = reference(a.rodlab, a.work)
    print("rule, N, dt [s], steps, max tip error [m], median wall [ms]")
    for rule in ("verlet", "symplectic-euler"):
        for n in (int(v) for v in a.nodes.split(",")):
            walls = []
            for _ in range(5):
                out = os.path.join(a.work, "variational.json")
                run(a.rodlab, out, "--scheme", "variational", "--nodes", n,
                    "--variational-step", rule)
                t, x, r = load(out)
                walls.append(r["wall_time_s"])
            error = max(np.abs(np.interp(t_ref, t, x[:, k]) - ref[:, k]).max() for k in range(3))
            print(f"{rule}, {n}, {r['dt']:.4g}, {r['steps']}, {error:.3e}, "
                  f"{statistics.median(walls) * 1e3:.2f}", flush=True)


if __name__ == "__main__":
    main()
