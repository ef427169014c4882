#!/usr/bin/python3
"""The iteration history of real runs and scripts/plot_convergence.py on it:

  check_convergence.py --work DIR --inputs INPUT_DIR -- MPIEXEC... TRIBOS

Runs the seed brick (F = 0.3, level 3) with Algorithm 2 and with MSA +
Algorithm 1, and the linear brick (projected CG), each into DIR/NAME, and
checks that
  - every result set holds BASE.history.csv, named by the summary's
    "history_file", with the documented header;
  - its rows agree with the summary: one row per outer iteration (Algorithm 2
    loops, MSA steps; one row for projected CG, at its iteration count), the
    last row's slip-bound change (Coulomb) or relative residual (projected
    CG) is the summary's, the last n_A is the summary's n_A; n_A and the time
    never decrease;
  - plot_convergence.py draws the two Coulomb runs in one PNG that is an image
    of the expected size and not blank, and a different PNG when the data
    change (residuals and n_A of one run scaled: not a golden image);
  - a directory without a history is refused with a message that says so.
"""
import argparse
import csv
import json
import math
import os
import shutil
import subprocess
import sys

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, "..", "scripts", "plot_convergence.py")
HEADER = ["outer_iteration", "relative_residual", "G_lambda_rel", "slip_bound_change", "n_A", "time_s", "step"]
failures = []


def check(ok, what):
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        failures.append(what)


def close(a, b, rel=1e-8):
    return abs(a - b) <= rel * max(abs(a), abs(b), 1e-300)


def number(v):
    return float(v) if v.strip() else math.nan


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], [[number(v) for v in r] for r in rows[1:]]


def run(tribos, work, name, input_file, *sets):
    out = os.path.join(work, name)
    cmd = tribos + [input_file, "--output", out, "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    p = subprocess.run(cmd, capture_output=True, text=True)
    check(p.returncode == 0, "%s: the run converged (exit %d)" % (name, p.returncode))
    if p.returncode != 0:
        print(p.stderr)
    return out


def check_history(name, out, kind):
    """The history of one result against its summary."""
    with open(os.path.join(out, "solution.json")) as f:
        s = json.load(f)
    path = os.path.join(out, "solution.history.csv")
    check(os.path.exists(path), "%s: solution.history.csv written" % name)
    if not os.path.exists(path):
        return
    named = s.get("history_file", "")
    check(os.path.realpath(named) == os.path.realpath(path), "%s: the summary names it (history_file %s)" % (name, named))
    header, rows = read_csv(path)
    check(header == HEADER, "%s: header %s" % (name, ",".join(header)))
    col = {c: i for i, c in enumerate(HEADER)}
    last = rows[-1] if rows else [math.nan] * len(HEADER)
    if kind == "Algorithm2":
        expected = s["outer_iterations"]
    elif kind == "MSA":
        expected = s["msa_iterations"]
    else:
        expected = 1
    check(len(rows) == expected, "%s: %d rows, the summary says %d outer iterations" % (name, len(rows), expected))
    if kind == "linear":
        check(last[col["outer_iteration"]] == s["outer_iterations"],
              "%s: the row is at iteration %g = outer_iterations %d" % (name, last[0], s["outer_iterations"]))
        check(close(last[col["relative_residual"]], s["relative_residual"]),
              "%s: final relative residual %g = summary %g" % (name, last[col["relative_residual"]], s["relative_residual"]))
    else:
        iterations = [r[col["outer_iteration"]] for r in rows]
        check(iterations == list(range(1, len(rows) + 1)), "%s: outer iterations 1..%d" % (name, len(rows)))
        check(close(last[col["slip_bound_change"]], s["slip_bound_change"]) and close(last[col["slip_bound_change"]], s["history"][-1]),
              "%s: final slip-bound change %g = summary %g (history %g)"
              % (name, last[col["slip_bound_change"]], s["slip_bound_change"], s["history"][-1]))
        check(all(close(r[col["slip_bound_change"]], h) for r, h in zip(rows, s["history"])),
              "%s: every row's slip-bound change is the summary's history" % name)
        check(all(r[col["relative_residual"]] > 0 and r[col["G_lambda_rel"]] >= 0 for r in rows),
              "%s: residuals and ||G lambda|| in every row" % name)
    check(last[col["n_A"]] == s["n_A"], "%s: final n_A %g = summary n_A %d" % (name, last[col["n_A"]], s["n_A"]))
    n_A = [r[col["n_A"]] for r in rows]
    t = [r[col["time_s"]] for r in rows]
    check(all(b >= a for a, b in zip(n_A, n_A[1:])), "%s: n_A never decreases" % name)
    check(all(not math.isnan(v) and v >= 0 for v in t) and all(b >= a for a, b in zip(t, t[1:])),
          "%s: time_s present and never decreasing" % name)


def draw(dirs, png, *extra):
    p = subprocess.run([sys.executable, SCRIPT] + dirs + ["--out", png] + list(extra), capture_output=True, text=True)
    check(p.returncode == 0, "plot_convergence.py exits 0 (%s)" % p.stderr.strip())
    ok = os.path.exists(png) and os.path.getsize(png) > 5000
    check(ok, "%s written" % os.path.basename(png))
    return mpimg.imread(png)[..., :3] if ok else None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--work", required=True)
    ap.add_argument("--inputs", required=True, help="the input directory of the repository")
    ap.add_argument("command", nargs=argparse.REMAINDER)
    a = ap.parse_args()
    tribos = a.command[1:] if a.command[:1] == ["--"] else a.command
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    brick = os.path.join(a.inputs, "brick_coulomb_F03.xml")
    a2 = run(tribos, a.work, "a2", brick, "Mesh/Level=3", "Solver/Outer Algorithm=Algorithm2")
    msa = run(tribos, a.work, "msa", brick, "Mesh/Level=3", "Solver/Outer Algorithm=MSA+Algorithm1")
    linear = run(tribos, a.work, "linear", os.path.join(a.inputs, "brick_linear.xml"))
    if failures:
        return 1
    check_history("Algorithm 2", a2, "Algorithm2")
    check_history("MSA+Algorithm1", msa, "MSA")
    check_history("projected CG", linear, "linear")

    png = os.path.join(a.work, "convergence.png")
    img = draw([a2, msa], png, "--label", "Algorithm 2", "--label", "MSA+Algorithm1")
    if img is not None:
        check(img.ndim == 3 and img.shape[0] > 300 and img.shape[1] > 600, "the figure is an image %s" % (img.shape,))
        dark = float((img.mean(axis=2) < 0.9).mean())
        check(dark > 0.01, "the figure is not blank (%.3f of the pixels drawn)" % dark)

    # Other data, other picture: Algorithm 2's residuals a thousand times
    # larger and twice its n_A.
    changed = os.path.join(a.work, "a2_changed")
    shutil.copytree(a2, changed)
    header, rows = read_csv(os.path.join(changed, "solution.history.csv"))
    with open(os.path.join(changed, "solution.history.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        for r in rows:
            r[1], r[2], r[3], r[4] = r[1] * 1e3, r[2] * 1e3, r[3] * 1e3, r[4] * 2
            w.writerow(["" if math.isnan(v) else repr(v) for v in r])
    other = draw([changed, msa], os.path.join(a.work, "convergence_changed.png"),
                 "--label", "Algorithm 2", "--label", "MSA+Algorithm1")
    if img is not None and other is not None:
        diff = float(np.abs(img - other).mean()) if img.shape == other.shape else 1.0
        check(diff > 1e-3, "the figure changes with the data (mean pixel change %.4f)" % diff)

    # A directory that is not a result: refused, saying why.
    empty = os.path.join(a.work, "empty")
    os.makedirs(empty)
    p = subprocess.run([sys.executable, SCRIPT, empty, "--out", os.path.join(a.work, "none.png")],
                       capture_output=True, text=True)
    check(p.returncode != 0 and "no iteration history" in p.stderr and not os.path.exists(os.path.join(a.work, "none.png")),
          "a directory without a history is refused (exit %d: %s)" % (p.returncode, p.stderr.strip()))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
