#!/usr/bin/python3
"""A load history's output neither overwrites another result nor grows
without bound:

  check_history_output.py --work DIR --input BRICK.xml -- MPIEXEC NPFLAG EXTRA... TRIBOS

(MPIEXEC NPFLAG: the launcher and its rank-count flag; the rank count is
inserted after NPFLAG.) On the linear brick (Level 1, 3 load steps), on 1
and 2 ranks, each refusal exits 1 before any work with a message naming
both files, and leaves the directory byte for byte as it was:

  - `--summary DIR/solution.step0002.h5` (step 2's data file), also through
    a symbolic link and under --restart; `--summary DIR/solution.step0099.h5`
    (a data file of the Base Name that the run's first step removes);
  - a run with Output/Base Name = solution.step0001 into DIR, which holds
    the series `solution` (its data file would be step 1's);
  - a run with Base Name `solution` into a directory holding the one-step
    result `solution.step0001` (the series' first step would remove it);
  - a history whose output cannot fit: 10^5 steps into a 16 MB tmpfs
    (skipped with a message where mount is refused), refused by the
    estimate naming Load Steps/Times.

And the steps table grows by one complete row a step: after the 3 steps it
has 3 rows, each naming its step file and that file's SHA-256.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import check_restart  # noqa: E402 (one way to run the driver and compare directories)
from check_restart import check, failures, snapshot  # noqa: E402

sha256 = check_restart.digest
SETS = ["Mesh/Level=1", "Load Steps/Times={0.5, 1, 1.5}"]


def tribos(args, np_, extra, sets=SETS):
    return check_restart.tribos(args, np_, extra, sets)


def refusal(args, np_, name, d, regex, extra, sets=SETS):
    before = snapshot(d)
    p = tribos(args, np_, extra, sets)
    ok = p.returncode == 1 and re.search(regex, p.stderr) is not None
    check(ok, "np %d, %s: exit 1 naming /%s/ (exit %d)" % (np_, name, regex, p.returncode))
    if not ok:
        print(p.stderr[-2000:])
    check(snapshot(d) == before, "np %d, %s: the directory is left as it was" % (np_, name))


def too_long(args, np_, work):
    small = os.path.join(work, "small")
    os.makedirs(small, exist_ok=True)
    subprocess.run(["umount", small], capture_output=True)
    m = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=16m", "tmpfs", small], capture_output=True, text=True)
    if m.returncode != 0:
        print("skipped: cannot mount a small tmpfs here (%s)" % m.stderr.strip())
        return
    try:
        steps = 100000
        with open(args.input) as f:
            text = f.read()
        times = "{" + ", ".join(repr((k + 1) / steps) for k in range(steps)) + "}"
        long_input = os.path.join(work, "long.xml")
        with open(long_input, "w") as f:
            f.write(text.replace('<ParameterList name="Output">',
                             '<ParameterList name="Load Steps">\n    <Parameter name="Times" type="Array(double)" value="'
                             + times + '"/>\n  </ParameterList>\n  <ParameterList name="Output">', 1))
        saved, args.input = args.input, long_input
        try:
            refusal(args, np_, "10^5 steps into 16 MB", small,
                    r"the results of the 100000 steps of \"Load Steps/Times\" need about .* GB.*has .* GB free",
                    ["--output", small], ["Mesh/Level=1"])
        finally:
            args.input = saved
    finally:
        subprocess.run(["umount", small], capture_output=True)


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
        series = os.path.join(work, "series")
        p = tribos(args, np_, ["--output", series])
        if not check(p.returncode == 0, "np %d: the history of 3 steps (exit %d)" % (np_, p.returncode)):
            print(p.stderr[-3000:])
            continue
        with open(os.path.join(series, "solution.json")) as f:
            s = json.load(f)
        with open(os.path.join(series, s["steps_file"])) as f:
            rows = [json.loads(line) for line in f]
        check(s["steps_completed"] == 3 and [r["step"] for r in rows] == [1, 2, 3] and
              all(r["sha256"] == sha256(os.path.join(series, r["file"])) for r in rows),
              "np %d: the steps table has a row a step, each with its file's SHA-256" % np_)

        step2 = os.path.join(series, "solution.step0002.h5")
        both = re.escape("--summary ") + r".*solution\.step0002\.h5 is the data file of load step 2 of the result " + \
            re.escape(os.path.join(series, "solution.json"))
        refusal(args, np_, "--summary on step 2", series, both, ["--output", series, "--summary", step2])
        refusal(args, np_, "--summary on step 2 under --restart", series, both,
                ["--restart", series, "--summary", step2])
        link = os.path.join(work, "link.json")
        os.symlink(step2, link)
        refusal(args, np_, "--summary through a link to step 2", series,
                re.escape(link) + r" is the data file of load step 2", ["--output", series, "--summary", link])
        refusal(args, np_, "--summary on a step the run removes", series,
                r"solution\.step0099\.h5 is a data file of Output/Base Name = solution in .*, which the run removes",
                ["--output", series, "--summary", os.path.join(series, "solution.step0099.h5")])
        refusal(args, np_, "Base Name solution.step0001 beside the series solution", series,
                r"Output/Base Name = solution\.step0001: the directory holds the result " +
                re.escape(os.path.join(series, "solution.json")) + r", whose load step file " +
                re.escape(os.path.join(series, "solution.step0001.h5")) + " would be this run's data file",
                ["--output", series], ["Mesh/Level=1", "Output/Base Name=solution.step0001"])

        single = os.path.join(work, "single")
        p = tribos(args, np_, ["--output", single], ["Mesh/Level=1", "Output/Base Name=solution.step0001"])
        check(p.returncode == 0, "np %d: a one-step result named solution.step0001 (exit %d)" % (np_, p.returncode))
        refusal(args, np_, "the series solution beside the result solution.step0001", single,
                r"Output/Base Name = solution: the directory holds the result " +
                re.escape(os.path.join(single, "solution.step0001.json")) + r", whose data file " +
                re.escape(os.path.join(single, "solution.step0001.h5")) + " has the name of a load step file",
                ["--output", single])
        too_long(args, np_, work)
    if failures:
        print("%d check(s) failed" % len(failures))
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
