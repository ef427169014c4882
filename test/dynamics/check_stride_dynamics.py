#!/usr/bin/python3
"""Output/Step Stride of a Dynamics run, and its restart:

  check_stride_dynamics.py --work DIR --input BAR.xml --ranks N [--stride K] [--set S ...]
                           -- MPIEXEC NPFLAG EXTRA... TRIBOS

The sliding bar of check_restart_dynamics.py (input/bar_impact.xml on 20
cells, 60 steps of the contact-stabilized scheme, Coulomb friction, the
restart point in the middle of the contact; solves at 1e-11) on N ranks:

  - run with stride 1 into DIR/every and with stride K (default 3) into
    DIR/strided: the strided run writes the data files of steps K, 2K, ...
    and the last (60) and no other, its index lists exactly those, its steps
    table has a row for each of the 60 steps (the written ones with their
    file and its digest, the others with neither), and every written step
    holds the stride-1 run's data, dataset by dataset, to the bit, and every
    row its energies;
  - a copy of the strided run made to look killed while it committed step
    33, after step 30 (the summary lists steps 1-30, the table holds rows
    31-32 and half of 33, the history rows up to 33, step 33's file is
    there, the later ones are not) is continued with --restart: it recomputes
    steps 31 and 32, which have no file, from step 30's, and ends as the
    uninterrupted strided run: files 3-30 untouched, the index the same
    byte for byte, every written step 33-60 with every node's displacement
    and velocity, the contact forces and dissipated energies, and every row
    31-60 with its energies, to 1e-8 relative (each against its largest
    magnitude in the uninterrupted run; the solvers' tolerance, as
    check_restart_dynamics.py measures);
  - a run stopped at step 31 (an End Time between two written steps: step
    31 is the last, so written) continues to step 60 with the same result,
    its index listing step 31 too.
"""
import argparse
import json
import os
import re
import shutil
import sys
import time

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, ".."))
import check_restart as cr  # noqa: E402
import check_restart_dynamics as crd  # noqa: E402

TOLERANCE = crd.TOLERANCE
check = cr.check
STEP_NAME = re.compile(r"^%s\.step(\d+)\.h5$" % re.escape(cr.BASE))


def written_steps(d):
    return sorted(int(m.group(1)) for m in map(STEP_NAME.match, os.listdir(d)) if m)


def indexed_steps(d):
    with open(os.path.join(d, cr.BASE + ".xmf")) as f:
        return sorted({int(n) for n in re.findall(r"%s\.step(\d+)\.h5:" % re.escape(cr.BASE), f.read())})


def datasets(path):
    out = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, obj: out.__setitem__(name, np.array(obj)) if isinstance(obj, h5py.Dataset) else None)
    return out


def compare_written(d, full, steps, after, written):
    """The largest relative difference of each quantity over the written steps
    after `after` and of the energies over every row after it."""
    ref_rows, rows = cr.summary(full)["steps"], cr.summary(d)["steps"]
    largest = {n: max(abs(r["dynamics"][n]) for r in ref_rows) for n in crd.ENERGIES}
    worst = {}
    for k in [s for s in written if s > after]:
        x, y = crd.read_step(d, k), crd.read_step(full, k)
        for name in x:
            scale = max(float(np.max(np.abs(y[name]))), 1e-300)
            worst[name] = max(worst.get(name, 0.0), float(np.max(np.abs(x[name] - y[name]))) / scale)
    for k in range(after + 1, steps + 1):
        for n in crd.ENERGIES:
            diff = abs(rows[k - 1]["dynamics"][n] - ref_rows[k - 1]["dynamics"][n]) / max(largest[n], 1e-300)
            worst[n] = max(worst.get(n, 0.0), diff)
    return worst


def strided_result(d, every, steps, written):
    s = cr.summary(d)
    rows = s["steps"]
    check(s["converged"] and s["steps_completed"] == steps and [r["step"] for r in rows] == list(range(1, steps + 1)),
          "the summary lists steps 1..%d, converged" % steps)
    check(written_steps(d) == written, "data files of steps %s only" % written)
    check(indexed_steps(d) == written, "the index lists those steps only")
    named = [r["step"] for r in rows if "file" in r]
    check(named == written and all(r["sha256"] == cr.digest(os.path.join(d, r["file"])) for r in rows if "file" in r)
          and all("sha256" not in r for r in rows if "file" not in r),
          "the rows of the written steps name their file and its digest, the others neither")
    same = all(all(np.array_equal(a, b[n]) for n, a in datasets(cr.step_file(d, k)).items())
               for k in written for b in [datasets(cr.step_file(every, k))])
    check(same, "every written step holds the stride-1 run's data to the bit")
    ref = cr.summary(every)["steps"]
    check(all(r["dynamics"] == q["dynamics"] for r, q in zip(rows, ref)), "every row has the stride-1 run's energies")


def killed_in_commit(full, d, after, commit, steps, written):
    """full as a run killed while it committed step `commit` (the first
    written step after `after`) leaves it: the summary at `after`, the rows
    of the steps up to commit - 1 and half of commit's, the history up to
    commit, commit's data file; no later file."""
    shutil.rmtree(d, ignore_errors=True)
    shutil.copytree(full, d)
    s = cr.raw_summary(d)
    s["steps_completed"] = after
    cr.write_summary(d, s)
    rows = cr.table_rows(d)
    cr.write_table(d, rows[:commit - 1], json.dumps(rows[commit - 1])[:40])
    hist = cr.history_rows(d)
    with open(os.path.join(d, cr.BASE + ".history.csv"), "w", newline="") as f:
        import csv
        csv.writer(f, lineterminator="\n").writerows([hist[0]] + [r for r in hist[1:] if int(r[6]) <= commit])
    for k in written:
        if k > commit:
            os.remove(cr.step_file(d, k))


def continued(what, args, np_, d, full, steps, after, written, sets, same_index=True):
    kept = {k: cr.digest(cr.step_file(d, k)) for k in written_steps(d) if k <= after}
    p = cr.tribos(args, np_, ["--restart", d], sets)
    if not check(p.returncode == 0, "%s: --restart after step %d (exit %d)" % (what, after, p.returncode)):
        print(p.stderr[-3000:])
        return
    s = cr.summary(d)
    check(s["converged"] and s["steps_completed"] == steps and [r["step"] for r in s["steps"]] == list(range(1, steps + 1)),
          "%s: the summary lists steps 1..%d, converged" % (what, steps))
    check({k: cr.digest(cr.step_file(d, k)) for k in kept} == kept, "%s: the step files up to %d are untouched" % (what, after))
    mine = sorted(set(written_steps(d)))
    check(mine == sorted(set(kept) | {k for k in written if k > after}), "%s: files of steps %s" % (what, mine))
    if same_index:
        check(cr.digest(os.path.join(d, cr.BASE + ".xmf")) == cr.digest(os.path.join(full, cr.BASE + ".xmf")),
              "%s: the index is the uninterrupted run's" % what)
    else:
        check(indexed_steps(d) == mine, "%s: the index lists the steps with files" % what)
    worst = compare_written(d, full, steps, after, written)
    check(max(worst.values()) <= TOLERANCE, "%s: steps %d-%d against the uninterrupted run (<= %g): %s" % (
        what, after + 1, steps, TOLERANCE, ", ".join("%s %.1e" % kv for kv in worst.items())))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--work", required=True)
    ap.add_argument("--input", required=True)
    ap.add_argument("--ranks", type=int, required=True)
    ap.add_argument("--stride", type=int, default=3)
    ap.add_argument("--set", action="append", default=[], dest="sets")
    ap.add_argument("launcher", nargs="+")
    args = ap.parse_args()
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    np_, work, K = args.ranks, args.work, args.stride
    dt = 2 * float(crd.parameter(args.input, "Dynamics/Time Step"))  # h / c on half the cells
    sets = crd.SLIDING + args.sets + ["Dynamics/Time Step=%r" % dt]
    steps = round(float(crd.parameter(args.input, "Dynamics/End Time")) / dt)
    written = sorted(set(range(K, steps + 1, K)) | {steps})
    after = (steps // 2) // K * K  # a written step in the middle
    commit = after + K
    started = time.time()

    every, full = os.path.join(work, "every"), os.path.join(work, "strided")
    strided = sets + ["Output/Step Stride=%d" % K]
    for d, s in ((every, sets), (full, strided)):
        p = cr.tribos(args, np_, ["--output", d], s)
        if not check(p.returncode == 0, "np %d: the run of %d steps into %s (exit %d)" % (np_, steps, d, p.returncode)):
            print(p.stderr[-3000:])
            sys.exit(1)
    strided_result(full, every, steps, written)

    killed = os.path.join(work, "killed")
    killed_in_commit(full, killed, after, commit, steps, written)
    continued("np %d, killed in step %d's commit" % (np_, commit), args, np_, killed, full, steps, after, written,
              strided)

    stopped = os.path.join(work, "stopped")
    p = cr.tribos(args, np_, ["--output", stopped], strided + ["Dynamics/End Time=%r" % ((after + 1) * dt)])
    check(p.returncode == 0 and written_steps(stopped) == [k for k in written if k <= after] + [after + 1],
          "np %d: a run to step %d writes %s and step %d (exit %d)" % (np_, after + 1, "every %d-th" % K, after + 1,
                                                                     p.returncode))
    continued("np %d, stopped at step %d" % (np_, after + 1), args, np_, stopped, full, steps, after + 1, written,
              strided, same_index=False)
    print("%.1f s" % (time.time() - started))
    if cr.failures:
        print("%d check(s) failed" % len(cr.failures))
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
