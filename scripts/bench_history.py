#!/usr/bin/python3
"""Load-history benchmark: a 20-step history of the Coulomb brick (F = 0.3)
side by side with the single static solve of the same mesh, in one run of
this script, with the user's defaults: `Solver/Outer Algorithm = Auto`
(the matrix-free semismooth Newton method for the static solve and for the
steps of the history); --set "Solver/Outer Algorithm=Algorithm2" measures
Algorithm 2 in both.

usage: scripts/bench_history.py [--levels 24 48] [--ranks 2] [--steps 20]
           [--set NAME=VALUE ...] [--tribos build/drivers/tribos]

The history (input/brick_coulomb_F03.xml, Mesh/Subdomain Size = Auto): the
top pressure rises in the first quarter of the steps (0.25, 0.5, ... of
its value) and is then held, while the free-end traction rises to its full
value over the next three eighths and goes back to zero over the last
three eighths. K, its factorizations, F and the coarse space are built once
and serve every step; each step starts from the multipliers of the one
before. For every level k (3k x k x k cubes of 6 tetrahedra) it prints a
row: mesh dofs, the static run's wall time, setup and n_A, the history's
wall time, setup and n_A, the ratio of the two walls, the mean and largest
solve time of a step, the mean n_A of a step, and the largest KKT residual
over all steps. docs/benchmarks.md holds its table.
"""
import argparse
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from bench_scaling import mpirun, run  # noqa: E402 (one way to run the driver for every benchmark)
KKT = ("equilibrium", "dirichlet", "nonpenetration", "complementarity", "friction_law")


def history(steps):
    """The --set entries of the history of `steps` steps at t = 1..steps."""
    press = steps / 4.0
    peak = press + (steps - press) / 2.0
    times = ", ".join(str(k) for k in range(1, steps + 1))
    return ["Load Steps/Times={%s}" % times,
            "Load Curves/press/Times={0, %g, %d}" % (press, steps),
            "Load Curves/press/Values={0, 1, 1}",
            "Load Curves/shear/Times={0, %g, %g, %d}" % (press, peak, steps),
            "Load Curves/shear/Values={0, 0, 1, 0}",
            "Boundary Conditions/Traction/top/Curve=press",
            "Boundary Conditions/Traction/free end/Curve=shear"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--levels", type=int, nargs="+", default=[24, 48])
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--steps", type=int, default=20)
    ap.add_argument("--set", action="append", default=[], help="extra NAME=VALUE for both runs")
    ap.add_argument("--tribos", default=os.path.join(ROOT, "build/drivers/tribos"))
    args = ap.parse_args()
    if not os.access(args.tribos, os.X_OK):
        sys.exit("bench_history: %s is not built (scripts/build.sh builds it)" % args.tribos)
    print("| k | mesh dofs | static wall s | static setup s | static n_A | history wall s | history setup s "
          "| history n_A | ratio | step solve s (mean / max) | n_A per step | KKT max (all steps) |")
    print("|---" * 12 + "|")
    for level in args.levels:
        base = mpirun(args.ranks) + [args.tribos, os.path.join(ROOT, "input/brick_coulomb_F03.xml"),
                                     "--set", "Mesh/Level=%d" % level, "--set", "Mesh/Subdomain Size=Auto",
                                     "--set", "Solver/Outer Algorithm=Auto"]
        for e in args.set:
            base += ["--set", e]
        static, static_wall = run(base)
        cmd = list(base)
        for e in history(args.steps):
            cmd += ["--set", e]
        hist, hist_wall = run(cmd)
        steps = hist["steps"]
        solves = [r["time_solve_s"] for r in steps]
        kkt = max(r["kkt"][k] for r in steps for k in KKT)
        ok = "" if hist["converged"] and len(steps) == args.steps else " (stopped: %s)" % hist["stop_reason"]
        mesh_dofs = 3 * (3 * level + 1) * (level + 1) ** 2
        print("| %d | %d | %.1f | %.1f | %d | %.1f | %.1f | %d | %.2f | %.2f / %.2f | %.0f | %.1e%s |"
              % (level, mesh_dofs, static_wall, static["time_setup_s"], static["n_A"], hist_wall,
                 hist["time_setup_s"], sum(r["n_A"] for r in steps), hist_wall / static_wall,
                 sum(solves) / len(solves), max(solves), sum(r["n_A"] for r in steps) / len(steps), kkt, ok))
        sys.stdout.flush()


if __name__ == "__main__":
    main()
