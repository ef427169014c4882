#!/usr/bin/python3
"""Cattaneo-Mindlin test: run tribos on input/cattaneo_mindlin.xml (the load
history) and on the same mesh with the contact stuck (the reference for the
linear part of the tangential displacement), then check the result against
the analytic solution (scripts/cattaneo_mindlin.py computes the figures;
docs/cattaneo_mindlin.md).

usage: check_cattaneo_mindlin.py --out DIR [--tol-c T] [--tol-s T] [--tol-w T] [--tol-xp T] [--kkt K]
                                 -- COMMAND...
           COMMAND (tribos INPUT ... without --output) runs twice: with --output DIR/history,
           and with --output DIR/stick and the stuck reference's --set arguments
       check_cattaneo_mindlin.py --compare DIR1 DIR2 ... [--rel R]
           results (directories of runs of one history) agree step by step

Checks: exit status 0 and `converged` (every step), every step's KKT
residuals at most K, and against the analytic answers (E, nu, F read from
input/cattaneo_mindlin.xml, never from the command: a wrong model run
against the right answer fails):
  err_c   max over the tangential steps of |c - c_exact| / a   <= tol-c
  err_s   max |s - s_exact| / s_exact(Q*)                       <= tol-s
  |err_w| the loop's width at Q = 0, relative                   <= tol-w
  x_P     max |pressure centre| / a                             <= tol-xp
The figures go to DIR/cattaneo_mindlin_check.json.
"""
import argparse
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(HERE)), "scripts"))
import cattaneo_mindlin as cm  # noqa: E402


def compare(directories, rel):
    """Every step of every run: P and Q to rel (relative to P), the stick
    and slip counts exactly."""
    runs = [cm.read_run(d) for d in directories]
    ref = runs[0]
    bad = []
    worst = 0.0
    for d, run in zip(directories[1:], runs[1:]):
        if len(run["steps"]) != len(ref["steps"]):
            bad.append("%s has %d steps, %s %d" % (d, len(run["steps"]), directories[0], len(ref["steps"])))
            continue
        for k, (a, b) in enumerate(zip(ref["steps"], run["steps"]), 1):
            for key in ("P", "Q", "delta"):
                scale = abs(a["P"]) if key != "delta" else max(abs(s["delta"]) for s in ref["steps"]) or 1.0
                diff = abs(a[key] - b[key]) / scale
                worst = max(worst, diff)
                if diff > rel:
                    bad.append("step %d: %s %.10g vs %.10g" % (k, key, a[key], b[key]))
            for code, name in ((1, "stick"), (2, "slip")):
                na, nb = int((a["status"] == code).sum()), int((b["status"] == code).sum())
                if na != nb:
                    bad.append("step %d: %d vs %d %s nodes" % (k, na, nb, name))
    print("largest relative difference %.2e (limit %.0e) over %d runs of %d steps"
          % (worst, rel, len(runs), len(ref["steps"])))
    if bad:
        sys.exit("check_cattaneo_mindlin.py: the runs differ: " + "; ".join(bad[:10]))
    print("check_cattaneo_mindlin.py: the runs agree")


def run(command, directory, extra=()):
    cmd = list(command) + ["--output", directory, "--quiet"]
    for s in extra:
        cmd += ["--set", s]
    done = subprocess.run(cmd, stdout=subprocess.DEVNULL)
    if done.returncode != 0:
        sys.exit("check_cattaneo_mindlin.py: tribos exited with %d (%s)" % (done.returncode, " ".join(cmd)))


def main():
    argv = sys.argv[1:]
    command = []
    if "--" in argv:
        i = argv.index("--")
        argv, command = argv[:i], argv[i + 1:]
    ap = argparse.ArgumentParser()
    ap.add_argument("--out")
    ap.add_argument("--tol-c", type=float, default=0.15)
    ap.add_argument("--tol-s", type=float, default=0.20)
    ap.add_argument("--tol-w", type=float, default=0.20)
    ap.add_argument("--tol-xp", type=float, default=0.05)
    ap.add_argument("--kkt", type=float, default=1e-5)
    ap.add_argument("--compare", nargs="+")
    ap.add_argument("--rel", type=float, default=1e-5)
    args = ap.parse_args(argv)
    if args.compare:
        return compare(args.compare, args.rel)
    if not command or not args.out:
        sys.exit("check_cattaneo_mindlin.py: give --out DIR and the command after --")
    history, stick = os.path.join(args.out, "history"), os.path.join(args.out, "stick")
    run(command, history)
    run(command, stick, cm.STICK_SETS)
    row = cm.analyse(history, stick)
    failures = []
    if not row["converged"]:
        failures.append("not converged")
    if not row["kkt"] <= args.kkt:
        failures.append("a KKT residual %.2e > %g" % (row["kkt"], args.kkt))
    print("P = %.1f N, Q*/(F P) = %.3f, Hertz a = %.4f mm, h = %.3f mm, largest KKT residual %.1e"
          % (row["P"], row["Qstar_FP"], row["a"], row["h"], row["kkt"]))
    for name, value, tol in (("err_c (stick radius / a)", row["err_c"], args.tol_c),
                             ("err_s (slip displacement)", row["err_s"], args.tol_s),
                             ("err_w (loop width at Q = 0)", row["err_w"], args.tol_w),
                             ("x_P / a (pressure centre)", row["xp_max_a"], args.tol_xp)):
        ok = value is not None and abs(value) <= tol
        print("%-28s %s  (tolerance %.3g) %s" % (name, "-" if value is None else "%+.4f" % value, tol,
                                                 "ok" if ok else "FAILED"))
        if not ok:
            failures.append("%s = %s beyond %g" % (name, value, tol))
    with open(os.path.join(args.out, "cattaneo_mindlin_check.json"), "w") as f:
        json.dump(row, f, indent=1)
    if failures:
        sys.exit("check_cattaneo_mindlin.py: " + "; ".join(failures))
    print("check_cattaneo_mindlin.py: Cattaneo-Mindlin ok")


if __name__ == "__main__":
    main()
