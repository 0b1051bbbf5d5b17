"""What the peer scripts share (docs/performance.md): the scene, the converged reference, the
error measure and the CSV files the side-by-side reads.

The scene: the Table 2.1 cantilever (scenes/cantilever-gravity.yaml: L = 0.1 m, D = 1 cm,
E = 1 MPa, G = 0.33 MPa, rho = 1000 kg/m^3, rod along +z, gravity -9.81 m/s^2 along x, clamped
base, free tip), released straight from rest, 0.5 s; undamped, or with Kelvin-Voigt viscosity
alpha [Pa s] (rodlab's V = alpha diag(3 I, 3 I, J, A, A, 3 A)).

The reference: rodlab's ida at N = 50 and 100 (rtol = atol = 1e-10, samples every 0.5 ms),
Richardson-extrapolated in ds at second order (the staggered grid's order). Cached in the work
directory.

The error of a run: the largest deviation of its tip from the reference over its own samples in
(0, 0.5 s] (the reference interpolated linearly onto them: at 0.5 ms sampling that adds < 1e-6 m
on this scene), the largest of the three components.
"""
import csv
import json
import os
import statistics
import subprocess

import numpy as np

SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENE = os.path.join(SOURCE, "scenes", "cantilever-gravity.yaml")
T_END = 0.5
ROD_LENGTH = 0.1  # [m]; a larger tip error means the run blew up
DEFAULT_WORK = os.path.join(SOURCE, "out", "peers")
DEFAULT_RODLAB = os.path.join(SOURCE, "build", "bin", "rodlab")


def add_run_arguments(parser):
    """The options every measuring script has: repeats per configuration, the rodlab binary (for
    the reference) and the work directory."""
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--rodlab", default=DEFAULT_RODLAB)
    parser.add_argument("--work", default=DEFAULT_WORK)


def case_name(viscosity):
    return "undamped" if viscosity == 0 else f"viscous{viscosity:g}"


def load_result(path):
    r = json.load(open(path))
    return np.array(r["series"]["t"]), np.array(r["series"]["tip_position"]), r


def pinned(command):
    """The command pinned to core 1 (timings on one core, away from core 0's interrupts) where
    this process may use it, else as it is."""
    return ["taskset", "-c", "1", *command] if 1 in os.sched_getaffinity(0) else list(command)


def run_rodlab(rodlab, out, viscosity, *args):
    """One `rodlab dynamic` run of the scene on core 1; returns the result (t, tip, json)."""
    extra = ["--set", f"rod.material.viscosity={viscosity:g}"] if viscosity else []
    subprocess.run(pinned([rodlab, "dynamic", SCENE, "--t-end", str(T_END), "--quiet", "--out",
                           out, *extra, *map(str, args)]), check=True, capture_output=True)
    return load_result(out)


def reference(rodlab, work, viscosity):
    """The converged tip (t, x): ida at N = 50 and 100, Richardson in ds (second order)."""
    runs = {}
    for n in (50, 100):
        path = os.path.join(work, f"ida{n}-{case_name(viscosity)}.json")
        if not os.path.exists(path):
            run_rodlab(rodlab, path, viscosity, "--scheme", "ida", "--nodes", n, "--dt", 5e-4,
                       "--rtol", 1e-10, "--atol", 1e-10)
        runs[n] = load_result(path)
    t, fine, _ = runs[100]
    coarse = runs[50][1]
    ratio = (99 / 49) ** 2
    return t, fine + (fine - coarse) / (ratio - 1)


def tip_error(t, x, ref):
    """max over the run's samples in (0, T_END] and the components of |x - reference|."""
    t_ref, x_ref = ref
    keep = (t > 0) & (t <= T_END + 1e-12)
    return max(np.abs(x[keep, k] - np.interp(t[keep], t_ref, x_ref[:, k])).max()
               for k in range(3))


def measure(run, repeats, ref):
    """Times one configuration: `run()` returns (wall [s], t, tip, steps, dt [s]), or a string
    saying why the code gave up. Returns the point's measured fields (median wall over
    `repeats` runs, steps, dt, max tip error), or why it has none: the code gave up, or the run
    blew up (a non-finite tip, or a tip error above the rod's length)."""
    walls = []
    for _ in range(repeats):
        out = run()
        if isinstance(out, str):
            return out
        wall, t, x, steps, dt = out
        error = tip_error(t, x, ref) if np.isfinite(x).all() else np.inf
        if not error < ROD_LENGTH:
            return f"blew up (tip error {error:.3g} m)"
        walls.append(wall)
    return dict(dt_s=dt, steps=steps, max_tip_error_m=error,
                wall_ms=statistics.median(walls) * 1e3)


def add_point(rows, label, code, configuration, nodes, measured):
    """Appends a measured point to rows (or says why there is none) and prints it."""
    if isinstance(measured, str):
        print(f"{label}: no point: {measured}", flush=True)
        return
    rows.append(dict(code=code, configuration=configuration, nodes=nodes, **measured))
    print(f"{label}: dt {measured['dt_s']:.4g} s, {measured['steps']} steps, max tip error "
          f"{measured['max_tip_error_m']:.3e} m, {measured['wall_ms']:.2f} ms", flush=True)


FIELDS = ["code", "configuration", "nodes", "dt_s", "steps", "max_tip_error_m", "wall_ms"]


def write_rows(path, rows):
    """The work-precision points of one code and case (atomically: temp file + rename)."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    tmp = path + ".tmp"
    with open(tmp, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=FIELDS)
        w.writeheader()
        for row in rows:
            w.writerow(row)
    os.replace(tmp, path)


def read_rows(path):
    with open(path) as f:
        return [dict(r, nodes=int(r["nodes"]), dt_s=float(r["dt_s"]), steps=int(r["steps"]),
                     max_tip_error_m=float(r["max_tip_error_m"]), wall_ms=float(r["wall_ms"]))
                for r in csv.DictReader(f)]
