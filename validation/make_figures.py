#!/usr/bin/env python3
"""Draws every figure of a rodlab validation report from its data.

    python3 validation/make_figures.py DIR

DIR is the output directory of `rodlab validate` (default out/validation) or of a study that
draws figures (`rodlab study control`). The script reads DIR/report.json (schema
rodlab.validation-report/1), else DIR/figures.json (schema rodlab.figures/1, the same list of
data sets), and for every data set listed there reads
DIR/data/NAME.csv and draws each of its figures to DIR/figures/FIGURE.svg, following the figure
spec in report.json:

    kind      line | loglog | semilogy | semilogx | shape (equal axes) | map (x, y coloured by y[0]...)
              | pareto (work-precision: loglog of y against x per series, style markers; the rows
              whose `pareto` column is 1 joined as the Pareto front, those whose `recommended`
              column is 1 starred)
    x, y      column names (one curve per y column)
    series    optional column: one curve per distinct value (and per y column); map: one
              row of the map per distinct value (then y[1] is not needed)
    reference_slopes  loglog: dashed lines y ~ x^slope (e.g. -1, -2, -4 for errors against N)
    style     lines | markers | lines+markers
    absolute  plot |y| (signed errors on log axes)
    select    only the rows whose series value starts with this text

Nothing else is read and nothing is computed here beyond drawing: the numbers are the ones the
rodlab binary wrote. `rodlab validate` runs this script itself at the end (without matplotlib
it says so in the report). Exit status: 0 every figure drawn; 1 some figure failed (the others
are still drawn); 2 bad usage or no report; 3 matplotlib or numpy cannot be imported.
"""
import csv
import json
import math
import os
import sys

# The look of every rodlab figure (also scripts/rodlab_plot.py's).
STYLE = {
    "svg.fonttype": "none",      # text stays text: small files, searchable
    "svg.hashsalt": "rodlab",    # reproducible ids
    "figure.figsize": (7.0, 4.4),
    "axes.grid": True,
    "grid.alpha": 0.3,
    "legend.fontsize": 8,
}


def main(argv):
    if len(argv) > 2 or (len(argv) == 2 and argv[1] in ("-h", "--help")):
        print(__doc__.strip())
        return 0 if len(argv) == 2 else 2
    out_dir = argv[1] if len(argv) == 2 else os.path.join("out", "validation")
    report, problem = read_figure_index(out_dir)
    if report is None:
        print(f"make_figures: {problem}", file=sys.stderr)
        return 2

    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        import numpy as np
    except ImportError as e:
        print(f"make_figures: cannot import matplotlib/numpy ({e})")
        return 3

    print(f"rodlab-figures: matplotlib {matplotlib.__version__}, numpy {np.__version__}")
    matplotlib.rcParams.update(STYLE)
    os.makedirs(os.path.join(out_dir, "figures"), exist_ok=True)

    failures = 0
    drawn = 0
    for data in report.get("data_sets", []):
        if not data.get("figures"):
            continue
        try:
            table = read_csv(os.path.join(out_dir, data["file"]))
        except (OSError, ValueError, KeyError) as e:
            print(f"make_figures: data set {data.get('name')}: {e}", file=sys.stderr)
            failures += len(data["figures"])
            continue
        for spec in data["figures"]:
            path = os.path.join(out_dir, spec["file"])
            try:
                fig = draw(plt, np, table, spec)
                fig.savefig(path + ".tmp", format="svg", metadata={"Date": None})
                plt.close(fig)
                os.replace(path + ".tmp", path)
                drawn += 1
                print(f"  {spec['file']}")
            except Exception as e:  # one bad figure must not stop the others
                plt.close("all")
                print(f"make_figures: figure {spec.get('name')}: {type(e).__name__}: {e}",
                      file=sys.stderr)
                failures += 1
    print(f"make_figures: {drawn} figures drawn, {failures} failed")
    return 1 if failures else 0


def read_figure_index(out_dir):
    """The data sets and figure specs of DIR: DIR/report.json (rodlab.validation-report/1), or,
    in a study's directory, DIR/figures.json (rodlab.figures/1: the same data_sets list, e.g.
    `rodlab study control`). Returns (index, None) or (None, why)."""
    for name, schema in (("report.json", "rodlab.validation-report/1"),
                         ("figures.json", "rodlab.figures/1")):
        path = os.path.join(out_dir, name)
        if not os.path.exists(path):
            continue
        try:
            with open(path, encoding="utf-8") as f:
                index = json.load(f)
        except (OSError, ValueError) as e:
            return None, f"cannot read {path}: {e}"
        if index.get("schema") != schema:
            return None, f"{path} is not a {schema}"
        return index, None
    return None, f"cannot read {os.path.join(out_dir, 'report.json')} (nor figures.json)"


def read_csv(path):
    """Columns by name: numeric columns as lists of floats, label columns as lists of str."""
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    if not rows:
        raise ValueError(f"{path} is empty")
    header, body = rows[0], rows[1:]
    columns = {}
    for i, name in enumerate(header):
        values = [r[i] for r in body]
        try:
            columns[name] = [float(v) for v in values]
        except ValueError:
            columns[name] = values
    return columns


def curves(table, spec):
    """(label, x, y) for every curve of the figure, in order of first appearance."""
    xs = table[spec["x"]]
    series = spec.get("series") or ""
    select = spec.get("select") or ""
    out = []
    for ycol in spec["y"]:
        ys = table[ycol]
        if series:
            keys = []
            for k in table[series]:
                if k not in keys and str(k).startswith(select):
                    keys.append(k)
            for k in keys:
                idx = [i for i, v in enumerate(table[series]) if v == k]
                label = str(k)[len(select):].strip() if len(spec["y"]) == 1 else f"{k}: {ycol}"
                out.append((label, [xs[i] for i in idx], [ys[i] for i in idx]))
        else:
            out.append((ycol, list(xs), list(ys)))
    return out


def draw_pareto(np, ax, table, spec):
    """Work-precision: markers per series on log-log axes, the Pareto front (rows with
    pareto = 1) as a line in order of x, the recommended rows (recommended = 1) starred."""
    for label, x, y in curves(table, spec):
        x, y = np.array(x, dtype=float), np.array(y, dtype=float)
        keep = np.isfinite(x) & np.isfinite(y) & (x > 0) & (y > 0)
        if keep.any():
            ax.plot(x[keep], y[keep], "o", label=label, markersize=5, alpha=0.85)
    xs = np.array(table[spec["x"]], dtype=float)
    ys = np.array(table[spec["y"][0]], dtype=float)
    for column, fmt, label in (("pareto", "k-", "Pareto front"),
                               ("recommended", "k*", "recommended")):
        if column not in table:
            continue
        flag = np.array(table[column], dtype=float) == 1
        keep = flag & np.isfinite(xs) & np.isfinite(ys) & (xs > 0) & (ys > 0)
        if not keep.any():
            continue
        order = np.argsort(xs[keep], kind="stable")
        if column == "pareto":
            ax.plot(xs[keep][order], ys[keep][order], fmt, linewidth=1.0, alpha=0.7,
                    drawstyle="steps-post", label=label)
        else:
            ax.plot(xs[keep][order], ys[keep][order], fmt, markersize=14, fillstyle="none",
                    label=label)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.legend(loc="best", fontsize=7)


def draw(plt, np, table, spec):
    kind = spec.get("kind", "line")
    fig, ax = plt.subplots()
    if kind == "map":
        select = spec.get("select") or ""
        if select and spec.get("series"):  # only the rows whose series value starts with it
            keep = [i for i, k in enumerate(table[spec["series"]]) if str(k).startswith(select)]
            table = {c: [v[i] for i in keep] for c, v in table.items()}
        x, z = np.array(table[spec["x"]]), np.array(table[spec["y"][0]])
        if spec.get("series"):
            keys = []
            for k in table[spec["series"]]:
                if k not in keys:
                    keys.append(k)
            y = np.array([keys.index(k) for k in table[spec["series"]]], dtype=float)
            ax.set_yticks(range(len(keys)))
            ax.set_yticklabels([str(k)[len(select):] for k in keys], fontsize=7)
            ax.set_ylim(-0.5, len(keys) - 0.5)
        else:
            y = np.array(table[spec["y"][1]])
        sc = ax.scatter(x, y, c=z, cmap="viridis", s=60)
        fig.colorbar(sc, ax=ax, label=spec["y"][0])
    elif kind == "pareto":
        draw_pareto(np, ax, table, spec)
    else:
        style = spec.get("style", "lines")
        fmt = {"lines": "-", "markers": "o", "lines+markers": "o-"}.get(style, "-")
        logx = kind in ("loglog", "semilogx")
        logy = kind in ("loglog", "semilogy")
        first_points = []
        for label, x, y in curves(table, spec):
            x, y = np.array(x, dtype=float), np.array(y, dtype=float)
            if spec.get("absolute"):
                y = np.abs(y)
            keep = np.isfinite(x) & np.isfinite(y)
            if logx:
                keep &= x > 0
            if logy:
                keep &= y > 0
            if kind == "shape" and np.all(np.abs(y) < 1e-14):
                continue  # a lateral coordinate that stays zero: nothing to see
            if not keep.any():
                continue
            order = np.argsort(x[keep], kind="stable") if kind in ("loglog",) else slice(None)
            xk, yk = x[keep][order], y[keep][order]
            ax.plot(xk, yk, fmt, label=label, markersize=4, linewidth=1.3)
            first_points.append((xk[0], yk[0]))
        if logx:
            ax.set_xscale("log")
        if logy:
            ax.set_yscale("log")
        if kind == "loglog" and spec.get("reference_slopes") and first_points:
            xs = np.array(table[spec["x"]], dtype=float)
            xs = xs[np.isfinite(xs) & (xs > 0)]
            x0, x1 = xs.min(), xs.max()
            y_anchor = float(np.median([p[1] for p in first_points]))
            for slope in spec["reference_slopes"]:
                # y ~ x^slope through (x0, 2 y_anchor) when falling, (x0, y_anchor / 2) when rising.
                xx = np.array([x0, x1])
                yy = y_anchor * (2.0 if slope < 0 else 0.5) * (xx / x0) ** slope
                ax.plot(xx, yy, "k--", linewidth=0.8, alpha=0.6)
                ax.annotate(f"slope {slope:g}", (xx[1], yy[1]), fontsize=7, alpha=0.8)
        if kind == "shape":
            ax.set_aspect("equal", adjustable="datalim")
        if len(ax.get_lines()) > 1 or spec.get("series"):
            ax.legend(loc="best")
    ax.set_title(spec.get("title", ""), fontsize=10)
    ax.set_xlabel(spec.get("xlabel") or spec["x"])
    ax.set_ylabel(spec.get("ylabel") or ", ".join(spec["y"]))
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    sys.exit(main(sys.argv))
