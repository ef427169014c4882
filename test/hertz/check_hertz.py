#!/usr/bin/python3
"""Hertz contact test: run tribos on input/hertz_sphere.xml, then check the
result against Hertz's solution (scripts/hertz.py computes the figures).

usage: check_hertz.py --out DIR [--tol-a T] [--tol-p0 T] [--kkt K] [--estar E]
                      -- COMMAND...          run COMMAND (tribos ... --output DIR), then check
       check_hertz.py --compare A.json B.json [--rel R]
                                             two checked runs agree

Checks: exit status 0, `converged` in the summary, every KKT residual of the
summary at most K (relative residuals), |a_h / a - 1| <= tol-a and
|p0_h / p0 - 1| <= tol-p0 (estimators: scripts/hertz.py, docs/hertz.md).
The figures go to DIR/hertz_check.json. --estar replaces E* of the analytic
solution (to show that a wrong E* fails); --set arguments inside COMMAND
reach the solver only, never the analytic side, so that a wrong model (e.g.
the rigid plane instead of the block) fails.
"""
import argparse
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(HERE)), "scripts"))
import hertz  # noqa: E402


def compare(a_file, b_file, rel):
    with open(a_file) as f:
        a = json.load(f)
    with open(b_file) as f:
        b = json.load(f)
    bad = []
    for key in ("F", "a_h", "p0_h", "a_fit"):
        d = abs(a[key] - b[key]) / max(abs(a[key]), 1e-300)
        print("%-5s %.10g  %.10g  rel. diff %.2e (limit %.0e)" % (key, a[key], b[key], d, rel))
        if d > rel:
            bad.append(key)
    if a["active"] != b["active"]:
        bad.append("active (%d vs %d)" % (a["active"], b["active"]))
    if bad:
        sys.exit("check_hertz.py: the runs differ in " + ", ".join(bad))
    print("check_hertz.py: the runs agree")


def main():
    argv = sys.argv[1:]
    command = []
    if "--" in argv:
        i = argv.index("--")
        argv, command = argv[:i], argv[i + 1:]
    ap = argparse.ArgumentParser()
    ap.add_argument("--out")
    ap.add_argument("--tol-a", type=float, default=0.04)
    ap.add_argument("--tol-p0", type=float, default=0.10)
    ap.add_argument("--kkt", type=float, default=1e-5)
    ap.add_argument("--estar", type=float)
    ap.add_argument("--compare", nargs=2)
    ap.add_argument("--rel", type=float, default=1e-4)
    args = ap.parse_args(argv)
    if args.compare:
        return compare(*args.compare, args.rel)
    if not command or not args.out:
        sys.exit("check_hertz.py: give --out DIR and the command after --")
    done = subprocess.run(command, stdout=subprocess.DEVNULL)
    if done.returncode != 0:
        sys.exit("check_hertz.py: tribos exited with %d" % done.returncode)
    row = hertz.analyse(args.out)
    if args.estar:
        row["Estar"] = args.estar
        row["a"], row["p0"] = hertz.hertz(row["F"], hertz.RADIUS, args.estar)
        row["err_a"], row["err_p0"] = row["a_h"] / row["a"] - 1, row["p0_h"] / row["p0"] - 1
    failures = []
    if not row["converged"]:
        failures.append("not converged")
    for key, value in row["kkt"].items():
        if key != "limit" and (value is None or value > args.kkt):
            failures.append("KKT %s = %s > %g" % (key, value, args.kkt))
    print("F = %.2f N, E* = %.1f MPa, h = %.4f mm, %d active nodes" % (row["F"], row["Estar"], row["h"], row["active"]))
    for name, est, exact, err, tol in (("a", row["a_h"], row["a"], row["err_a"], args.tol_a),
                                       ("p0", row["p0_h"], row["p0"], row["err_p0"], args.tol_p0)):
        ok = abs(err) <= tol
        print("%-2s FE %.5g  Hertz %.5g  error %+.2f%% (tolerance %.0f%%) %s" % (name, est, exact, 100 * err, 100 * tol,
                                                                              "ok" if ok else "FAILED"))
        if not ok:
            failures.append("%s error %+.2f%% beyond %.0f%%" % (name, 100 * err, 100 * tol))
    with open(os.path.join(args.out, "hertz_check.json"), "w") as f:
        json.dump({k: v for k, v in row.items() if k not in ("r", "pressure", "status", "master_weight")}, f, indent=1)
    if failures:
        sys.exit("check_hertz.py: " + "; ".join(failures))
    print("check_hertz.py: Hertz ok")


if __name__ == "__main__":
    main()
