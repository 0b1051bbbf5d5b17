#!/usr/bin/env python3
"""The first solve against the warm one (issue #17, item 5; docs/statics.md "Cold and warm solves").

For each statics scheme it measures
  cold: the wall time a user sees in the result file of one `rodlab static` run (`wall_time_s`:
        the solve alone, in a fresh process), the median of --runs runs;
  warm: bench_statics' `static_solve/SCHEME/cosserat` (the same solve repeated in one process),
        the median of --repetitions repetitions;
on the same problem (scenes/cantilever-gravity.yaml: the Table 2.1 cantilever under gravity, tol
1e-10) at the benchmark's node count (chebyshev 24, the others 100), every process pinned to one
core. Prints a Markdown table with cold / warm; --json FILE also writes the figures (atomically).
Rounds (--rounds) interleave the cold and warm measurements and report the median of each
round's medians, with the rounds' range.

    python3 bench/cold_static.py                      # rkmk-rk4, chebyshev, kinsol; 15 runs
    python3 bench/cold_static.py --schemes all --rounds 3 --json cold.json

--copy runs a copy of rodlab made in 1 MB writes, not the build's binary. The kernel keeps a file
in the page cache in pieces (folios) as large as the writes that made it, and a first run faults
its code in by them: a just-linked binary, written in small pieces, costs rkmk-euler-explicit
about 20 us more a cold solve than the same bytes copied (docs/statics.md "Cold and warm solves",
kernel 6.18, ext4). To compare two builds, give both --copy, so that both are in the same state.

Time only on an idle machine (parallel builds distort timings). Exit 0 measured; 1 a run
failed (its stderr is shown); 2 bad usage (nothing written).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(HERE)
SCENE = os.path.join(SOURCE, "scenes", "cantilever-gravity.yaml")
DEFAULT_SCHEMES = ["rkmk-rk4", "chebyshev", "kinsol"]


def bench_nodes(scheme):
    """bench_statics' node count for a scheme (bench_statics.cpp nodes_for)."""
    return 24 if scheme == "chebyshev" else 100


class Failure(Exception):
    pass


def pinned(cpu):
    return None if cpu is None else (lambda: os.sched_setaffinity(0, {cpu}))


def statics_schemes(rodlab):
    """The statics schemes of `rodlab schemes` (the catalogue), in its order."""
    out = subprocess.run([rodlab, "schemes"], capture_output=True, text=True, check=True).stdout
    return [line.split()[0] for line in out.splitlines()
            if len(line.split()) > 1 and line.split()[1] == "statics"]


def cold_us(rodlab, scheme, runs, cpu, scratch):
    """Median wall_time_s of `runs` fresh `rodlab static` processes, in microseconds."""
    out = os.path.join(scratch, "cold.json")
    times = []
    for _ in range(runs):
        r = subprocess.run([rodlab, "static", SCENE, "--scheme", scheme,
                            "--nodes", str(bench_nodes(scheme)), "--out", out],
                           capture_output=True, text=True, preexec_fn=pinned(cpu))
        if r.returncode != 0:
            raise Failure(f"rodlab static --scheme {scheme} exited {r.returncode}:\n{r.stderr}")
        with open(out) as f:
            times.append(json.load(f)["wall_time_s"] * 1e6)
    return statistics.median(times)


def copied(path, scratch):
    """A copy of the executable `path` in `scratch`, written in 1 MB pieces (see --copy)."""
    target = os.path.join(scratch, os.path.basename(path))
    with open(path, "rb") as src, open(target, "wb") as dst:
        while chunk := src.read(1 << 20):
            dst.write(chunk)
    os.chmod(target, 0o755)
    return target


def warm_us(bench, scheme, repetitions, min_time, cpu):
    """bench_statics' median real time of static_solve/SCHEME/cosserat, in microseconds."""
    r = subprocess.run([bench, f"--benchmark_filter=^static_solve/{scheme}/cosserat$",
                        f"--benchmark_repetitions={repetitions}",
                        f"--benchmark_min_time={min_time}",
                        "--benchmark_format=json"],
                       capture_output=True, text=True, preexec_fn=pinned(cpu))
    if r.returncode != 0:
        raise Failure(f"bench_statics ({scheme}) exited {r.returncode}:\n{r.stderr}")
    rows = [b for b in json.loads(r.stdout)["benchmarks"] if b.get("run_type") == "iteration"]
    if not rows:
        raise Failure(f"bench_statics has no static_solve/{scheme}/cosserat")
    scale = {"ns": 1e-3, "us": 1.0, "ms": 1e3, "s": 1e6}[rows[0]["time_unit"]]
    return statistics.median(b["real_time"] * scale for b in rows)


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--build", default=os.environ.get("RODLAB_BUILD_DIR",
                                                     os.path.join(SOURCE, "build")),
                   help="the build directory (bin/rodlab, bin/bench_statics); default build/")
    p.add_argument("--schemes", default=",".join(DEFAULT_SCHEMES),
                   help="comma-separated statics schemes, or 'all' (default %(default)s)")
    p.add_argument("--runs", type=int, default=15, help="cold runs per round (default 15)")
    p.add_argument("--repetitions", type=int, default=5,
                   help="warm benchmark repetitions per round (default 5)")
    p.add_argument("--min-time", type=float, default=0.5,
                   help="seconds per warm repetition (Google Benchmark's; default 0.5)")
    p.add_argument("--rounds", type=int, default=1, help="interleaved rounds (default 1)")
    p.add_argument("--cpu", type=int, default=max(os.sched_getaffinity(0)),
                   help="the core to pin to (default: the last one allowed, %(default)s; -1: none)")
    p.add_argument("--copy", action="store_true",
                   help="run a copy of rodlab written in 1 MB pieces (see above)")
    p.add_argument("--json", help="also write the figures to this file")
    a = p.parse_args(argv)
    for name in ("runs", "repetitions", "rounds"):
        if getattr(a, name) < 1:
            p.error(f"--{name} must be >= 1")
    if not a.min_time > 0:
        p.error("--min-time must be > 0")
    if a.cpu >= 0 and a.cpu not in os.sched_getaffinity(0):
        p.error(f"--cpu {a.cpu}: not a core this process may run on")
    a.cpu = None if a.cpu < 0 else a.cpu
    a.rodlab = os.path.join(a.build, "bin", "rodlab")
    a.bench = os.path.join(a.build, "bin", "bench_statics")
    for path in (a.rodlab, a.bench):
        if not os.access(path, os.X_OK):
            p.error(f"--build: {path} is missing "
                    f"(build it: make -C {a.build} rodlab bench_statics)")
    known = statics_schemes(a.rodlab)
    a.schemes = known if a.schemes == "all" else a.schemes.split(",")
    for s in a.schemes:
        if s not in known:
            p.error(f"--schemes: '{s}' is not a statics scheme (the statics schemes: "
                    f"{', '.join(known)})")
    return a


def measure(a):
    rows = {s: {"cold_us": [], "warm_us": []} for s in a.schemes}
    with tempfile.TemporaryDirectory() as scratch:
        rodlab = copied(a.rodlab, scratch) if a.copy else a.rodlab
        for _ in range(a.rounds):
            for s in a.schemes:
                rows[s]["cold_us"].append(cold_us(rodlab, s, a.runs, a.cpu, scratch))
                rows[s]["warm_us"].append(warm_us(a.bench, s, a.repetitions, a.min_time, a.cpu))
    out = []
    for s in a.schemes:
        cold, warm = rows[s]["cold_us"], rows[s]["warm_us"]
        out.append({"scheme": s, "nodes": bench_nodes(s), "cold_us": statistics.median(cold),
                    "warm_us": statistics.median(warm), "cold_rounds_us": cold,
                    "warm_rounds_us": warm,
                    "ratio": statistics.median(cold) / statistics.median(warm)})
    return out


def table(rows, a):
    def span(values):
        return (f"{values[0]:.0f}" if len(values) == 1
                else f"{statistics.median(values):.0f} ({min(values):.0f}-{max(values):.0f})")
    lines = [f"cold: median of {a.runs} `rodlab static` runs; warm: bench_statics, median of "
             f"{a.repetitions}; {a.rounds} round(s); core {a.cpu if a.cpu is not None else 'any'}"
             f"{'; rodlab copied' if a.copy else ''}",
             "",
             "| scheme, N | cold (CLI) [us] | warm (bench) [us] | cold / warm |",
             "|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['scheme']}, {r['nodes']} | {span(r['cold_rounds_us'])} | "
                     f"{span(r['warm_rounds_us'])} | {r['ratio']:.2f} |")
    return "\n".join(lines)


def write_atomically(path, text):
    directory = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(dir=directory, prefix=".cold_static.")
    try:
        with os.fdopen(fd, "w") as f:
            f.write(text)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def main(argv):
    a = parse_args(argv)
    try:
        rows = measure(a)
    except Failure as e:
        print(f"cold_static.py: {e}", file=sys.stderr)
        return 1
    print(table(rows, a))
    if a.json:
        write_atomically(a.json, json.dumps({"schema": "rodlab.cold-static/1", "scene": SCENE,
                                             "runs": a.runs, "repetitions": a.repetitions,
                                             "rounds": a.rounds, "cpu": a.cpu, "copy": a.copy,
                                             "rows": rows},
                                            indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
