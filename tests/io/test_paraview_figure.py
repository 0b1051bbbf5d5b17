"""The headless ParaView rendering of a dynamic run (scripts/paraview_figure.py, `make
paraview-figure`, docs/visualisation.md), where Debian's pvpython (python3-paraview) and
Xvfb (xvfb) are installed; skipped otherwise (they are not in the bootstrap: a large install).

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
import time

import pytest

RODLAB = os.environ["RODLAB_BINARY"]
SOURCE = os.environ["RODLAB_SOURCE_DIR"]
SCRIPT = os.path.join(SOURCE, "scripts", "paraview_figure.py")

pytestmark = pytest.mark.skipif(
    not (shutil.which("pvpython") and shutil.which("Xvfb")),
    reason="needs pvpython and Xvfb: apt-get install paraview python3-paraview xvfb")


@pytest.fixture(scope="module")
def display():
    """One virtual X server for the module, on the display number it picks itself and reports
    through -displayfd (two `xvfb-run -a` started close together can race for the same one)."""
    read_end, write_end = os.pipe()
    server = subprocess.Popen(["Xvfb", "-displayfd", str(write_end), "-screen", "0",
                               "1024x768x24", "-nolisten", "tcp"],
                              pass_fds=(write_end,), stderr=subprocess.DEVNULL)
    os.close(write_end)
    with os.fdopen(read_end) as numbers:
        number = numbers.readline().strip()
    assert number, "Xvfb did not report a display"
    yield ":" + number
    server.terminate()
    server.wait()


def render(display, *args):
    """pvpython on the script. Under the full suite's load (ctest -j 2), about one run in three
    had pvpython's first connection refused ("bad X server connection") although Xvfb had
    reported the display ready and kept running; a second attempt connects. Retried twice on
    that message only: any other failure is the script's."""
    for _ in range(3):
        p = subprocess.run(["pvpython", SCRIPT, *map(str, args)], capture_output=True,
                           text=True, env={**os.environ, "DISPLAY": display})
        if "bad X server connection" not in p.stderr:
            break
        time.sleep(0.5)
    return p


def test_a_dynamic_run_renders(display, tmp_path):
    subprocess.run([RODLAB, "dynamic", f"{SOURCE}/scenes/cantilever-gravity.yaml", "--t-end",
                    "0.12", "--nodes", "12", "--output-every", "10", "--quiet",
                    "--vtk", tmp_path / "swing"], check=True, capture_output=True)
    out = tmp_path / "swing.png"
    p = render(display, tmp_path / "swing" / "rod.pvd", out, "--snapshots", "4", "--size", "640",
               "480")
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


def test_a_static_file_is_refused(display, tmp_path):
    subprocess.run([RODLAB, "static", f"{SOURCE}/scenes/cable-driven.yaml", "--vtk",
                    tmp_path / "bent"], check=True, capture_output=True)
    out = tmp_path / "bent.png"
    p = render(display, tmp_path / "bent" / "rod.vtp", out)
    assert p.returncode == 2, p.stderr
    assert "not a time series" in p.stderr
    assert not out.exists()
