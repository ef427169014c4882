#!/usr/bin/python3
"""A restarted load history equals the uninterrupted one:

  check_restart.py --work DIR --input BRICK.xml -- MPIEXEC NPFLAG EXTRA... TRIBOS

(MPIEXEC NPFLAG: the launcher and its rank-count flag; the rank count is
inserted after NPFLAG.) On the seed Coulomb brick (level 2), pressed and
then sheared out, back and partly out again (a cycle curve on the free-end
traction, 6 steps; the path matters: steps 4-6 stick and slip against the
slip left by steps 1-3), on 1 and 2 ranks:

  - the history runs uninterrupted into DIR/full;
  - a copy of it is made to look like a run killed after step 3 while it
    committed step 4: the summary lists steps 1-3, but step 4's data file
    and its history rows are there already, and the files of steps 5 and 6
    are gone (docs/load_history_output.md: what a killed run can leave);
  - `tribos INPUT --restart COPY` exits 0 and leaves the series of the
    uninterrupted run: steps 1-3 untouched (their files byte for byte,
    their steps table and history rows as they were), steps 4-6 solved again
    from step 3's displacement read back from its file, with every node's
    displacement and contact forces equal to the uninterrupted run's to
    1e-8 relative (the solves run to a relative tolerance of 1e-12: the
    two runs differ only in where the iterations of step 4 start, zero
    against the previous multipliers, so their results lie within the
    solver's tolerance of the same discrete solution; measured: 1e-11 in
    the displacement, 5e-11 in the tangential forces), the same stick/slip
    state of every contact node, the same index and as many history rows
    per step;
  - the comparison can fail: the same restart from step 3 with its
    displacement set to zero in its file (a restart that forgot where the
    contact had slipped to) differs from the uninterrupted run by far more;
  - refusals, each exit 1 with a message naming the file, the directory
    left exactly as it was: another input (parameters differ), a complete
    run, a step file missing, a step file of another mesh, a last step that
    did not converge, no step listed, a summary or history that does not
    read, and a result written on 1 rank (on 2 ranks, where every rank
    reads the files and refuses together).
"""
import argparse
import csv
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts"))
import tribos_summary  # noqa: E402

failures = []
BASE = "solution"
STEPS = 6
KILLED_AFTER = 3
TOLERANCE = 1e-8
HISTORY = ["Mesh/Level=2",
           "Load Steps/Times={0.5, 1, 1.5, 2, 2.5, 3}",
           "Load Curves/cycle/Times={0, 1, 2, 3}",
           "Load Curves/cycle/Values={0, 1, -1, 0}",
           "Boundary Conditions/Traction/free end/Curve=cycle",
           "Solver/Algorithm 2/Relative Tolerance=1e-12"]


def check(ok, what):
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        failures.append(what)
    return ok


def tribos(args, np_, extra, sets=HISTORY):
    cmd = args.launcher[:2] + [str(np_)] + args.launcher[2:] + [args.input, "--quiet"] + extra
    for s in sets:
        cmd += ["--set", s]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=600)


def step_file(d, k):
    return os.path.join(d, "%s.step%04d.h5" % (BASE, k))


def summary(d):
    """The summary with its steps (the complete rows of its steps table)."""
    return tribos_summary.load(os.path.join(d, BASE + ".json"))


def raw_summary(d):
    with open(os.path.join(d, BASE + ".json")) as f:
        return json.load(f)


def write_summary(d, s):
    with open(os.path.join(d, BASE + ".json"), "w") as f:
        json.dump(s, f, indent=2)


def table_path(d):
    return os.path.join(d, BASE + ".steps.jsonl")


def table_rows(d):
    with open(table_path(d)) as f:
        return [json.loads(line) for line in f if line.endswith("\n")]


def write_table(d, rows, tail=""):
    with open(table_path(d), "w") as f:
        f.write("".join(json.dumps(r) + "\n" for r in rows) + tail)


def history_rows(d):
    with open(os.path.join(d, BASE + ".history.csv")) as f:
        return list(csv.reader(f))


def digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


def snapshot(d):
    """Every file of a directory with its content's digest; the directory's
    lock file aside (a run that opened the directory wrote its pid there)."""
    return {name: digest(os.path.join(d, name)) for name in sorted(os.listdir(d)) if name != ".tribos.lock"}


def killed_copy(full, d, k, steps=STEPS):
    """A copy of the uninterrupted result (of `steps` steps) as a run killed
    after step k while it committed step k + 1 leaves it: the summary says
    steps 1..k are complete, step k + 1's data file, its row of the steps
    table and its history rows are there (and half the row of step k + 2),
    the later steps' files are not."""
    shutil.rmtree(d, ignore_errors=True)
    shutil.copytree(full, d)
    s = raw_summary(d)
    s["steps_completed"] = k
    write_summary(d, s)
    rows = table_rows(d)
    write_table(d, rows[:k + 1], json.dumps(rows[k + 1])[:40])
    rows = history_rows(d)
    with open(os.path.join(d, BASE + ".history.csv"), "w", newline="") as f:
        csv.writer(f, lineterminator="\n").writerows([rows[0]] + [r for r in rows[1:] if int(r[6]) <= k + 1])
    for step in range(k + 2, steps + 1):
        os.remove(step_file(d, step))


def record_digest(d, k):
    """The steps table of d records the present digest of step k's file."""
    rows = table_rows(d)
    rows[k - 1]["sha256"] = digest(step_file(d, k))
    write_table(d, rows)


def read_step(d, k):
    with h5py.File(step_file(d, k), "r") as f:
        c = f["points/contact"]
        return {"u": np.array(f["nodes/displacement"]), "normal": np.array(c["normal_force"]),
                "tangential": np.array(c["tangential_force"]), "status": np.array(c["status"]).ravel()}


def relative(a, b):
    return float(np.max(np.abs(a - b)) / max(float(np.max(np.abs(b))), 1e-300))


def largest_difference(a, b):
    """The largest relative difference of the displacement and the contact
    forces over the steps after the restart point."""
    worst = 0.0
    for k in range(KILLED_AFTER + 1, STEPS + 1):
        x, y = read_step(a, k), read_step(b, k)
        worst = max(worst, relative(x["u"], y["u"]), relative(x["normal"], y["normal"]),
                    relative(x["tangential"], y["tangential"]))
    return worst


def check_restarted(args, np_, full, d):
    """The restarted directory d against the uninterrupted run full."""
    s, ref = summary(d), summary(full)
    check(s["converged"] and s["load_steps"] == STEPS and [r["step"] for r in s["steps"]] == list(range(1, STEPS + 1)),
          "np %d: the restarted summary lists steps 1..%d, converged" % (np_, STEPS))
    check(s["steps"][:KILLED_AFTER] == ref["steps"][:KILLED_AFTER],
          "np %d: the rows of steps 1..%d are those of the run restarted" % (np_, KILLED_AFTER))
    check(all(digest(step_file(d, k)) == digest(step_file(full, k)) for k in range(1, KILLED_AFTER + 1)),
          "np %d: the step files 1..%d are untouched" % (np_, KILLED_AFTER))
    check(digest(os.path.join(d, BASE + ".xmf")) == digest(os.path.join(full, BASE + ".xmf")),
          "np %d: the index is the uninterrupted run's" % np_)
    rows, ref_rows = history_rows(d), history_rows(full)
    check(rows[:1] + [r for r in rows[1:] if int(r[6]) <= KILLED_AFTER] ==
          ref_rows[:1] + [r for r in ref_rows[1:] if int(r[6]) <= KILLED_AFTER],
          "np %d: the history rows of steps 1..%d are kept as they were" % (np_, KILLED_AFTER))
    check([int(r[6]) for r in rows[1:]] == sorted(int(r[6]) for r in rows[1:]) and
          {int(r[6]) for r in rows[1:]} == set(range(1, STEPS + 1)),
          "np %d: the history continues with rows of steps %d..%d" % (np_, KILLED_AFTER + 1, STEPS))
    for k in range(KILLED_AFTER + 1, STEPS + 1):
        x, y = read_step(d, k), read_step(full, k)
        du, dn, dt = relative(x["u"], y["u"]), relative(x["normal"], y["normal"]), relative(x["tangential"], y["tangential"])
        check(max(du, dn, dt) <= TOLERANCE,
              "np %d, step %d: displacement %.1e, normal force %.1e, tangential force %.1e from the uninterrupted run "
              "(<= %g)" % (np_, k, du, dn, dt, TOLERANCE))
        row, ref_row = s["steps"][k - 1], ref["steps"][k - 1]
        check(np.array_equal(x["status"], y["status"]) and row["contact"] == ref_row["contact"],
              "np %d, step %d: the same stick/slip state of every contact node (%s)" % (np_, k, row["contact"]))
        forces = [[p["normal_force"]] + p["tangential_force"] for p in row["pairs"]]
        ref_forces = [[p["normal_force"]] + p["tangential_force"] for p in ref_row["pairs"]]
        check(relative(np.array(forces), np.array(ref_forces)) <= TOLERANCE,
              "np %d, step %d: the pair's resultant contact force" % (np_, k))


def refusal(args, np_, name, d, regex, extra=None, sets=HISTORY):
    """A restart of d that must be refused, leaving d as it was."""
    before = snapshot(d)
    p = tribos(args, np_, ["--restart", d] + (extra or []), sets)
    ok = p.returncode == 1 and re.search(regex, p.stderr) is not None
    check(ok, "np %d, %s: exit 1 naming /%s/ (exit %d)" % (np_, name, regex, p.returncode))
    if not ok:
        print(p.stderr[-2000:])
    check(snapshot(d) == before, "np %d, %s: the directory is left as it was" % (np_, name))


def not_a_result(args, np_, work):
    """--restart of what is not a result directory: each exit 1 saying what
    the path is, nothing created there."""
    places = os.path.join(work, "places")
    shutil.rmtree(places, ignore_errors=True)
    os.makedirs(os.path.join(places, "empty"))
    with open(os.path.join(places, "file"), "w") as f:
        f.write("not a directory\n")
    os.symlink("loop", os.path.join(places, "loop"))
    for name, regex in (("missing", r": the directory does not exist"),
                        ("file", r": it is not a directory \(a regular file\)"),
                        ("loop", r": cannot access the directory \(Too many levels of symbolic links\)"),
                        ("empty", r": it is not a result directory of Output/Base Name = solution: it holds no "
                                  r"solution\.json")):
        path = os.path.join(places, name)
        before = sorted(os.listdir(places)) + (sorted(os.listdir(path)) if os.path.isdir(path) else [])
        p = tribos(args, np_, ["--restart", path])
        ok = p.returncode == 1 and re.search(re.escape(path) + regex, p.stderr) is not None
        check(ok, "np %d, --restart of a %s path: exit 1 naming /%s/ (exit %d)" % (np_, name, regex, p.returncode))
        if not ok:
            print(p.stderr[-2000:])
        after = sorted(os.listdir(places)) + (sorted(os.listdir(path)) if os.path.isdir(path) else [])
        check(after == before, "np %d, --restart of a %s path: nothing created" % (np_, name))


def refusals(args, np_, full, work):
    not_a_result(args, np_, work)
    cut = os.path.join(work, "cut")
    killed_copy(full, cut, KILLED_AFTER)
    refusal(args, np_, "another input", cut,
            re.escape(os.path.join(cut, BASE + ".parameters.xml")) + r"\) differ: \"Mesh/Level\" is 3 here and 2 there",
            sets=HISTORY + ["Mesh/Level=3"])
    refusal(args, np_, "a complete run", full, re.escape(os.path.join(full, BASE + ".json")) +
            ": it lists all 6 steps: the run is complete")

    def variant(name, change, regex):
        d = os.path.join(work, name)
        killed_copy(full, d, KILLED_AFTER)
        change(d)
        refusal(args, np_, name, d, regex)

    # Step files that are not those their steps wrote: each refused by its
    # digest, naming the step and the file.
    def replaced_by_step_2(d):
        shutil.copy(step_file(d, 2), step_file(d, 3))

    def truncated(d):
        size = os.path.getsize(step_file(d, 1))
        with open(step_file(d, 1), "r+b") as f:
            f.truncate(size // 3)

    def doubled(d):
        with h5py.File(step_file(d, 3), "r+") as f:
            f["nodes/displacement"][...] *= 2.0

    for name, change, k in (("step_3_is_step_2", replaced_by_step_2, 3), ("step_1_truncated", truncated, 1),
                            ("step_3_doubled", doubled, 3)):
        variant(name, change, re.escape(step_file(os.path.join(work, name), k)) +
                r" is not the file step %d wrote: its SHA-256 is [0-9a-f]{64}, .*steps\.jsonl records" % k)
    variant("no_summary", lambda d: os.remove(os.path.join(d, BASE + ".json")),
            r"there is no summary .*solution\.json: the run there completed no step \(run the input again without --restart\)")
    variant("last_step_file_missing", lambda d: os.remove(step_file(d, 3)),
            re.escape(step_file(os.path.join(work, "last_step_file_missing"), 3)) + " is missing")
    variant("first_step_file_missing", lambda d: os.remove(step_file(d, 1)),
            re.escape(step_file(os.path.join(work, "first_step_file_missing"), 1)) + " is missing")
    other_mesh = os.path.join(work, "level3")
    p = tribos(args, np_, ["--output", other_mesh], [s for s in HISTORY if "Mesh/Level" not in s] +
               ["Mesh/Level=3", "Load Steps/Times={0.5, 1}"])
    check(p.returncode == 0, "np %d: a level 3 run of two steps (exit %d)" % (np_, p.returncode))
    def other_mesh_recorded(d):
        shutil.copy(step_file(other_mesh, 2), step_file(d, 3))
        record_digest(d, 3)  # a record that vouches for it: the mesh check still refuses it
    variant("other_mesh", other_mesh_recorded,
            re.escape(step_file(os.path.join(work, "other_mesh"), 3)) + r" holds \d+ nodes, the mesh of this input \d+")

    def rewrite_summary(d, edit):
        s = raw_summary(d)
        edit(s)
        write_summary(d, s)

    def not_converged(d):
        rows = table_rows(d)
        rows[KILLED_AFTER - 1]["converged"] = False
        rows[KILLED_AFTER - 1]["stop_reason"] = "maximum iterations"
        write_table(d, rows)
    variant("not_converged", not_converged,
            r"solution\.steps\.jsonl: its last step 3 did not converge \(\"maximum iterations\"\)")
    variant("no_step", lambda d: rewrite_summary(d, lambda s: s.update(steps_completed=0)),
            r"solution\.json: it lists no complete step")
    variant("table_short", lambda d: write_table(d, table_rows(d)[:2]),
            r"solution\.steps\.jsonl: it has 2 complete rows; .*solution\.json says 3 steps are complete")

    def row_of_other_file(d):
        rows = table_rows(d)
        rows[1]["file"] = os.path.basename(step_file(d, 3))
        write_table(d, rows)
    variant("row_names_other_file", row_of_other_file,
            r"solution\.steps\.jsonl: its row 2 does not name the file \"solution\.step0002\.h5\"")

    def truncate(path):
        with open(path, "r+") as f:
            f.truncate(os.path.getsize(path) // 2)
    variant("summary_truncated", lambda d: truncate(os.path.join(d, BASE + ".json")),
            r"solution\.json: not a summary of a run: not a JSON text")
    variant("history_broken", lambda d: open(os.path.join(d, BASE + ".history.csv"), "a").write("1,x,,,,,4\n"),
            r"solution\.history\.csv: line \d+ is not a row of 7 numbers")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--work", required=True)
    ap.add_argument("--input", required=True)
    ap.add_argument("launcher", nargs="+")
    args = ap.parse_args()
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)

    for np_ in (1, 2):
        work = os.path.join(args.work, "np%d" % np_)
        full = os.path.join(work, "full")
        p = tribos(args, np_, ["--output", full])
        if not check(p.returncode == 0, "np %d: the uninterrupted history (exit %d)" % (np_, p.returncode)):
            print(p.stderr[-3000:])
            continue

        restarted = os.path.join(work, "restarted")
        killed_copy(full, restarted, KILLED_AFTER)
        p = tribos(args, np_, ["--restart", restarted])
        if check(p.returncode == 0, "np %d: the restart after step %d (exit %d)" % (np_, KILLED_AFTER, p.returncode)):
            check(json.loads(p.stdout) == raw_summary(restarted), "np %d: the summary on stdout is the file's" % np_)
            check_restarted(args, np_, full, restarted)
        else:
            print(p.stderr[-3000:])

        # The comparison detects a restart that loses the contact's state:
        # step 3's displacement set to zero, and its digest recorded anew
        # (as if the run had written it so; without that the restart
        # refuses the file, refusals() below).
        forgetful = os.path.join(work, "forgetful")
        killed_copy(full, forgetful, KILLED_AFTER)
        with h5py.File(step_file(forgetful, KILLED_AFTER), "r+") as f:
            f["nodes/displacement"][...] = 0.0
        record_digest(forgetful, KILLED_AFTER)
        p = tribos(args, np_, ["--restart", forgetful])
        if check(p.returncode == 0, "np %d: a restart from a zeroed step %d (exit %d)" % (np_, KILLED_AFTER, p.returncode)):
            worst = largest_difference(forgetful, full)
            check(worst > 1e3 * TOLERANCE, "np %d: from a zeroed displacement the history differs by %.1e (> %g): the "
                  "comparison sees the state a restart carries" % (np_, worst, 1e3 * TOLERANCE))

        # The refusals on 2 ranks, the stricter case: every rank reads the
        # files and refuses together (1 rank runs the same checks alone).
        if np_ == 2:
            refusals(args, np_, full, work)
            one_rank = os.path.join(args.work, "np1", "full")
            refusal(args, 2, "a result of 1 rank", one_rank,
                    re.escape(os.path.join(one_rank, BASE + ".json")) + r": the run ran on 1 ranks; restart it on as many")

    if failures:
        print("%d check(s) failed" % len(failures))
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
