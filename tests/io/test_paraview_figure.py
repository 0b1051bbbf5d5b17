"""The headless ParaView rendering of a dynamic run (scripts/paraview_figure.py, `make
paraview-figure`, docs/visualisation.md), where Debian's pvpython (python3-paraview) and
xvfb-run (xvfb) are installed; skipped otherwise (they are not in the bootstrap: a large install).

- a dynamic --vtk run of the gravity cantilever renders: exit 0, a PNG of the requested size,
  not blank (more than 2 % of its pixels differ from the white background), and the rod drawn
  in the colour map's top hue somewhere left of the colour bar (viridis' yellow, shaded by the
  lighting: the largest bending moment, at the clamped base of the last snapshot);
- a collection that is not a time series (a static rod.vtp) is refused with exit status 2 and
  no image.
"""
import os
import shutil
import subprocess

import pytest

RODLAB = os.environ["RODLAB_BINARY"]
SOURCE = os.environ["RODLAB_SOURCE_DIR"]
SCRIPT = os.path.join(SOURCE, "scripts", "paraview_figure.py")

pytestmark = pytest.mark.skipif(
    not (shutil.which("pvpython") and shutil.which("xvfb-run")),
    reason="needs pvpython and xvfb-run: apt-get install paraview python3-paraview xvfb")


def render(*args):
    return subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 1024x768x24", "pvpython",
                           SCRIPT, *map(str, args)], capture_output=True, text=True)


def test_a_dynamic_run_renders(tmp_path):
    subprocess.run([RODLAB, "dynamic", f"{SOURCE}/scenes/cantilever-gravity.yaml", "--t-end",
                    "0.12", "--nodes", "12", "--output-every", "10", "--quiet",
                    "--vtk", tmp_path / "swing"], check=True, capture_output=True)
    out = tmp_path / "swing.png"
    p = render(tmp_path / "swing" / "rod.pvd", out, "--snapshots", "4", "--size", "640", "480")
    assert p.returncode == 0, p.stderr
    import matplotlib.image
    pixels = matplotlib.image.imread(out)[:, :, :3]
    assert pixels.shape[:2] == (480, 640)
    drawn = (pixels < 0.95).any(axis=2)
    assert drawn.mean() > 0.02, drawn.mean()
    r, g, b = pixels[:, :, 0], pixels[:, :, 1], pixels[:, :, 2]
    yellow = (r > 0.4) & (g > 0.85 * r) & (b < 0.3 * r)  # the hue of viridis' top, shaded
    rod_area = yellow[:, : int(0.8 * pixels.shape[1])]  # left of the colour bar
    assert rod_area.any()


def test_a_static_file_is_refused(tmp_path):
    subprocess.run([RODLAB, "static", f"{SOURCE}/scenes/cable-driven.yaml", "--vtk",
                    tmp_path / "bent"], check=True, capture_output=True)
    out = tmp_path / "bent.png"
    p = render(tmp_path / "bent" / "rod.vtp", out)
    assert p.returncode == 2, p.stderr
    assert "not a time series" in p.stderr
    assert not out.exists()
