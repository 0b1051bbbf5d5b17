"""The side-by-side of docs/performance.md: every code's work-precision points on one figure, and
per error level the least wall time at which each code gets there and the ratios to rodlab.

    python3 bench/peers/rodlab_cantilever.py            # <work>/rodlab-undamped.csv
    python3 bench/peers/till_cantilever.py --till DIR   # <work>/till-undamped.csv (if present)
    python3 bench/peers/side_by_side.py [--figure docs/figures/peers-work-precision.svg]

"Time to reach e" is the least median wall time among a code's runs with max tip error <= e (no
interpolation between runs). A code with no run at or below e has not reached it. Codes without
a CSV (not on the machine) are left out and named.
"""
import argparse
import glob
import itertools
import math
import os

import common

LEVELS = (1e-2, 5e-3, 3e-3, 2e-3, 1e-3, 3e-4, 1e-4)


def time_to_reach(rows, level):
    times = [r["wall_ms"] for r in rows if r["max_tip_error_m"] <= level]
    return min(times) if times else math.inf


def front(rows):
    """The Pareto front (error falling as wall time rises), in wall-time order."""
    out, best = [], math.inf
    for r in sorted(rows, key=lambda r: (r["wall_ms"], r["max_tip_error_m"])):
        if r["max_tip_error_m"] < best:
            out.append(r)
            best = r["max_tip_error_m"]
    return out


def table(codes):
    peers = [c for c in codes if c != "rodlab"]
    head = "| max tip error | rodlab | " + " | ".join(f"{p} | rodlab faster by" for p in peers) + " |"
    rule = "|---" * (2 + 2 * len(peers)) + "|"
    lines = [head, rule]
    fmt = lambda t: "not reached" if math.isinf(t) else f"{t:.3g} ms"
    for level in LEVELS:
        ours = time_to_reach(codes["rodlab"], level)
        cells = [f"{level:g} m", fmt(ours)]
        for p in peers:
            theirs = time_to_reach(codes[p], level)
            ratio = "-" if math.isinf(ours) or math.isinf(theirs) else f"{theirs / ours:.1f}x"
            cells += [fmt(theirs), ratio]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def figure(codes, path, case):
    import matplotlib
    matplotlib.use("Agg")
    matplotlib.rcParams["svg.hashsalt"] = "rodlab"  # reproducible ids
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    colours = {"rodlab": "tab:blue", "Till": "tab:red", "PyElastica": "tab:green"}
    markers = itertools.cycle("os^vD<>ph*")  # more configurations than shapes: repeat
    for code, rows in codes.items():
        colour = colours.get(code, "tab:gray")
        for config in sorted({r["configuration"] for r in rows}):
            pts = [r for r in rows if r["configuration"] == config]
            ax.loglog([r["wall_ms"] for r in pts], [r["max_tip_error_m"] for r in pts],
                      marker=next(markers), linestyle="none", markersize=4, alpha=0.55,
                      color=colour, label=f"{code}: {config}")
        best = front(rows)
        ax.loglog([r["wall_ms"] for r in best], [r["max_tip_error_m"] for r in best], "-",
                  color=colour, linewidth=1.6, label=f"{code}: fastest at each error")
    ax.set_xlabel("wall time, median of repeats [ms] (one core)")
    ax.set_ylabel("max tip error over 0.5 s [m]")
    ax.set_title(f"Table 2.1 cantilever released under gravity ({case})")
    ax.grid(True, which="both", linewidth=0.3)
    ax.legend(fontsize=6.5, ncol=2)
    fig.tight_layout()
    kind = os.path.splitext(path)[1][1:] or "svg"
    tmp = path + ".tmp." + kind
    fig.savefig(tmp, format=kind, metadata={"Date": None} if kind == "svg" else None)
    os.replace(tmp, path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--viscosity", type=float, default=0.0)
    parser.add_argument("--work", default=common.DEFAULT_WORK)
    parser.add_argument("--figure", default="")
    a = parser.parse_args()
    case = common.case_name(a.viscosity)
    codes = {}
    names = {"rodlab": "rodlab", "till": "Till", "pyelastica": "PyElastica"}
    for path in sorted(glob.glob(os.path.join(a.work, f"*-{case}.csv"))):
        key = os.path.basename(path)[: -len(f"-{case}.csv")]
        if key in names:
            codes[names[key]] = common.read_rows(path)
    if "rodlab" not in codes:
        raise SystemExit(f"side_by_side: no rodlab-{case}.csv in {a.work}: run rodlab_cantilever.py")
    missing = [n for n in names.values() if n not in codes]
    print(table(codes))
    if missing:
        print(f"\nNot measured here (no CSV): {', '.join(missing)}")
    for code, rows in codes.items():
        print(f"\n{code} front: " + "; ".join(
            f"{r['configuration']} N={r['nodes']} dt={r['dt_s']:.3g}: {r['max_tip_error_m']:.3g} m "
            f"in {r['wall_ms']:.3g} ms" for r in front(rows)))
    if a.figure:
        figure(codes, a.figure, case)
        print(f"\nfigure written to {a.figure}")


if __name__ == "__main__":
    main()
