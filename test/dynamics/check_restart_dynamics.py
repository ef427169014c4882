#!/usr/bin/python3
"""A restarted Dynamics run equals the uninterrupted one:

  check_restart_dynamics.py --work DIR --input BAR.xml --ranks N [--killed] [--refuse-inputs]
                            [--refuse-files] [--set S ...] -- MPIEXEC NPFLAG EXTRA... TRIBOS

(MPIEXEC NPFLAG: the launcher and its rank-count flag; the rank count is
inserted after NPFLAG.) Signorini's bar of input/bar_impact.xml on 20
cells instead of 40, dt = h / c as there (60 steps of the
contact-stabilized scheme; a step writes its file and flushes it, and a
run's time is mostly that), made to slide as it bounces: Coulomb friction
F = 0.3, an initial velocity (0.5, 0, -1) m/s and gravity, so that the
restart point, step 30, lies in the middle of the contact, the bar
compressed and its foot held by friction: the state carries the velocity,
the friction's slip origin, the work of the loads and the dissipation. The
solves run to a relative tolerance of 1e-11 (Algorithm 2's for the step's
Coulomb problem, SMALBE's for the frictionless projection) on N ranks
(--set: more parameters of every run):

  - the run goes through its 60 steps into DIR/full;
  - it runs again to half its End Time (30 steps) into DIR/half, and is
    continued there with `--restart` to the full End Time: steps 1-30 stay
    byte for byte as they were, the index is the uninterrupted run's, and
    every step 31-60 has every node's displacement and velocity, the
    contact forces, each contact node's dissipated energy, and the steps
    table's energies (kinetic, strain, work of the loads, friction
    dissipation) equal to the uninterrupted run's to 1e-8 relative (each
    against its largest magnitude in the uninterrupted run). The two runs
    differ in where the solves of step 31 start (zero multipliers against
    the last ones) and in the subdomain copies of a node (made equal, where
    they agreed to the gluing the solves reached); both results lie within
    the solvers' tolerance of the same discrete solution, the velocity, a
    difference quotient 2 (u_{n+1} - u_pred) / dt, about 10 times the
    tolerance from it;
  - with --killed, a copy of the full run made to look like a run killed
    after step 30 while it committed step 31 (test/check_restart.py) is
    continued to the same result, and the comparison can fail: the same
    restart from a step 30 whose velocity reads 0 in its file (its digest
    recorded anew, as if the run had written it so) ends far from the
    uninterrupted run;
  - refusals, each exit 1 naming the file or the parameter, the directory
    left as it was: with --refuse-inputs, another Time Step and an End Time
    whose step numbers need more digits; with --refuse-files, a step file
    whose velocity was changed (by its digest) and one that lost its
    velocity (its digest recorded anew; every rank reads its rows). (The
    Newmark scheme is refused before any work, test/bad_inputs; the other
    refusals are those of a load history, test/check_restart.py.)

Measured on 1 and 2 ranks, the largest over steps 31-60: 1.5e-12 relative
in the displacement, 1.2e-10 in the velocity, 6.6e-12 and 8.4e-11 in the
normal and friction forces, 7e-12 in the dissipated energy; the energies,
the work and the dissipation of the steps table agree to all their 10
digits. The difference follows the tolerance: 1.7e-9, 1.2e-10 and 4.3e-12
in the velocity at 1e-10, 1e-11 and 1e-12 (with one subdomain, no copies,
2.6e-11 at 1e-11). A run is about 1 s of work and 1.5-2.5 s of mpiexec's
start; the test takes 5-10 s on 1 rank and 7 s on 2.
"""
import argparse
import json
import os
import re
import shutil
import sys
import time
import xml.etree.ElementTree as ET

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import check_restart as cr  # noqa: E402  (the load-history restart test's helpers)

TOLERANCE = 1e-8
SLIDING = ["Mesh/Cells={1, 1, 20}",
           "Contact/Friction Law=Coulomb",
           "Contact/Friction Coefficient=0.3",
           "Initial Conditions/Velocity={0.5, 0, -1}",
           "Boundary Conditions/Volume Force={0, 0, -77008.5}",
           "Solver/Algorithm 2/Relative Tolerance=1e-11",
           "Solver/Algorithm 1/SMALBE/Relative Tolerance=1e-11"]
check = cr.check


def parameter(path, name):
    node = ET.parse(path).getroot()
    for part in name.split("/")[:-1]:
        node = next(c for c in node if c.tag == "ParameterList" and c.get("name") == part)
    return next(c for c in node if c.tag == "Parameter" and c.get("name") == name.split("/")[-1]).get("value")


def read_step(d, k):
    with h5py.File(cr.step_file(d, k), "r") as f:
        c = f["points/contact"]
        return {"u": np.array(f["nodes/displacement"]), "v": np.array(f["nodes/velocity"]),
                "normal": np.array(c["normal_force"]), "tangential": np.array(c["tangential_force"]),
                "dissipated": np.array(c["dissipated_energy"])}


ENERGIES = ("kinetic_energy", "strain_energy", "external_work", "friction_dissipation")


def differences(d, full, steps, after):
    """The largest relative difference of each quantity over the steps after
    `after`, against its largest magnitude in the uninterrupted run (node
    and contact fields in each step, energies over the run)."""
    ref_rows, rows = cr.summary(full)["steps"], cr.summary(d)["steps"]
    largest = {name: max(abs(r["dynamics"][name]) for r in ref_rows) for name in ENERGIES}
    worst = {}
    for k in range(after + 1, steps + 1):
        x, y = read_step(d, k), read_step(full, k)
        for name in x:
            scale = max(float(np.max(np.abs(y[name]))), 1e-300)
            worst[name] = max(worst.get(name, 0.0), float(np.max(np.abs(x[name] - y[name]))) / scale)
        for name in ENERGIES:
            diff = abs(rows[k - 1]["dynamics"][name] - ref_rows[k - 1]["dynamics"][name]) / max(largest[name], 1e-300)
            worst[name] = max(worst.get(name, 0.0), diff)
    return worst


def check_continued(what, d, full, steps, after, kept):
    """d continued after step `after` against the uninterrupted run full;
    kept: the digests of d's step files 1..after before the restart."""
    s, ref = cr.summary(d), cr.summary(full)
    check(s["converged"] and s["load_steps"] == steps and s["steps_completed"] == steps and
          [r["step"] for r in s["steps"]] == list(range(1, steps + 1)),
          "%s: the summary lists steps 1..%d, converged" % (what, steps))
    check([cr.digest(cr.step_file(d, k)) for k in range(1, after + 1)] == kept,
          "%s: the step files 1..%d are untouched" % (what, after))
    check(cr.digest(os.path.join(d, cr.BASE + ".xmf")) == cr.digest(os.path.join(full, cr.BASE + ".xmf")),
          "%s: the index is the uninterrupted run's" % what)
    with h5py.File(cr.step_file(d, steps), "r") as f, h5py.File(cr.step_file(full, steps), "r") as g:
        for name in ("external_work", "friction_dissipation"):
            mine, theirs = float(f.attrs[name]), float(g.attrs[name])
            check(abs(mine - theirs) <= TOLERANCE * abs(theirs) and theirs != 0,
                  "%s: the last step file's %s %.12g J, uninterrupted %.12g J" % (what, name, mine, theirs))
    worst = differences(d, full, steps, after)
    check(max(worst.values()) <= TOLERANCE, "%s: steps %d-%d against the uninterrupted run (<= %g): %s" % (
        what, after + 1, steps, TOLERANCE, ", ".join("%s %.1e" % kv for kv in worst.items())))


def refuse_inputs(args, np_, full, work, steps, after, dt):
    cut = os.path.join(work, "cut")
    cr.killed_copy(full, cut, after, steps)
    sets = SLIDING
    cr.refusal(args, np_, "another Time Step", cut,
               re.escape(os.path.join(cut, cr.BASE + ".parameters.xml")) +
               r"\) differ: \"Dynamics/Time Step\" is 5e-06 here and %s there" % re.escape(repr(dt)),
               sets=sets + ["Dynamics/Time Step=5e-6"])
    cr.refusal(args, np_, "an End Time of 10000 steps", cut,
               r"the run there names its %d steps' files solution\.step0001\.h5, \.\.\., this run of 10000 steps "
               r"solution\.step00001\.h5" % steps, sets=sets + ["Dynamics/End Time=%r" % (10000 * dt)])


def refuse_files(args, np_, full, work, steps, after):
    sets = SLIDING

    def variant(name, change, regex):
        d = os.path.join(work, name)
        cr.killed_copy(full, d, after, steps)
        change(d)
        cr.refusal(args, np_, name, d, regex, sets=sets)

    def velocity_changed(d):
        with h5py.File(cr.step_file(d, after), "r+") as f:
            f["nodes/velocity"][...] *= 1.001
    variant("velocity_changed", velocity_changed, re.escape(cr.step_file(os.path.join(work, "velocity_changed"), after)) +
            r" is not the file step %d wrote: its SHA-256 is [0-9a-f]{64}, .*steps\.jsonl records" % after)

    def velocity_lost(d):
        with h5py.File(cr.step_file(d, after), "r+") as f:
            del f["nodes/velocity"]
        cr.record_digest(d, after)  # a record that vouches for it: the file still lacks the state
    variant("velocity_lost", velocity_lost, re.escape(cr.step_file(os.path.join(work, "velocity_lost"), after)) +
            r", dataset /nodes/velocity: no such dataset")


def killed_runs(args, np_, full, work, steps, after):
    """Killed while it committed step after + 1, restarted with the same
    input; and from a velocity of 0."""
    killed = os.path.join(work, "killed")
    cr.killed_copy(full, killed, after, steps)
    kept = [cr.digest(cr.step_file(killed, k)) for k in range(1, after + 1)]
    p = cr.tribos(args, np_, ["--restart", killed], SLIDING)
    if check(p.returncode == 0, "np %d: the restart after step %d of a killed run (exit %d)" % (np_, after, p.returncode)):
        check_continued("np %d, killed then restarted" % np_, killed, full, steps, after, kept)
    else:
        print(p.stderr[-3000:])

    # The comparison sees the velocity a restart carries.
    forgetful = os.path.join(work, "forgetful")
    cr.killed_copy(full, forgetful, after, steps)
    with h5py.File(cr.step_file(forgetful, after), "r+") as f:
        f["nodes/velocity"][...] = 0.0
    cr.record_digest(forgetful, after)
    p = cr.tribos(args, np_, ["--restart", forgetful], SLIDING)
    if check(p.returncode == 0, "np %d: a restart from a step %d at rest (exit %d)" % (np_, after, p.returncode)):
        worst = differences(forgetful, full, steps, after)
        check(worst["v"] > 1e3 * TOLERANCE, "np %d: from a velocity of 0 the run differs by %.1e in the velocity "
              "(> %g): the comparison sees the state a restart carries" % (np_, worst["v"], 1e3 * TOLERANCE))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--work", required=True)
    ap.add_argument("--input", required=True)
    ap.add_argument("--ranks", type=int, required=True)
    ap.add_argument("--killed", action="store_true")
    ap.add_argument("--refuse-inputs", action="store_true")
    ap.add_argument("--refuse-files", action="store_true")
    ap.add_argument("--set", action="append", default=[], dest="sets")
    ap.add_argument("launcher", nargs="+")
    args = ap.parse_args()
    SLIDING.extend(args.sets)
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    np_, work = args.ranks, args.work
    dt = 2 * float(parameter(args.input, "Dynamics/Time Step"))  # h / c on half the cells
    SLIDING.append("Dynamics/Time Step=%r" % dt)
    steps = round(float(parameter(args.input, "Dynamics/End Time")) / dt)
    after = steps // 2
    started = time.time()

    full = os.path.join(work, "full")
    p = cr.tribos(args, np_, ["--output", full], SLIDING)
    if not check(p.returncode == 0, "np %d: the uninterrupted run of %d steps (exit %d)" % (np_, steps, p.returncode)):
        print(p.stderr[-3000:])
        sys.exit(1)

    # Stopped at half its End Time, then continued to the end.
    half = os.path.join(work, "half")
    half_end = ["Dynamics/End Time=%r" % (after * dt)]
    p = cr.tribos(args, np_, ["--output", half], SLIDING + half_end)
    check(p.returncode == 0 and cr.summary(half)["steps_completed"] == after,
          "np %d: the run to half the End Time, %d steps (exit %d)" % (np_, after, p.returncode))
    kept = [cr.digest(cr.step_file(half, k)) for k in range(1, after + 1)]
    p = cr.tribos(args, np_, ["--restart", half], SLIDING)
    if check(p.returncode == 0, "np %d: continued from step %d to the End Time (exit %d)" % (np_, after, p.returncode)):
        check(json.loads(p.stdout) == cr.raw_summary(half), "np %d: the summary on stdout is the file's" % np_)
        check_continued("np %d, half then continued" % np_, half, full, steps, after, kept)
    else:
        print(p.stderr[-3000:])

    if args.killed:
        killed_runs(args, np_, full, work, steps, after)
    if args.refuse_inputs:
        refuse_inputs(args, np_, full, work, steps, after, dt)
    if args.refuse_files:
        refuse_files(args, np_, full, work, steps, after)
    print("%.1f s" % (time.time() - started))
    if cr.failures:
        print("%d check(s) failed" % len(cr.failures))
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
