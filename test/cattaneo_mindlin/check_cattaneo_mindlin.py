#!/usr/bin/python3
"""Cattaneo-Mindlin test: run tribos on input/cattaneo_mindlin.xml (the load
history) and on the same mesh with the contact stuck (the reference for the
linear part of the tangential displacement), then check the result against
the analytic solution (scripts/cattaneo_mindlin.py computes the figures;
docs/cattaneo_mindlin.md).

usage: check_cattaneo_mindlin.py --out DIR [--tol-c T] [--tol-s T] [--tol-w T] [--tol-xp T]
                                 [--tol-spurious T] [--kkt K]
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
  spurious  the friction after the normal load alone,
          sum |f_T| / (F sum f_N) (exact: 0)                    <= tol-spurious
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


def pair_friction(directory):
    """The friction coefficient of the pair, from the run's parameters."""
    import xml.etree.ElementTree as ET

    path = os.path.join(directory, "solution.parameters.xml")
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as e:
        sys.exit("check_cattaneo_mindlin.py: cannot read %s: %s" % (path, e))
    for pairs in root.iter("ParameterList"):
        if pairs.get("name") != "Pairs":
            continue
        for pair in pairs.findall("ParameterList"):
            if pair.get("name") == cm.PAIR:
                for p in pair.findall("Parameter"):
                    if p.get("name") == "Friction Coefficient":
                        return float(p.get("value"))
    sys.exit("check_cattaneo_mindlin.py: %s names no Friction Coefficient of the pair '%s'" % (path, cm.PAIR))


def compare(directories, rel):
    """Every step of every run: P and Q to rel (relative to P), delta to rel
    of its largest value, and node by node the contact forces to rel of the
    largest normal force; the stick/slip status of every node whose
    decision is clear by more than the forces may differ (its slip margin
    F f_N - |f_T| beyond 2 rel of the largest normal force) exactly. A node
    within that of the stick/slip boundary (or of losing contact) may read
    either way: at the accuracy the runs promise its status is not
    determined, and counting such nodes would compare round-off."""
    import numpy as np

    runs = [cm.read_run(d) for d in directories]
    ref = runs[0]
    friction = pair_friction(directories[0])
    bad = []
    worst = 0.0
    undecided = 0
    for d, run in zip(directories[1:], runs[1:]):
        if len(run["steps"]) != len(ref["steps"]):
            bad.append("%s has %d steps, %s %d" % (d, len(run["steps"]), directories[0], len(ref["steps"])))
            continue
        # The numbering of the written mesh follows the decomposition: match
        # the contact points by their positions.
        order = match_points(ref["x"], run["x"])
        if order is None:
            bad.append("%s and %s have different contact points" % (directories[0], d))
            continue
        for k, (a, b) in enumerate(zip(ref["steps"], run["steps"]), 1):
            for key in ("P", "Q", "delta"):
                scale = abs(a["P"]) if key != "delta" else max(abs(s["delta"]) for s in ref["steps"]) or 1.0
                diff = abs(a[key] - b[key]) / scale
                worst = max(worst, diff)
                if diff > rel:
                    bad.append("step %d: %s %.10g vs %.10g" % (k, key, a[key], b[key]))
            scale = float(np.abs(a["fn"]).max()) or 1.0
            fn_b, ft_b, status_b = b["fn"][order], b["ft"][order], b["status"][order]
            diff = max(float(np.abs(a["fn"] - fn_b).max()), float(np.abs(a["ft"] - ft_b).max())) / scale
            worst = max(worst, diff)
            if diff > rel:
                bad.append("step %d: nodal contact forces differ by %.2e of the largest" % (k, diff))
            margin = np.minimum(np.abs(friction * a["fn"] - np.linalg.norm(a["ft"], axis=1)), np.abs(a["fn"]))
            clear = margin > 2 * rel * scale
            undecided += int((~clear & (a["status"] != status_b)).sum())
            for i in np.flatnonzero(clear & (a["status"] != status_b)):
                bad.append("step %d: the node at %s is %s in %s, %s in %s (margin %.2e of the largest normal force)"
                           % (k, tuple(ref["x"][i]), STATUS[a["status"][i]], directories[0], STATUS[status_b[i]], d,
                              margin[i] / scale))
    print("largest relative difference %.2e (limit %.0e) over %d runs of %d steps; %d statuses within the "
          "difference of the stick/slip boundary read differently" % (worst, rel, len(runs), len(ref["steps"]),
                                                                     undecided))
    if bad:
        sys.exit("check_cattaneo_mindlin.py: the runs differ: " + "; ".join(bad[:10]))
    print("check_cattaneo_mindlin.py: the runs agree")


STATUS = {0: "out of contact", 1: "sticking", 2: "slipping"}


def match_points(x, y):
    """The row of y at each point of x (equal to 1e-9 of the extent), or None."""
    import numpy as np

    if x.shape != y.shape:
        return None
    tol = 1e-9 * max(float(np.abs(x).max()), 1.0)
    kx, ky = np.lexsort(np.round(x / tol).T[::-1]), np.lexsort(np.round(y / tol).T[::-1])
    if np.abs(x[kx] - y[ky]).max() > 10 * tol:
        return None
    order = np.empty(len(x), dtype=int)
    order[kx] = ky
    return order


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
    ap.add_argument("--tol-spurious", type=float, default=1.0)
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
                             ("x_P / a (pressure centre)", row["xp_max_a"], args.tol_xp),
                             ("spurious friction / (F P)", row["spurious"], args.tol_spurious)):
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
