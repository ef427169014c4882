#!/usr/bin/python3
"""A load history run by the driver, checked from its files:

  check_load_history.py --work DIR --input BRICK.xml --fretting TWO_BLOCKS.xml -- MPIEXEC NPFLAG EXTRA... TRIBOS

(MPIEXEC NPFLAG: the launcher and its rank-count flag; the rank count is
inserted after NPFLAG.) On the seed Coulomb brick (level 3), pressed and
then sheared out, back and out the other way (a cycle curve on the free-end
traction), it checks that

  - Load Steps {1} is the run without Load Steps: the same displacement,
    iterations and n_A (one step is the static solve);
  - every FETI outer algorithm that solves Coulomb friction solves every
    step of the history (Algorithm 2, MSA + Algorithm 1, Semismooth Newton),
    each step converged with its KKT residuals under the limit, and they
    agree step by step on the displacement and on each pair's resultant
    contact force (to their common tolerance); Algorithm 1 solves a Tresca
    history the same way;
  - friction remembers: after the shear is removed, a friction force is
    left (the contact does not return to its state before the shear), and
    it differs from the static solve of the same loads;
  - 1, 2 and 3 ranks give the same history;
  - a step that fails its check stops the run with exit 2 naming the step
    (the two blocks of TWO_BLOCKS.xml, held sideways by friction alone,
    sheared beyond what friction can hold at the fourth step): the steps
    before it stay complete (their data files and converged summary rows),
    the failed step is written and marked, none after it.
"""
import argparse
import glob
import json
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts"))
import tribos_summary  # noqa: E402

failures = []


def check(ok, what):
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        failures.append(what)


HISTORY = ["Load Steps/Times={1, 2, 3, 4}",
           "Load Curves/cycle/Times={0, 1, 2, 3, 4}",
           "Load Curves/cycle/Values={0, 0, 1, -1, 0}",
           "Boundary Conditions/Traction/free end/Curve=cycle"]


def run(args, name, np_, sets, expect=0, input_file=None):
    out = os.path.join(args.work, name)
    shutil.rmtree(out, ignore_errors=True)
    cmd = args.launcher[:2] + [str(np_)] + args.launcher[2:] + [input_file or args.input, "--output", out, "--quiet"]
    if not input_file:
        cmd += ["--set", "Mesh/Level=3"]
    for s in sets:
        cmd += ["--set", s]
    p = subprocess.run(cmd, capture_output=True, text=True)
    check(p.returncode == expect, "%s: exit %d (expected %d)" % (name, p.returncode, expect))
    if p.returncode != expect:
        print(p.stderr[-3000:])
    summary = os.path.join(out, "solution.json")
    s = tribos_summary.load(summary) if os.path.exists(summary) else None
    return out, s, p


def driver_arguments():
    """The arguments of a driver check: --work DIR --input FILE -- LAUNCHER...
    (the work directory made)."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--work", required=True)
    ap.add_argument("--input", required=True)
    ap.add_argument("launcher", nargs="+")
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    return args


def displacements(out):
    """The displacement of every step, the nodes sorted by their coordinates
    (the files of runs on other rank counts order the nodes by rank)."""
    files = sorted(glob.glob(os.path.join(out, "solution.step*.h5"))) or [os.path.join(out, "solution.h5")]
    steps = []
    for path in files:
        with h5py.File(path, "r") as f:
            u = np.array(f["/nodes/displacement"])
            x = np.array(f["/mesh/geometry"])
        steps.append(u[np.lexsort((x[:, 2], x[:, 1], x[:, 0]))])
    return steps


def relative(a, b):
    return float(np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300))


def pair_forces(s):
    """Per step, the resultant (normal, tangential x, y, z) of each pair."""
    return [np.array([[p["normal_force"]] + p["tangential_force"] for p in r["pairs"]]) for r in s["steps"]]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--work", required=True)
    ap.add_argument("--input", required=True)
    ap.add_argument("--fretting", required=True)
    ap.add_argument("launcher", nargs="+")
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)

    # One step is the static solve.
    static_out, static, _ = run(args, "static", 2, [])
    one_out, one, _ = run(args, "one_step", 2, ["Load Steps/Times={1}"])
    if static and one:
        same = [k for k in ("n_A", "outer_iterations", "max_abs_displacement") if static[k] != one[k]]
        check(not same, "Load Steps {1} = the static run (n_A, outer iterations, largest displacement); differ: %s" % same)
        check(relative(displacements(one_out)[0], displacements(static_out)[0]) == 0.0,
              "Load Steps {1}: the displacement of the static run, bit for bit")

    # Every Coulomb algorithm solves every step, and they agree.
    runs = {}
    for algorithm in ("Algorithm2", "MSA+Algorithm1", "Semismooth Newton"):
        out, s, _ = run(args, "history_" + algorithm.replace("+", "_").replace(" ", "_"), 2,
                        HISTORY + ["Solver/Outer Algorithm=" + algorithm])
        if not s:
            continue
        check(s["load_steps"] == 4 and len(s["steps"]) == 4, "%s: 4 step rows" % algorithm)
        check(all(r["converged"] for r in s["steps"]) and s["converged"], "%s: every step converged" % algorithm)
        check(len(displacements(out)) == 4, "%s: 4 step data files" % algorithm)
        runs[algorithm] = (out, s)
    if "Algorithm2" in runs:
        ref_out, ref = runs["Algorithm2"]
        ref_u, ref_f = displacements(ref_out), pair_forces(ref)
        for algorithm, (out, s) in runs.items():
            u, f = displacements(out), pair_forces(s)
            du = max(relative(a, b) for a, b in zip(u, ref_u))
            df = max(float(np.max(np.abs(a - b)) / np.max(np.abs(b))) for a, b in zip(f, ref_f))
            check(du < 1e-3 and df < 1e-3, "%s agrees with Algorithm 2 in every step: displacement %.2e, pair forces %.2e"
                  % (algorithm, du, df))
        # Memory: after the cycle the shear is gone but friction forces stay.
        last = ref["steps"][-1]["pairs"][0]["tangential_force"]
        pressed = ref["steps"][0]["pairs"][0]["tangential_force"]
        left = float(np.hypot(last[0] - pressed[0], last[1] - pressed[1]))
        check(left > 1e-3 * ref["steps"][0]["pairs"][0]["normal_force"],
              "the cycle leaves a friction force: |t_T(t=4) - t_T(t=1)| = %.4g" % left)
        check(relative(ref_u[-1], ref_u[0]) > 1e-3,
              "the displacement after the cycle differs from before it (%.2e)" % relative(ref_u[-1], ref_u[0]))

    # Tresca by Algorithm 1.
    _, tresca, _ = run(args, "history_tresca", 2, HISTORY + ["Contact/Friction Law=Tresca",
                                                            "Contact/Slip Bound Traction=5e6",
                                                            "Solver/Outer Algorithm=Auto"])
    if tresca:
        check(tresca["outer_algorithm"] == "Algorithm1" and all(r["converged"] for r in tresca["steps"]),
              "Tresca history: Algorithm 1, every step converged")

    # 1, 2 and 3 ranks.
    if "Algorithm2" in runs:
        for np_ in (1, 3):
            out, s, _ = run(args, "history_np%d" % np_, np_, HISTORY + ["Solver/Outer Algorithm=Algorithm2"])
            if s:
                du = max(relative(a, b) for a, b in zip(displacements(out), ref_u))
                df = max(float(np.max(np.abs(a - b)) / np.max(np.abs(b))) for a, b in zip(pair_forces(s), ref_f))
                check(du < 1e-3 and df < 1e-3, "%d ranks = 2 ranks in every step: displacement %.2e, forces %.2e"
                      % (np_, du, df))

    # A step that fails stops the run there.
    out, s, p = run(args, "history_stopped", 2,
                    ["Boundary Conditions/Traction/shear/Value={4e6, 0, 0}", "Load Steps/Times={0.5, 1, 1.5, 2, 2.5}"],
                    expect=2, input_file=args.fretting)
    if s:
        rows = s["steps"]
        check(len(rows) == 4 and [r["converged"] for r in rows] == [True, True, True, False] and not s["converged"]
              and s["stop_reason"].startswith("load step 4 of 5 (t = 2): "),
              "the failed step stops the run, named: %s" % s["stop_reason"][:100])
        files = [os.path.exists(os.path.join(out, "solution.step%04d.h5" % k)) for k in range(1, 6)]
        check(files == [True, True, True, True, False], "steps 1-3 complete, step 4 written and marked, step 5 not: %s"
              % files)
        with h5py.File(os.path.join(out, "solution.step0004.h5"), "r") as f:
            check(f.attrs["converged"] == 0, "step 4's data file says converged = 0")

    print("%d failure(s)" % len(failures))
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
