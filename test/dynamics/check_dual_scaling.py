#!/usr/bin/python3
"""The scaling of the dual by F's diagonal (FETI "Dual Scaling",
docs/dynamics.md) on a graded mesh:

  check_dual_scaling.py --out DIR --steps N -- MPIEXEC ... TRIBOS INPUT ...

runs the command twice for N time steps (Dynamics/End Time = N x Time
Step), with Solver/FETI/Dual Scaling true and false, into DIR/scaled and
DIR/unscaled, and checks: both exit 0 with every step converged; the
displacement and velocity of every step file agree to --tol relative to
the largest of each field (two solutions of the same problem: the
command's solver tolerance bounds their difference; the velocity, a
difference quotient of displacements over dt, is the more sensitive); and
the scaled runs took at most --ratio times the applications of F of the
unscaled ones (the steps table's n_A, which holds the predictor's
projection too). Prints the counts and the differences.
"""
import argparse
import json
import subprocess
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np

from dynamics_checks import check, failed, parameter

p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
p.add_argument("--out", required=True)
p.add_argument("--steps", type=int, default=10)
p.add_argument("--tol", type=float, default=1e-6)
p.add_argument("--ratio", type=float, default=0.5)
p.add_argument("command", nargs=argparse.REMAINDER)
a = p.parse_args()
command = a.command[1:] if a.command[:1] == ["--"] else a.command


runs = {scaled: f"{a.out}/{'scaled' if scaled else 'unscaled'}" for scaled in (True, False)}
# One run per setting, N steps each: the time step read from the input.
dt = None
for scaled in (True, False):
    out = runs[scaled]
    if dt is None:
        printed = subprocess.run(command + ["--print-parameters"], check=True, capture_output=True, text=True).stdout
        subprocess.run(["mkdir", "-p", a.out], check=True)
        with open(f"{a.out}/parameters.xml", "w") as f:
            f.write(printed)
        dt = float(parameter(ET.parse(f"{a.out}/parameters.xml").getroot(), "Dynamics/Time Step"))
    rc = subprocess.run(command + ["--output", out, "--quiet", "--set", f"Dynamics/End Time={a.steps * dt}",
                                   "--set", f"Solver/FETI/Dual Scaling={'true' if scaled else 'false'}"],
                        stdout=subprocess.DEVNULL).returncode
    check(rc == 0, f"Dual Scaling = {scaled}: exit {rc}")

rows = {}
for scaled in (True, False):
    rows[scaled] = [json.loads(line) for line in open(f"{runs[scaled]}/solution.steps.jsonl")]
    check(len(rows[scaled]) == a.steps and all(r["converged"] for r in rows[scaled]),
          f"Dual Scaling = {scaled}: {len(rows[scaled])} steps, all converged")
if failed():
    sys.exit(1)
nA = {s: sum(r["n_A"] for r in rows[s]) for s in rows}
check(nA[True] <= a.ratio * nA[False],
      f"applications of F: {nA[True]} scaled, {nA[False]} unscaled (ratio {nA[True] / nA[False]:.3f}, at most {a.ratio})")
worst = {"displacement": 0.0, "velocity": 0.0}
for one, other in zip(rows[True], rows[False]):
    with h5py.File(f"{runs[True]}/{one['file']}", "r") as h, h5py.File(f"{runs[False]}/{other['file']}", "r") as g:
        for field in worst:
            x, y = h[f"nodes/{field}"][:], g[f"nodes/{field}"][:]
            scale = max(np.abs(x).max(), np.abs(y).max(), 1e-300)
            worst[field] = max(worst[field], np.abs(x - y).max() / scale)
for field, d in worst.items():
    check(d <= a.tol, f"{field}: largest difference over the steps {d:.3g} of the field's largest value (at most {a.tol})")
sys.exit(1 if failed() else 0)
