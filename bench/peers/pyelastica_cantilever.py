"""PyElastica on the peer scene (issue #17 item 4, docs/performance.md): the Table 2.1 cantilever
released straight under gravity, 0.5 s, undamped (bench/peers/common.py: reference, error).

M. Gazzola, L. Dudte, A. McCormick, L. Mahadevan, "Forward and inverse problems in the mechanics
of soft filaments", R. Soc. Open Sci. 5, 2018; code: github.com/GazzolaLab/PyElastica (the
discrete Cosserat rod of Gazzola et al., explicit position Verlet in time). Not vendored, not
downloaded:

    git clone https://github.com/GazzolaLab/PyElastica /path/to/PyElastica   # or pip install pyelastica
    apt-get install python3-numba python3-scipy python3-tqdm                 # Debian's numba
    python3 bench/peers/pyelastica_cantilever.py --pyelastica /path/to/PyElastica

(or set PYELASTICA; an installed `elastica` package is used when neither is given). Without
PyElastica the script says so and exits 0 (skipped).

The model is rodlab's: E, G, rho and the circular section of the scene; PyElastica scales the
shear stiffness by alpha_c = 27/28 (Kaneko), so the rod's shear matrix is set to G A after
construction (its bend/twist matrix is already diag(E I, E I, G 2I), its inertias rho diag(I, I,
2I) and rho A). The base is clamped (OneEndFixedBC), gravity -9.81 m/s^2 along x, the rod along
+z. PyElastica has no Kelvin-Voigt viscosity in its constitutive law (its dampers act on
velocities), so only the undamped case is compared. elastica.mesh imports pyvista when the
package is imported; the scene uses no mesh, so where pyvista is not installed (Debian 12 has no
package) an empty stand-in module is put on the path.

Each configuration (elements, dt) runs --repeats times in one process after a warm-up run that
compiles numba's kernels; wall = the median of time.perf_counter around integrate(); the tip is
recorded every step. Runs that blow up (a non-finite tip, or a tip error above the rod's
length) are reported and left out. Points go to
<work>/pyelastica-undamped.csv for bench/peers/side_by_side.py.
"""
import argparse
import contextlib
import importlib
import io
import os
import sys
import tempfile
from time import perf_counter

import numpy as np

import common

L, RADIUS, E, G, RHO = common.ROD_LENGTH, 0.005, 1.0e6, 0.33e6, 1000.0


def import_elastica(path):
    """The elastica package from `path` (a checkout) or the installed one; None if absent."""
    if path:
        sys.path.insert(0, path)
    try:
        return importlib.import_module("elastica")
    except ModuleNotFoundError as e:
        if e.name != "pyvista":
            print(f"pyelastica_cantilever: skipped: elastica cannot be imported ({e})")
            return None
    stub = tempfile.mkdtemp(prefix="pyvista-stub-")  # elastica.mesh's import; no mesh is used
    open(os.path.join(stub, "pyvista.py"), "w").close()
    sys.path.insert(0, stub)
    return importlib.import_module("elastica")


def simulate(ea, n_elements, dt):
    """One run: (wall [s], t, tip, steps, dt) for common.measure, the samples at t = 0 and after
    every step."""

    class Cantilever(ea.BaseSystemCollection, ea.Constraints, ea.Forcing, ea.CallBacks):
        pass

    sim = Cantilever()
    rod = ea.CosseratRod.straight_rod(
        n_elements, np.zeros(3), np.array([0.0, 0.0, 1.0]), np.array([1.0, 0.0, 0.0]), L, RADIUS,
        RHO, youngs_modulus=E, shear_modulus=G)
    area = np.pi * RADIUS**2
    rod.shear_matrix[0, 0, :] = G * area  # rodlab's G A (PyElastica: 27/28 G A)
    rod.shear_matrix[1, 1, :] = G * area
    sim.append(rod)
    sim.constrain(rod).using(ea.OneEndFixedBC, constrained_position_idx=(0,),
                             constrained_director_idx=(0,))
    sim.add_forcing_to(rod).using(ea.GravityForces, acc_gravity=np.array([-9.81, 0.0, 0.0]))
    samples = []

    class Tip(ea.CallBackBaseClass):
        def make_callback(self, system, time, current_step):  # noqa: A002 (elastica's name)
            samples.append((time, *system.position_collection[:, -1]))

    sim.collect_diagnostics(rod).using(Tip)
    sim.finalize()
    steps = int(round(common.T_END / dt))
    with contextlib.redirect_stdout(io.StringIO()):  # integrate() prints its final time
        start = perf_counter()
        ea.integrate(ea.PositionVerlet(), sim, common.T_END, steps, progress_bar=False)
        wall = perf_counter() - start
    data = np.array(samples)
    return wall, data[:, 0], data[:, 1:4], steps, dt


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pyelastica", default=os.environ.get("PYELASTICA", ""),
                        help="a checkout of github.com/GazzolaLab/PyElastica")
    parser.add_argument("--elements", default="10,20,40,80,160,320")
    parser.add_argument("--dts", default="1e-4,5e-5,2e-5,1e-5")
    parser.add_argument("--append", action="store_true",
                        help="add the points to the existing CSV (a second sweep, other dt per N)")
    common.add_run_arguments(parser)
    a = parser.parse_args()
    ea = import_elastica(a.pyelastica)
    if ea is None:
        return 0
    os.makedirs(a.work, exist_ok=True)
    ref = common.reference(a.rodlab, a.work, 0.0)
    simulate(ea, 4, 1e-4)  # numba compiles its kernels here, outside the timings
    rows = []
    for n in (int(v) for v in a.elements.split(",")):
        for dt in (float(v) for v in a.dts.split(",")):
            common.add_point(rows, f"{n} elements, dt {dt:g}", "PyElastica", "position Verlet",
                             n + 1, common.measure(lambda: simulate(ea, n, dt), a.repeats, ref))
    path = os.path.join(a.work, "pyelastica-undamped.csv")
    if a.append and os.path.exists(path):
        rows = common.read_rows(path) + rows
    common.write_rows(path, rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
