#!/usr/bin/env python3
"""Draws a rodlab result file, or a study, with matplotlib.

    python3 scripts/rodlab_plot.py RESULT OUT

RESULT is a JSON result file of rodlab, or a study's directory or its study.json:

    rodlab.static-result/1     the centreline in 3D (equal axes), base and tip marked
    rodlab.dynamic-result/1    the tip's x, y, z and the energies against t; in 3D the final
                               centreline and the tip's trajectory. OUT .gif or .mp4: an
                               animation of the tip moving along its trajectory with its trail
                               (a dynamic result holds the tip's series and the final centreline
                               only, so the shape drawn is the final one and does not move)
    rodlab.workspace-result/1  the converged tips as a point cloud in 3D (equal axes),
                               coloured by the constant-curvature fit's omega
    rodlab.control-result/1    the tip and the target against t (x, y, z; episodes one after
                               another), and the tip error
    rodlab.study/1             convergence: error against ds or dt, log-log, with dashed slopes
                               of the expected orders; work-precision: error against median wall
                               time, the Pareto front joined (both drawn by
                               validation/make_figures.py's `draw`)

OUT ends in .png, .svg or .pdf (a figure) or, for a dynamic result, .gif (Pillow) or .mp4
(ffmpeg on the PATH). It is written atomically: to a temporary file in its directory, then
renamed. `rodlab plot` checks its arguments and runs this script (docs/cli.md).

Exit status: 0 drawn; 1 the drawing failed, or .mp4 without ffmpeg; 2 bad usage or RESULT is
not a result this script draws (nothing written); 3 matplotlib or numpy cannot be imported.
"""
import contextlib
import json
import os
import re
import sys
import tempfile
import textwrap
import traceback

# The figures' look and the study diagrams are the validation report's.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir,
                                "validation"))
import make_figures  # noqa: E402  (standard library only at import)

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    from matplotlib import animation, ticker
    IMPORT_ERROR = None
except ImportError as e:  # reported by main(): exit 3, "unavailable" to `rodlab plot`
    IMPORT_ERROR = e

STATIC = "rodlab.static-result/1"
DYNAMIC = "rodlab.dynamic-result/1"
WORKSPACE = "rodlab.workspace-result/1"
CONTROL = "rodlab.control-result/1"
STUDY = "rodlab.study/1"
STUDY_KINDS = ("convergence", "work-precision")
PICTURES = (".png", ".svg", ".pdf")
ANIMATIONS = (".gif", ".mp4")
ENERGIES = ("kinetic", "strain", "gravity", "dissipated", "work_in", "total")
DPI = 150          # PNG: 7 x 4.4 in -> 1050 x 660 pixels
MAX_FRAMES = 80    # an animation samples the tip series at most this often ...
FPS = 20           # ... and shows them at this rate: at most 4 s


class PlotError(Exception):
    """A figure that cannot be drawn, with the reason for the user (exit 1)."""


def main(argv):
    if len(argv) == 2 and argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0
    if len(argv) != 3:
        print("usage: rodlab_plot.py RESULT OUT (--help for more)", file=sys.stderr)
        return 2
    result, out = argv[1], argv[2]
    doc, problem = read_result(result)
    ext = os.path.splitext(out)[1].lower()
    if doc is not None and ext not in PICTURES + ANIMATIONS:
        problem = f"{out}: OUT must end in {', '.join(PICTURES + ANIMATIONS)}"
    elif doc is not None and ext in ANIMATIONS and doc["schema"] != DYNAMIC:
        problem = f"{out}: an animation is drawn from a dynamic result only"
    if problem:
        print(f"rodlab_plot: {problem}", file=sys.stderr)
        return 2
    if IMPORT_ERROR is not None:
        print(f"rodlab_plot: cannot import matplotlib/numpy ({IMPORT_ERROR})")
        return 3
    matplotlib.rcParams.update(make_figures.STYLE)
    try:
        if ext in ANIMATIONS:
            animate_dynamic(doc, out)
        else:
            save_figure(DRAWERS[doc["schema"]](doc), out)
    except PlotError as e:
        print(f"rodlab_plot: {e}", file=sys.stderr)
        return 1
    except Exception:  # a result this script does not understand: the traceback says where
        traceback.print_exc()
        return 1
    print(f"rodlab_plot: {out} (matplotlib {matplotlib.__version__})")
    return 0


def read_result(path):
    """(document, None) when PATH (or PATH/study.json) is a result this script draws, else
    (None, why)."""
    if os.path.isdir(path):
        path = os.path.join(path, "study.json")
    try:
        with open(path, encoding="utf-8") as f:
            doc = json.load(f)
    except (OSError, ValueError) as e:
        return None, f"cannot read {path}: {e}"
    schema = doc.get("schema") if isinstance(doc, dict) else None
    if schema not in DRAWERS:
        return None, f"{path} is not a result this script draws (schema {schema!r})"
    if schema == STUDY and doc.get("kind") not in STUDY_KINDS:
        return None, f"{path}: a {doc.get('kind')} study; drawn are {', '.join(STUDY_KINDS)}"
    return doc, None


# --- writing ------------------------------------------------------------------------------


def save_atomically(out, write):
    """Calls write(tmp) for a temporary file beside OUT (same extension, which Pillow and
    ffmpeg go by), then renames it to OUT: no reader sees half a figure, and a failure leaves
    OUT as it was."""
    directory, name = os.path.split(os.path.abspath(out))
    fd, tmp = tempfile.mkstemp(prefix=f".{name}.", suffix=os.path.splitext(name)[1],
                               dir=directory)
    os.close(fd)
    try:
        write(tmp)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp's 0600 would make the figure private
        os.replace(tmp, out)
    except BaseException:
        with contextlib.suppress(OSError):
            os.remove(tmp)
        raise


def save_figure(fig, out):
    fmt = os.path.splitext(out)[1].lower()[1:]
    # No dates in SVG and PDF: the same result draws the same file.
    metadata = {"svg": {"Date": None}, "pdf": {"CreationDate": None}}.get(fmt)
    save_atomically(out, lambda tmp: fig.savefig(tmp, format=fmt, dpi=DPI, metadata=metadata))
    plt.close(fig)


# --- data ---------------------------------------------------------------------------------


def column(values):
    """Numbers (JSON null, the writers' NaN, as NaN) as a float array."""
    return np.array([np.nan if v is None else v for v in values], dtype=float)


def points(values):
    """[x, y, z] lists (a null point as NaNs) as an n x 3 array."""
    return np.array([[np.nan] * 3 if p is None else p for p in values],
                    dtype=float).reshape(-1, 3)


def centreline(nodes):
    return points([n["position"] for n in nodes])


def heading(doc, what):
    """'scene: what (scheme, N = nodes)', and the reason on a second line when not converged."""
    text = f"{doc.get('scene', '?')}: {what} ({doc.get('scheme', '?')}, N = {doc.get('nodes')})"
    if doc.get("converged") is False:
        text += f"\nnot converged: {doc.get('reason') or 'no reason recorded'}"
    return text


# --- 3D -----------------------------------------------------------------------------------


def equal_axes(ax, *point_sets):
    """Cube limits around every finite point, so that a metre is as long on every axis."""
    pts = np.concatenate([p.reshape(-1, 3) for p in point_sets])
    pts = pts[np.isfinite(pts).all(axis=1)]
    if len(pts):
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        centre = (lo + hi) / 2
        half = 0.55 * float((hi - lo).max())
        if half <= 0:  # one point: a box of a tenth of its distance from the origin
            half = max(1e-3, 0.1 * float(np.abs(centre).max()))
        for set_limits, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre):
            set_limits(c - half, c + half)
    ax.set_box_aspect((1, 1, 1))
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):  # millimetre ticks would overlap
        axis.set_major_locator(ticker.MaxNLocator(5))
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_zlabel("z [m]")


def draw_rod(ax, line, label, faint=False):
    """A centreline with its nodes, the base (s = 0) and the tip (s = L) marked."""
    ax.plot(line[:, 0], line[:, 1], line[:, 2], "-o", color="C0", markersize=2.5,
            linewidth=2.0, alpha=0.35 if faint else 1.0, label=label)
    base, tip = line[0], line[-1]
    ax.scatter(*base, marker="s", s=45, color="k", depthshade=False, label="base (s = 0)")
    ax.scatter(*tip, marker="*", s=140, color="C3", depthshade=False,
               label=f"tip (s = L): [{tip[0]:.4g}, {tip[1]:.4g}, {tip[2]:.4g}] m")


# --- the result kinds ---------------------------------------------------------------------


def draw_static(doc):
    line = centreline(doc["centerline"])
    fig = plt.figure(figsize=(7.0, 6.2))
    ax = fig.add_subplot(projection="3d")
    draw_rod(ax, line, "centreline")
    equal_axes(ax, line)
    ax.legend(loc="upper left", fontsize=7)
    ax.set_title(heading(doc, "static equilibrium"), fontsize=10)
    fig.tight_layout()
    return fig


def draw_dynamic(doc):
    """Left: the tip's coordinates and the energies against t; right: the final centreline
    and the tip's trajectory in 3D."""
    series = doc["series"]
    t, tip = column(series["t"]), points(series["tip_position"])
    line = centreline(doc["final"]["centerline"])
    fig = plt.figure(figsize=(12.0, 6.6))
    grid = fig.add_gridspec(2, 2, width_ratios=(1.2, 1.0))
    ax = fig.add_subplot(grid[0, 0])
    for k, name in enumerate("xyz"):
        ax.plot(t, tip[:, k], label=f"tip {name}", gid=f"tip_{name}")  # the SVG's ids
    ax.set_ylabel("tip position [m]")
    ax.legend(loc="best")
    ax.set_title("tip against time", fontsize=10)
    ax = fig.add_subplot(grid[1, 0], sharex=ax)
    energies = series.get("energy") or {}
    for name in ENERGIES:  # whichever the result holds
        e = column(energies.get(name) or [])
        if np.isfinite(e).any():
            style = {"color": "k", "linewidth": 1.8} if name == "total" else {}
            ax.plot(t, e, label=name.replace("_", " "), **style)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("energy [J]")
    if ax.get_lines():
        ax.legend(loc="best")
    ax.set_title("energies", fontsize=10)
    ax = fig.add_subplot(grid[:, 1], projection="3d")
    ax.plot(tip[:, 0], tip[:, 1], tip[:, 2], color="C1", linewidth=1.0, label="tip trajectory")
    draw_rod(ax, line, "final centreline")
    equal_axes(ax, line, tip)
    ax.legend(loc="upper left", fontsize=7)
    end = t[-1] if len(t) else 0.0
    fig.suptitle(heading(doc, f"dynamics to t = {end:.4g} s"), fontsize=11)
    fig.tight_layout()
    return fig


def animate_dynamic(doc, out):
    """The tip moving along its trajectory, with its trail, in front of the final centreline
    (the only shape a dynamic result holds)."""
    mp4 = out.lower().endswith(".mp4")
    if mp4 and not animation.FFMpegWriter.isAvailable():
        raise PlotError(f"{out}: an .mp4 needs ffmpeg on the PATH, and there is none; install "
                        "ffmpeg, or write a .gif (drawn with Pillow)")
    series = doc["series"]
    t, tip = column(series["t"]), points(series["tip_position"])
    if not len(t):
        raise PlotError("the result has no time series to animate")
    line = centreline(doc["final"]["centerline"])
    fig = plt.figure(figsize=(6.4, 5.8))
    ax = fig.add_subplot(projection="3d")
    draw_rod(ax, line, "final centreline (the result holds no other shape)", faint=True)
    trail, = ax.plot([], [], [], "-", color="C1", linewidth=1.2, label="tip trail")
    point, = ax.plot([], [], [], "o", color="C3", markersize=7, label="tip")
    equal_axes(ax, line, tip)
    ax.legend(loc="upper left", fontsize=7)
    frames = np.unique(np.linspace(0, len(t) - 1, min(len(t), MAX_FRAMES)).round().astype(int))

    def show(i):
        trail.set_data_3d(tip[:i + 1, 0], tip[:i + 1, 1], tip[:i + 1, 2])
        point.set_data_3d(tip[i:i + 1, 0], tip[i:i + 1, 1], tip[i:i + 1, 2])
        ax.set_title(f"{doc.get('scene', '?')}: tip at t = {t[i]:.4f} s", fontsize=10)
        return trail, point

    movie = animation.FuncAnimation(fig, show, frames=frames, blit=False)
    writer = animation.FFMpegWriter(fps=FPS) if mp4 else animation.PillowWriter(fps=FPS)
    save_atomically(out, lambda tmp: movie.save(tmp, writer=writer, dpi=100))
    plt.close(fig)


def draw_workspace(doc):
    tips = [s for s in doc.get("tips", []) if s.get("converged") and s.get("tip") is not None]
    fig = plt.figure(figsize=(7.4, 6.2))
    ax = fig.add_subplot(projection="3d")
    if tips:
        cloud = points([s["tip"] for s in tips])
        omega = column([s.get("omega") for s in tips])
        if np.isfinite(omega).all():
            dots = ax.scatter(*cloud.T, c=omega, cmap="viridis", s=16, depthshade=False)
            fig.colorbar(dots, ax=ax, shrink=0.6, pad=0.12, label="curvature omega [1/m]")
        else:
            ax.scatter(*cloud.T, s=16, depthshade=False)
        equal_axes(ax, cloud)
    else:
        ax.text2D(0.5, 0.5, "no converged sample", transform=ax.transAxes, ha="center")
    ax.set_title(heading(doc, f"workspace, {len(tips)} of {doc.get('samples', '?')} tips"),
                 fontsize=10)
    return fig


def control_axis(series):
    """The abscissa of a control run: t, each episode's times after the previous episode's
    last (t restarts in every episode), or the control step when that does not increase (the
    quasi-static controller's steps take no time); and the episodes' bounds: 0, the index of
    each episode's first row, the number of rows."""
    t = column(series.get("t", []))
    episodes = series.get("episode") or [0] * len(t)
    shifted, starts, offset, last = [], [], 0.0, 0.0
    for i, (ti, episode) in enumerate(zip(t, episodes)):
        if i and episode != episodes[i - 1]:
            offset += last
            starts.append(i)
        last = ti
        shifted.append(ti + offset)
    x = np.array(shifted, dtype=float)
    if len(x) > 1 and np.all(np.diff(x) > 0):
        label = "t [s]" + (" (the episodes one after another)" if starts else "")
    else:
        x, label = np.arange(len(t), dtype=float), "control step"
    return x, label, [0, *starts, len(x)]


def draw_control(doc):
    """x, y, z of the tip (solid) and the target (dashed) against t, and the tip error; each
    episode's lines apart (the target jumps between them), their borders dotted."""
    series = doc["series"]
    x, xlabel, bounds = control_axis(series)
    tip, target = points(series.get("tip", [])), points(series.get("target", []))
    error = column(series.get("error", []))
    fig, axes = plt.subplots(2, 2, figsize=(10.0, 6.6), sharex=True)
    few = len(x) <= 40  # few steps: show each one (a one-step episode is a point)
    fmt, target_fmt = ("o-", "x--") if few else ("-", "--")
    for a, b in zip(bounds[:-1], bounds[1:]):
        first = a == 0  # one legend entry for all the episodes
        for k, ax in enumerate(axes.flat[:3]):
            ax.plot(x[a:b], tip[a:b, k], fmt, color="C0", markersize=3,
                    label="tip" if first else None)
            ax.plot(x[a:b], target[a:b, k], target_fmt, color="k", linewidth=1.0,
                    label="target" if first else None)
        axes.flat[3].plot(x[a:b], error[a:b], fmt, color="C3", markersize=3)
        if not first:
            for ax in axes.flat:
                ax.axvline((x[a - 1] + x[a]) / 2, color="0.5", linewidth=0.8, linestyle=":")
    for k, ax in enumerate(axes.flat[:3]):
        ax.set_ylabel(f"{'xyz'[k]} [m]")
    axes.flat[0].legend(loc="best")
    if len(error) and np.all(np.isfinite(error) & (error > 0)):
        axes.flat[3].set_yscale("log")
    axes.flat[3].set_ylabel("tip error |tip - target| [m]")
    for ax in axes[1]:
        ax.set_xlabel(xlabel)
        if xlabel == "control step":
            ax.xaxis.set_major_locator(ticker.MaxNLocator(integer=True))
    what = f"{doc.get('controller', '?')} on {doc.get('task', '?')}"
    fig.suptitle(heading(doc, what), fontsize=11)
    fig.tight_layout()
    return fig


# --- studies --------------------------------------------------------------------------------


def study_variable(doc):
    """What a convergence study refines: 'dt' (dynamics, --refine time) or 'ds'."""
    for order in doc.get("orders") or []:
        if order.get("variable"):
            return order["variable"]
    settings = doc.get("settings") or {}
    return "dt" if settings.get("problem") == "dynamics" and settings.get("refine") == "time" \
        else "ds"


def expected_slopes(doc, variable):
    """The expected orders, as slopes of the error against h: '4' or, for dynamics,
    '2 (t) / 2 (s)' (the one of the refined variable); 'spectral' has none."""
    slopes = set()
    for order in doc.get("orders") or []:
        text = str(order.get("expected_order") or "")
        if "(" in text:
            found = re.search(r"([0-9.]+) \(" + variable[1] + r"\)", text)  # (t) or (s)
        else:
            found = re.fullmatch(r"([0-9.]+)", text)
        if found:
            slopes.add(float(found.group(1)))
    return sorted(slopes)


def draw_study(doc):
    """A convergence or work-precision study as the validation report draws it: a table of the
    study's runs (the reference run left out) and a figure spec for make_figures.draw."""
    rows = [r for r in doc.get("rows", []) if r.get("role") == "study"]
    kind, variable = doc.get("kind"), study_variable(doc)
    by_nodes = kind == "convergence" and variable == "dt"  # one curve per scheme and N
    table = {
        "series": [f"{r['scheme']}, N = {r['nodes']}" if by_nodes else r["scheme"] for r in rows],
        "h": column([r.get("h") for r in rows]),
        "error": column([r.get("error") for r in rows]),
        "wall_time_s": column([r.get("wall_time_s") for r in rows]),
        "pareto": column([1.0 if r.get("pareto") else 0.0 for r in rows]),
    }
    reference = (doc.get("reference") or {}).get("description") or "the reference"
    # The error column's measure, without the note on max_error (a column not drawn here).
    ylabel = textwrap.fill((doc.get("error_measure") or "error").split(";")[0], 40)
    if kind == "convergence":
        spec = {"kind": "loglog", "x": "h", "y": ["error"], "series": "series",
                "style": "lines+markers", "reference_slopes": expected_slopes(doc, variable),
                "xlabel": "dt [s]" if variable == "dt" else "ds [m]",
                "title": f"{doc.get('scene', '?')}: convergence against {reference}"}
    else:
        spec = {"kind": "pareto", "x": "wall_time_s", "y": ["error"], "series": "series",
                "style": "markers", "xlabel": "median wall time [s]",
                "title": f"{doc.get('scene', '?')}: work-precision against {reference}"}
    spec["ylabel"] = ylabel
    spec["title"] = textwrap.fill(spec["title"], 80)
    return make_figures.draw(plt, np, table, spec)


DRAWERS = {STATIC: draw_static, DYNAMIC: draw_dynamic, WORKSPACE: draw_workspace,
           CONTROL: draw_control, STUDY: draw_study}

if __name__ == "__main__":
    sys.exit(main(sys.argv))
