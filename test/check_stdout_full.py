#!/usr/bin/python3
"""tribos with stdout on /dev/full, where every write fails with ENOSPC:

  check_stdout_full.py --work DIR -- TRIBOS

The summary of a converged run, the usage (--help) and the parameters
(--print-parameters) that cannot be printed end the run with exit 3 and the
reason on stderr, never 0; --summary FILE still holds the summary. The same
runs with stdout on /dev/null exit 0, which shows that the checks can tell.
"""
import json
import os
import subprocess
import sys

SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
INPUT = os.path.join(SOURCE, "input", "brick_linear.xml")
failures = []


def expect(ok, what, err=""):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)
        print("--- stderr ---\n" + err[-2000:])


def run(command, sink):
    with open(sink, "w") as out:
        return subprocess.run(command, stdout=out, stderr=subprocess.PIPE, text=True, timeout=300)


def main():
    sep = sys.argv.index("--")
    work = os.path.abspath(sys.argv[sys.argv.index("--work") + 1])
    tribos = sys.argv[sep + 1]
    os.makedirs(work, exist_ok=True)
    summary = os.path.join(work, "summary.json")
    solve = [tribos, INPUT, "--quiet", "--set", "Mesh/Level=2", "--output", os.path.join(work, "out")]
    cases = [
        ("the summary", solve + ["--summary", summary],
         "tribos: run failed: cannot write the summary on stdout: No space left on device (it is in %s); "
         "the result is written" % summary),
        ("the usage", [tribos, "--help"], "tribos: run failed: cannot write the usage on stdout: No space left"),
        ("the parameters", [tribos, "--print-parameters", INPUT],
         "tribos: run failed: cannot write the parameters on stdout: No space left"),
    ]
    for what, command, said in cases:
        p = run(command, "/dev/null")
        expect(p.returncode == 0, "%s on /dev/null: exit 0 (exit %d)" % (what, p.returncode), p.stderr)
        if os.path.exists(summary):
            os.remove(summary)
        p = run(command, "/dev/full")
        expect(p.returncode == 3, "%s on /dev/full: exit 3 (exit %d)" % (what, p.returncode), p.stderr)
        expect(said in p.stderr, "%s on /dev/full: the reason on stderr" % what, p.stderr)
        if command is cases[0][1]:
            expect(os.path.exists(summary) and json.load(open(summary)).get("converged") is True,
                   "the summary file written although stdout failed")
    if failures:
        sys.exit("%d check(s) failed" % len(failures))


if __name__ == "__main__":
    main()
