#!/usr/bin/python3
"""The cost of writing a long load history: a step must cost the same at
step 10 and at step 10^4 (docs/load_history_output.md).

usage: scripts/bench_history_output.py [--steps N] [--ranks R] [--level K] [--tribos PATH]

Runs input/brick_linear.xml at Mesh/Level K with Load Steps/Times = 1/N,
2/N, ..., 1 on R ranks into a scratch directory, and prints one table row:
the wall time, the seconds a step, and the seconds of the first and of the
last hundred steps (from the step files' modification times), whose ratio
is 1 when writing a step does not grow with the steps before it.
"""
import argparse
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tribos_summary  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--steps", type=int, default=3000)
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--level", type=int, default=1)
    ap.add_argument("--tribos", default=os.path.join(ROOT, "build/drivers/tribos"))
    args = ap.parse_args()
    if not os.access(args.tribos, os.X_OK):
        sys.exit("bench_history_output: %s is not built (scripts/build.sh builds it)" % args.tribos)
    n = args.steps
    times = "{" + ", ".join(repr((k + 1) / n) for k in range(n)) + "}"
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out")
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(args.ranks), args.tribos,
               os.path.join(ROOT, "input/brick_linear.xml"), "--quiet", "--output", out,
               "--set", "Mesh/Level=%d" % args.level, "--set", "Load Steps/Times=" + times]
        t0 = time.monotonic()
        p = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        wall = time.monotonic() - t0
        if p.returncode != 0:
            sys.exit("bench_history_output: the run failed (exit %d): %s" % (p.returncode, p.stderr[-2000:]))
        s = tribos_summary.load(os.path.join(out, "solution.json"))
        # A summary without the steps' file names (before the steps table)
        # names them by the series' rule: 4 digits, more when N needs them.
        width = max(4, len(str(n)))
        files = [r.get("file", "solution.step%0*d.h5" % (width, r["step"])) for r in s["steps"]]
        mtime = [os.path.getmtime(os.path.join(out, f)) for f in files]
        span = min(100, n - 1)
        first, last = mtime[span] - mtime[0], mtime[-1] - mtime[-1 - span]
        size = sum(os.path.getsize(os.path.join(out, f)) for f in os.listdir(out))
    print("| steps | ranks | nodes | wall s | ms a step | first %d steps s | last %d steps s | last / first | output MB |"
          % (span, span))
    print("|---" * 9 + "|")
    print("| %d | %d | %d | %.1f | %.1f | %.2f | %.2f | %.2f | %.0f |"
          % (n, args.ranks, s["nodes"], wall, 1e3 * wall / n, first, last, last / first if first > 0 else float("nan"),
             size / 1e6))


if __name__ == "__main__":
    main()
