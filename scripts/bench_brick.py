#!/usr/bin/python3
"""Seed brick benchmark (Kucera): Coulomb friction F = 0.1 and 0.3, levels
k = 4..12, Algorithm 2 and MSA + Algorithm 1, printed as markdown tables in the
seed's format (n, m, Time, Iter, n_A = qpp + qpq) next to the seed's numbers.

usage: scripts/bench_brick.py [--levels 4 6 8 10 12] [--tolerance 1e-6] [--ranks 1] [--set NAME=VALUE ...]

Setup is assembly, factorization and (explicit dual operator) the dense
blocks of K+; solve is everything after it. Peak RSS is that of the
Algorithm 2 run.
"""
import argparse
import json
import os
import subprocess
import tempfile

SEED = {  # F: [(n, m, Time, Iter, n_A, qpp, qpq)] for k = 4, 6, 8, 10, 12
    "0.1": [(900, 180, 1, 5, 102, 63, 39), (2646, 378, 11, 5, 180, 98, 82), (5832, 648, 34, 5, 156, 94, 62),
            (10890, 990, 67, 5, 112, 50, 62), (18252, 1404, 221, 5, 155, 73, 82)],
    "0.3": [(900, 180, 2, 7, 140, 46, 32), (2646, 378, 12, 7, 186, 54, 69), (5832, 648, 38, 7, 169, 72, 50),
            (10890, 990, 94, 7, 153, 35, 49), (18252, 1404, 254, 7, 176, 78, 54)],
}
LEVELS = [4, 6, 8, 10, 12]


def run(root, F, level, algorithm, tol, ranks, extra):
    with tempfile.TemporaryDirectory() as tmp:
        summary = os.path.join(tmp, "s.json")
        cmd = []
        if ranks > 1:
            cmd = ["mpirun", "-np", str(ranks), "--oversubscribe"] + (["--allow-run-as-root"] if os.getuid() == 0 else [])
        cmd += [os.path.join(root, "build/drivers/tribos"), os.path.join(root, "input/brick_coulomb_F0%s.xml" % F[-1]),
                "--summary", summary, "--set", "Mesh/Level=%d" % level, "--set", "Output/Write Results=false",
                "--set", "Solver/Outer Algorithm=%s" % algorithm,
                "--set", "Solver/Algorithm 2/Relative Tolerance=%g" % tol,
                "--set", "Solver/Algorithm 1/SMALBE/Relative Tolerance=%g" % tol]
        for e in extra:
            cmd += ["--set", e]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        with open(summary) as f:
            return json.load(f)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--levels", type=int, nargs="+", default=LEVELS)
    ap.add_argument("--tolerance", type=float, default=1e-6)
    ap.add_argument("--ranks", type=int, default=1)
    ap.add_argument("--set", action="append", default=[], help="extra parameter NAME=VALUE for the driver")
    args = ap.parse_args()
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    for F in ["0.1", "0.3"]:
        print("\n#### F = %s, relative tolerance %g, %d rank(s)\n" % (F, args.tolerance, args.ranks))
        print("| k | n | m | setup [s] | Algorithm 2: Time [s] | Iter | n_A (=qpp+qpq) | peak RSS [MB] | MSA+Alg. 1: Time [s] | MSA its | "
              "SMALBE its | n_A (=qpp+qpq) | KKT friction law (Alg. 2) | seed n | seed m | seed Time | seed Iter | seed n_A |")
        print("|---" * 18 + "|")
        for level in args.levels:
            a2 = run(root, F, level, "Algorithm2", args.tolerance, args.ranks, args.set)
            msa = run(root, F, level, "MSA+Algorithm1", args.tolerance, args.ranks, args.set)
            seed = SEED[F][LEVELS.index(level)] if level in LEVELS else None
            def na(s):
                return "%d (=%d+%d)" % (s["n_A"], s["n_A_qpp"], s["n_A_qpq"])
            row = [str(level), str(a2["primal_dofs"]), str(a2["dual_dofs"]), "%.2f" % a2["time_setup_s"],
                   "%.2f" % a2["time_solve_s"], str(a2["outer_iterations"]), na(a2), "%.0f" % a2["peak_rss_mb"],
                   "%.2f" % msa["time_solve_s"], str(msa["msa_iterations"]), str(msa["outer_iterations"]), na(msa),
                   "%.1e" % a2["kkt"]["friction_law"]]
            row += ["%d" % seed[0], "%d" % seed[1], "%d" % seed[2], "%d" % seed[3], "%d (=%d+%d)" % seed[4:]] if seed else ["-"] * 5
            if not (a2["converged"] and msa["converged"]):
                row[0] += " (not converged: %s / %s)" % (a2.get("stop_reason"), msa.get("stop_reason"))
            print("| " + " | ".join(row) + " |", flush=True)


if __name__ == "__main__":
    main()
