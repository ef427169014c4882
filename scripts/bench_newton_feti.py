#!/usr/bin/python3
"""Semismooth Newton against Algorithm 2 on the FETI seed brick (Kucera):
Coulomb friction F = 0.1 and 0.3, levels k = 4..12, side by side in one run.
Newton runs at its tolerance (default 1e-8), Algorithm 2 at its default 1e-6
and at the Newton tolerance; each row gives the solve time (setup excluded:
it is the same FETI setup), the iterations and the largest KKT residual of
the written result (equilibrium, non-penetration, complementarity, friction
law; docs/friction.md).

usage: scripts/bench_newton_feti.py [--levels 4 6 8 10 12] [--newton-tolerance 1e-8] [--ranks 1]
"""
import argparse
import os

from bench_brick import LEVELS, run

KKT = ("equilibrium", "nonpenetration", "complementarity", "friction_law")


def kkt(s):
    return max(s["kkt"][k] for k in KKT)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--levels", type=int, nargs="+", default=LEVELS)
    ap.add_argument("--newton-tolerance", type=float, default=1e-8)
    ap.add_argument("--ranks", type=int, default=1)
    args = ap.parse_args()
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    tol = args.newton_tolerance
    for F in ["0.1", "0.3"]:
        print("\n#### F = %s, %d rank(s)\n" % (F, args.ranks))
        print("| k | n | m | setup [s] | Newton %g: solve [s] | steps | KKT | Alg. 2 1e-6: solve [s] | Iter | n_A | KKT "
              "| Alg. 2 %g: solve [s] | Iter | n_A | KKT |" % (tol, tol))
        print("|---" * 15 + "|")
        for level in args.levels:
            newton = run(root, F, level, "Semismooth Newton", tol, args.ranks,
                         ["Solver/Semismooth Newton/Relative Tolerance=%g" % tol])
            a2 = run(root, F, level, "Algorithm2", 1e-6, args.ranks, [])
            a2t = run(root, F, level, "Algorithm2", tol, args.ranks, [])
            row = [str(level), str(newton["primal_dofs"]), str(newton["dual_dofs"]), "%.2f" % newton["time_setup_s"],
                   "%.3f" % newton["time_solve_s"], str(newton["outer_iterations"]), "%.1e" % kkt(newton)]
            for s in (a2, a2t):
                row += ["%.3f" % s["time_solve_s"], str(s["outer_iterations"]), str(s["n_A"]), "%.1e" % kkt(s)]
            bad = [s.get("stop_reason") for s in (newton, a2, a2t) if not s["converged"]]
            if bad:
                row[0] += " (not converged: %s)" % "; ".join(bad)
            print("| " + " | ".join(row) + " |", flush=True)


if __name__ == "__main__":
    main()
