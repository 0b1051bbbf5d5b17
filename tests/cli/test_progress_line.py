"""The progress line of long runs (apps/rodlab/progress_line.hpp, docs/cli.md "Progress"):
with standard error on a pseudo-terminal, `dynamic`, `workspace`, `train`, `validate` and
`study` draw it there ("label  done/total unit  p %  elapsed ..." redrawn after a carriage
return) and erase it at the end; with standard error not a terminal, or with --quiet, they
write nothing there. Standard output, the result file and the exit status are the same either
way.
"""
import json
import os
import pty
import re
import subprocess

RODLAB = os.environ["RODLAB_BINARY"]
SCENES = os.path.join(os.environ["RODLAB_SOURCE_DIR"], "scenes")
TIMED = {"wall_time_s", "real_time_ratio"}  # the only fields that differ between two runs


def run(args, tty):
    """Exit status, stdout and stderr of rodlab with stderr on a pseudo-terminal (tty) or a pipe."""
    if not tty:
        p = subprocess.run([RODLAB, *args], capture_output=True, text=True)
        return p.returncode, p.stdout, p.stderr
    master, slave = pty.openpty()
    p = subprocess.Popen([RODLAB, *args], stdout=subprocess.PIPE, stderr=slave,
                         stdin=subprocess.DEVNULL)
    os.close(slave)
    chunks = []
    while True:
        try:
            data = os.read(master, 4096)
        except OSError:  # EIO: the child closed the terminal
            break
        if not data:
            break
        chunks.append(data)
    out = p.stdout.read().decode()
    p.wait()
    os.close(master)
    return p.returncode, out, b"".join(chunks).decode()


def untimed(text):
    """A result file without its timings."""
    return {k: v for k, v in json.loads(text).items() if k not in TIMED}


def stable_lines(stdout, mode):
    """Standard output with every number as # and table rules shortened (timings differ between
    runs, and with them column widths), the run's own result file name as X."""
    text = stdout.replace(f"{mode}.json", "X.json")
    return [re.sub(r"-{2,}", "--", re.sub(r"\d[\d.e+-]*", "#", line)).split()
            for line in text.splitlines()]


def check_command(tmp_path, label, args, result=None):
    statuses = []
    for mode in ("tty", "pipe", "quiet"):
        extra = ["--quiet"] if mode == "quiet" else []
        out_args = ["--out", str(tmp_path / f"{mode}.json")] if result else []
        status, stdout, stderr = run([*args, *extra, *out_args], tty=mode == "tty")
        statuses.append(status)
        if mode == "tty":
            assert stderr.startswith("\r" + label + "  "), stderr[:200]
            assert " %  elapsed " in stderr
            last = stderr.rstrip(" \r").split("\r")[-1]
            assert "100 %" in last, last  # the last drawing is the finished count
            assert stderr.endswith("\r")  # erased: the cursor back at the line's start
            tty_stdout = stdout
        else:
            assert stderr == "", (mode, stderr)
            assert stable_lines(stdout, mode) == stable_lines(tty_stdout, "tty")
    assert len(set(statuses)) == 1
    if result:
        files = [untimed((tmp_path / f"{m}.json").read_text()) for m in ("tty", "pipe", "quiet")]
        assert files[0] == files[1] == files[2]


def test_dynamic(tmp_path):
    check_command(tmp_path, "dynamic",
                  ["dynamic", os.path.join(SCENES, "cantilever-gravity.yaml"), "--t-end", "0.05"],
                  result=True)


def test_workspace(tmp_path):
    check_command(tmp_path, "workspace",
                  ["workspace", os.path.join(SCENES, "cable-driven.yaml"), "--samples", "4"],
                  result=True)


def test_train(tmp_path):
    check_command(tmp_path, "train",
                  ["train", os.path.join(SCENES, "control-cable.yaml"), "--algorithm", "ddpg",
                   "--task", "reach-any", "--samples", "40", "--out",
                   str(tmp_path / "policy.json")])


def test_validate(tmp_path):
    check_command(tmp_path, "validate",
                  ["validate", "--quick", "--only", "scenes", "--no-figures", "--out",
                   str(tmp_path / "report")])


def test_study(tmp_path):
    check_command(tmp_path, "study convergence",
                  ["study", "convergence", os.path.join(SCENES, "cable-driven.yaml"), "--schemes",
                   "rkmk-rk4", "--nodes", "8,16", "--out", str(tmp_path / "study")])
