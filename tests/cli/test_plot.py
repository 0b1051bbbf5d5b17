"""`rodlab plot RESULT [--out FILE]` (apps/rodlab/cmd_plot.cpp, scripts/rodlab_plot.py,
docs/cli.md): for every kind of result the real rodlab writes (static, dynamic, workspace,
control, a convergence and a work-precision study), the figure is written (exit 0, "figure
written to FILE"): a PNG of plausible size and pixel dimensions read from its header, an SVG
that parses as XML with an <svg> root, a PDF, and a GIF animation of a dynamic result with
more than one frame. An .mp4 needs ffmpeg: without it, exit 1, a message that suggests .gif,
nothing written. Bad input (a missing file, a JSON file that is not a rodlab result, a CSV
result, an unknown --out extension, an animation of a static result, a missing directory, a
stability study) is refused with exit 2 before anything runs, and nothing is written; without
a usable python3 the exit status is 1. No temporary file is left behind.
"""
import os
import shutil
import struct
import subprocess
import xml.etree.ElementTree as ET

import numpy as np
import pytest

RODLAB = os.environ["RODLAB_BINARY"]
SCENES = os.path.join(os.environ["RODLAB_SOURCE_DIR"], "scenes")
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def rodlab(*args, env=None):
    return subprocess.run([RODLAB, *map(str, args)], capture_output=True, text=True,
                          env=None if env is None else {**os.environ, **env})


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    """One result of every kind, made by the real rodlab (about a second in all)."""
    d = tmp_path_factory.mktemp("results")
    runs = {
        "static": ["static", f"{SCENES}/cable-driven.yaml", "--out", d / "static.json"],
        "dynamic": ["dynamic", f"{SCENES}/cantilever-gravity.yaml", "--t-end", "0.1",
                    "--out", d / "dynamic.json"],
        "workspace": ["workspace", f"{SCENES}/cable-driven.yaml", "--samples", "20",
                      "--out", d / "workspace.json"],
        "control": ["control", f"{SCENES}/control-cable.yaml", "--controller", "quasi-static",
                    "--task", "reach", "--targets", "2", "--out", d / "control.json"],
        "convergence": ["study", "convergence", f"{SCENES}/cantilever-gravity.yaml",
                        "--schemes", "rkmk-rk4,chebyshev", "--nodes", "4,8,16",
                        "--out", d / "convergence"],
        "work-precision": ["study", "work-precision", f"{SCENES}/cantilever-gravity.yaml",
                           "--schemes", "rkmk-rk4,chebyshev", "--nodes", "4,8",
                           "--repeats", "1", "--out", d / "work-precision"],
    }
    for kind, args in runs.items():
        quiet = ["--quiet"] if args[0] in ("dynamic", "workspace", "study") else []
        p = rodlab(*args, *quiet)
        assert p.returncode == 0, (kind, p.stderr)
    return {kind: d / (kind if args[0] == "study" else f"{kind}.json")
            for kind, args in runs.items()}


def plot(*args, env=None):
    """Runs rodlab plot; returns the process. Exit 0 must name the figure."""
    p = rodlab("plot", *args, env=env)
    if p.returncode == 0:
        assert p.stdout.startswith("figure written to "), p.stdout
    return p


def png_size(path):
    """(width, height) from the IHDR chunk, right after the signature."""
    data = path.read_bytes()
    assert data.startswith(PNG_SIGNATURE)
    assert data[12:16] == b"IHDR"
    return struct.unpack(">II", data[16:24])


def gif_frames(path):
    """The number of frames of a GIF: Pillow's count, else the image descriptors found by
    walking the GIF's blocks (GIF89a specification: header, screen descriptor, global colour
    table, then extension blocks 0x21, image descriptors 0x2C, trailer 0x3B)."""
    try:
        from PIL import Image
        with Image.open(path) as im:
            return im.n_frames
    except ImportError:
        pass
    data = path.read_bytes()
    pos = 13 + (3 << ((data[10] & 7) + 1) if data[10] & 0x80 else 0)
    frames = 0

    def skip_sub_blocks(p):
        while data[p]:
            p += data[p] + 1
        return p + 1

    while data[pos] != 0x3B:
        if data[pos] == 0x21:  # extension: label, sub-blocks
            pos = skip_sub_blocks(pos + 2)
        elif data[pos] == 0x2C:  # image: descriptor, local colour table, LZW size, sub-blocks
            flags = data[pos + 9]
            pos += 10 + (3 << ((flags & 7) + 1) if flags & 0x80 else 0)
            pos = skip_sub_blocks(pos + 1)
            frames += 1
        else:
            raise AssertionError(f"not a GIF block at byte {pos}")
    return frames


def listing(directory):
    return sorted(os.listdir(directory))


@pytest.mark.parametrize("kind", ["static", "dynamic", "workspace", "control", "convergence",
                                  "work-precision"])
def test_every_kind_draws_a_png(results, tmp_path, kind):
    out = tmp_path / f"{kind}.png"
    p = plot(results[kind], "--out", out)
    assert p.returncode == 0, p.stderr
    assert p.stdout == f"figure written to {out}\n"
    assert out.stat().st_size > 10_000
    width, height = png_size(out)
    assert 600 <= width <= 4000 and 400 <= height <= 4000, (width, height)
    assert listing(tmp_path) == [f"{kind}.png"]  # the temporary file renamed, none left


def test_default_out_is_the_result_with_png(results, tmp_path):
    result = tmp_path / "run.json"
    shutil.copy(results["static"], result)
    assert plot(result).returncode == 0
    assert png_size(tmp_path / "run.png")[0] > 0
    # a study's directory: DIR/study.png
    study = tmp_path / "conv"
    shutil.copytree(results["convergence"], study)
    p = plot(study)
    assert p.returncode == 0, p.stderr
    assert p.stdout == f"figure written to {study / 'study.png'}\n"
    # and its study.json the same
    assert plot(study / "study.json", "--out", tmp_path / "conv.png").returncode == 0
    assert png_size(tmp_path / "conv.png")[0] > 0


def test_svg_and_pdf(results, tmp_path):
    for kind in ("static", "control", "work-precision"):
        out = tmp_path / f"{kind}.svg"
        assert plot(results[kind], "--out", out).returncode == 0
        root = ET.parse(out).getroot()
        assert root.tag in ("svg", "{http://www.w3.org/2000/svg}svg"), root.tag
    out = tmp_path / "dynamic.pdf"
    assert plot(results["dynamic"], "--out", out).returncode == 0
    assert out.read_bytes().startswith(b"%PDF-")


SVG = "{http://www.w3.org/2000/svg}"
XLINK_HREF = "{http://www.w3.org/1999/xlink}href"


def axis_map(axes, axis):
    """Pixel = a * value + b for one axis of a drawn matplotlib Axes, fitted through its tick
    marks (the <use> of each xtick_k/ytick_k group) and their labels (text, svg.fonttype none;
    U+2212 is matplotlib's minus). Returns (a, b) and the largest residual of the fit [px]."""
    marks = []
    for tick in axes.iter(SVG + "g"):
        if not tick.get("id", "").startswith(axis + "tick_"):
            continue
        use = next(tick.iter(SVG + "use"))
        label = "".join(next(tick.iter(SVG + "text")).itertext()).replace("\u2212", "-")
        marks.append((float(label), float(use.get(axis))))
    assert len(marks) >= 3, marks
    value, pixel = (np.array(c) for c in zip(*marks))
    (a, b), *_ = np.linalg.lstsq(np.c_[value, np.ones_like(value)], pixel, rcond=None)
    return (a, b), np.abs(a * value + b - pixel).max()


def path_vertices(d):
    """The vertices of an SVG path made of M and L commands (matplotlib's polylines)."""
    tokens = d.replace("M", " ").replace("L", " ").split()
    return np.array(tokens, dtype=float).reshape(-1, 2)


def test_drawn_tip_matches_the_result(results, tmp_path):
    """The tip-against-time panel of a dynamic result, read back from the SVG: every drawn
    vertex of the lines tip x and tip z, mapped to data by the axis ticks, is a sample (t, tip)
    of the result's series, and the last one its final tip. Tolerance: 0.01 px in data units
    (the SVG's coordinates have 6 decimals; the tick labels are exact to 2 digits, so the fit
    through them is exact to its residual, asserted below 1e-3 px)."""
    import json
    out = tmp_path / "dynamic.svg"
    assert plot(results["dynamic"], "--out", out).returncode == 0
    series = json.loads(results["dynamic"].read_text())["series"]
    t, tip = np.array(series["t"]), np.array(series["tip_position"])
    axes = next(g for g in ET.parse(out).getroot().iter(SVG + "g")
                if g.get("id", "").startswith("axes_")
                and any(line.get("id") == "tip_x" for line in g.iter(SVG + "g")))
    (ax, bx), fit_x = axis_map(axes, "x")
    (ay, by), fit_y = axis_map(axes, "y")
    assert fit_x < 1e-3 and fit_y < 1e-3, (fit_x, fit_y)
    for k, name in ((0, "x"), (2, "z")):
        group = next(g for g in axes.iter(SVG + "g") if g.get("id") == f"tip_{name}")
        drawn = path_vertices(next(group.iter(SVG + "path")).get("d"))
        drawn_t, drawn_tip = (drawn[:, 0] - bx) / ax, (drawn[:, 1] - by) / ay
        tolerance_t, tolerance_tip = 0.01 / abs(ax), 0.01 / abs(ay)
        assert len(drawn) >= 2
        nearest = np.abs(t[None, :] - drawn_t[:, None]).argmin(axis=1)
        assert np.abs(t[nearest] - drawn_t).max() < tolerance_t, name
        assert np.abs(tip[nearest, k] - drawn_tip).max() < tolerance_tip, name
        assert abs(drawn_t[-1] - t[-1]) < tolerance_t
        assert abs(drawn_tip[-1] - tip[-1, k]) < tolerance_tip, (name, drawn_tip[-1], tip[-1, k])
    # the rod sags across its length (gravity along -x): the drawn tip left x = 0
    assert tip[-1, 0] < -5 * tolerance_tip


def test_gif_animation_of_a_dynamic_result(results, tmp_path):
    out = tmp_path / "tip.gif"
    p = plot(results["dynamic"], "--out", out)
    assert p.returncode == 0, p.stderr
    assert out.read_bytes()[:6] in (b"GIF89a", b"GIF87a")
    assert gif_frames(out) > 1
    assert listing(tmp_path) == ["tip.gif"]


def test_mp4_needs_ffmpeg(results, tmp_path):
    out = tmp_path / "tip.mp4"
    p = plot(results["dynamic"], "--out", out)
    if shutil.which("ffmpeg"):
        assert p.returncode == 0, p.stderr
        assert out.read_bytes()[4:8] == b"ftyp"  # an ISO media file
    else:
        assert p.returncode == 1
        assert "ffmpeg" in p.stderr and ".gif" in p.stderr, p.stderr
        assert listing(tmp_path) == []


def bad_input(args, words, directory):
    """Exit 2, a message naming the file or option, nothing written into `directory`."""
    before = listing(directory)
    p = plot(*args)
    assert p.returncode == 2, (p.returncode, p.stdout, p.stderr)
    assert p.stdout == ""
    for w in words:
        assert w in p.stderr, (w, p.stderr)
    assert listing(directory) == before


def test_bad_input_writes_nothing(results, tmp_path):
    missing = tmp_path / "missing.json"
    bad_input([missing], ["RESULT", str(missing), "no such file"], tmp_path)
    other = tmp_path / "other.json"
    other.write_text('{"schema": "rodlab.scene/1"}\n')
    bad_input([other], [str(other), "not a rodlab result", "rodlab.scene/1"], tmp_path)
    text = tmp_path / "notes.json"
    text.write_text("not json\n")
    bad_input([text], [str(text), "not JSON"], tmp_path)
    csv = tmp_path / "static.csv"
    assert rodlab("static", f"{SCENES}/cable-driven.yaml", "--out", csv).returncode == 0
    bad_input([csv], [str(csv), "not JSON", ".json"], tmp_path)
    static = results["static"]
    bad_input([static, "--out", tmp_path / "x.jpg"], ["--out", "x.jpg", ".png"], tmp_path)
    bad_input([static, "--out", tmp_path / "x"], ["--out", ".png"], tmp_path)
    bad_input([static, "--out", tmp_path / "x.gif"], ["--out", "dynamic result only"], tmp_path)
    bad_input([static, "--out", tmp_path / "no" / "x.png"], ["--out", "does not exist"],
              tmp_path)
    bad_input([static, "--out", tmp_path], ["--out", "is a directory"], tmp_path)
    bad_input([], ["RESULT"], tmp_path)
    stability = tmp_path / "stability"
    stability.mkdir()
    (stability / "study.json").write_text('{"schema": "rodlab.study/1", "kind": "stability"}')
    bad_input([stability], ["stability study", "convergence"], stability)
    bad_input([tmp_path], ["study.json", "no such file"], tmp_path)  # a directory, no study


def test_without_a_usable_python(results, tmp_path):
    out = tmp_path / "s.png"
    p = plot(results["static"], "--out", out, env={"RODLAB_PYTHON": "/nonexistent/python3"})
    assert p.returncode == 1
    assert "/nonexistent/python3 not found" in p.stderr, p.stderr
    # Debian's python3 without its site packages: no matplotlib (the script's exit status 3)
    p = plot(results["static"], "--out", out, env={"RODLAB_PYTHON": "/usr/bin/python3 -S"})
    assert p.returncode == 1
    assert "cannot import matplotlib" in p.stderr and "python3-matplotlib" in p.stderr, p.stderr
    assert listing(tmp_path) == []


def test_a_failed_drawing_keeps_the_old_figure(results, tmp_path):
    """A result whose schema is right but whose content is not: exit 1, the traceback's tail,
    and the figure already there untouched (the script renames only a finished file)."""
    out = tmp_path / "s.png"
    assert plot(results["static"], "--out", out).returncode == 0
    before = out.read_bytes()
    broken = tmp_path / "broken.json"
    broken.write_text('{"schema": "rodlab.static-result/1", "centerline": 3}\n')
    p = plot(broken, "--out", out)
    assert p.returncode == 1
    assert "failed" in p.stderr and "TypeError" in p.stderr, p.stderr
    assert out.read_bytes() == before
    assert listing(tmp_path) == ["broken.json", "s.png"]
