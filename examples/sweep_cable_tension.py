"""Sweep a cable's tension and plot the tip deflection (a notebook-style example of the Python
module; docs/python.md). Run from the source tree after `make test` (or `cmake --build build`):

    PYTHONPATH=build/python /usr/bin/python3 examples/sweep_cable_tension.py [out.png]

One cable at r = 4 mm along the whole rod bends it into a circular arc: a constant moment T r
and an axial force -T give the curvature kappa = T r / (E I) and the stretch e = 1 - T / (E A)
per unit reference length, so the tip lies at x = e (1 - cos(kappa L)) / kappa,
z = e sin(kappa L) / kappa. The script solves the statics for each tension with the scene's
scheme and plots the computed tip against this closed form.
"""
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

import rodlab

here = os.path.dirname(os.path.abspath(__file__))
scene = rodlab.Scene.load(os.path.join(here, "..", "scenes", "cable-driven.yaml"))
E, d, r, L = 1.0e6, 0.01, 0.004, scene.length
EI, EA = E * math.pi * d**4 / 64, E * math.pi * d**2 / 4

tensions = [0.05 * k for k in range(11)]
computed, arc = [], []
for T in tensions:
    scene.set("actuators.0.cable.tension", T)
    result = rodlab.solve_static(scene)
    assert result.converged, result.reason
    computed.append(result.centerline.positions[-1, 0])
    kappa, e = T * r / EI, 1 - T / EA
    arc.append(e * (1 - math.cos(kappa * L)) / kappa if kappa > 0 else 0.0)

fig, ax = plt.subplots(figsize=(5, 3.5))
ax.plot(tensions, [1e3 * x for x in computed], "o", label=f"rodlab ({result.scheme})")
ax.plot(tensions, [1e3 * x for x in arc], "-", label="closed form: arc, kappa = T r / EI")
ax.set_xlabel("cable tension T [N]")
ax.set_ylabel("tip deflection x [mm]")
ax.grid(True, alpha=0.3)
ax.legend()
fig.tight_layout()
out = sys.argv[1] if len(sys.argv) > 1 else "sweep_cable_tension.png"
fig.savefig(out, dpi=120)
print(f"max |computed - arc| = {max(abs(a - b) for a, b in zip(computed, arc)):.3g} m; figure {out}")
