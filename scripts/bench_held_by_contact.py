#!/usr/bin/python3
"""Bodies held by their contact alone: the user's default (`Solver/Outer
Algorithm = Auto`, which solves them by the matrix-free Newton method)
side by side with Algorithm 2 on the same input, in one run of this script,
and for the Cattaneo-Mindlin cases the same history with the tangential
load prescribed as a displacement (Dirichlet conditions hold the sphere:
the Newton method's established fast path).

usage: scripts/bench_held_by_contact.py [--cases two_blocks fretting lap cm_1 cm_2 cm_3]
           [--ranks 2] [--set NAME=VALUE ...] [--tribos build/drivers/tribos]

Cases (input/):
  two_blocks  two_blocks_coulomb.xml: a static solve; friction alone holds
              both blocks along x
  fretting    two_blocks_fretting.xml: its 10-step fretting cycle
  lap         lap_joint.xml: the lap joint's 21-step cycle; the upper plate
              is held by its contact alone
  cm_L        cattaneo_mindlin_traction.xml at mesh Level L (1, 2, 3): the
              21-step Cattaneo-Mindlin cycle with the shear a force;
              reference: cattaneo_mindlin.xml on the same mesh (the shear a
              displacement)

Each row: primal dofs, load steps; Auto: the method of every step, its
applications of F, solve and whole-run wall seconds, the largest KKT
residual over all steps; the same for Algorithm 2; the wall ratio Auto /
Algorithm 2; for cm_L the reference's wall and Auto's wall over it.
docs/semismooth.md ("Bodies held by their contact") holds the table.
"""
import argparse
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from bench_scaling import mpirun, run  # noqa: E402 (one way to run the driver for every benchmark)

KKT = ("equilibrium", "dirichlet", "nonpenetration", "complementarity", "friction_law")
CASES = {
    "two_blocks": ("two_blocks_coulomb.xml", [], None),
    "fretting": ("two_blocks_fretting.xml", [], None),
    "lap": ("lap_joint.xml", [], None),
}
for level in (1, 2, 3):
    mesh = ["Mesh/File=cattaneo_mindlin_%d.msh" % level]
    CASES["cm_%d" % level] = ("cattaneo_mindlin_traction.xml", mesh, "cattaneo_mindlin.xml")


def figures(s, wall):
    """The method(s), n_A, solve and wall seconds, worst KKT residual of a run."""
    rows = s.get("steps") or [s]
    methods = sorted({r.get("outer_algorithm", s["outer_algorithm"]) for r in rows})
    kkt = max(max(r["kkt"][k] for k in KKT) for r in rows)
    if not s["converged"]:
        methods.append("NOT CONVERGED")
    return "+".join(methods), s["n_A_total"], s["time_solve_s"], wall, kkt


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cases", nargs="+", default=["two_blocks", "fretting", "lap", "cm_1", "cm_2"])
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--set", action="append", default=[])
    ap.add_argument("--tribos", default=os.path.join(ROOT, "build", "drivers", "tribos"))
    args = ap.parse_args()
    print("| case | dofs | steps | Auto: method | n_A | solve s | wall s | KKT max | Algorithm 2: n_A | solve s | "
          "wall s | KKT max | wall Auto / Alg. 2 | shear prescribed: wall s | wall Auto / prescribed |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for case in args.cases:
        xml, sets, reference = CASES[case]
        base = mpirun(args.ranks) + [args.tribos, os.path.join(ROOT, "input", xml)]
        for s in sets + args.set:
            base += ["--set", s]
        auto, auto_wall = run(base)
        alg2, alg2_wall = run(base + ["--set", "Solver/Outer Algorithm=Algorithm2"])
        a, b = figures(auto, auto_wall), figures(alg2, alg2_wall)
        row = [case, auto["primal_dofs"], auto["load_steps"], a[0], a[1], "%.1f" % a[2], "%.1f" % a[3], "%.1e" % a[4],
               b[1], "%.1f" % b[2], "%.1f" % b[3], "%.1e" % b[4], "%.2f" % (a[3] / b[3])]
        if reference:
            cmd = mpirun(args.ranks) + [args.tribos, os.path.join(ROOT, "input", reference)]
            for s in sets + args.set:
                cmd += ["--set", s]
            ref, ref_wall = run(cmd)
            row += ["%.1f" % ref_wall, "%.2f" % (a[3] / ref_wall)]
        else:
            row += ["-", "-"]
        print("| " + " | ".join(str(v) for v in row) + " |", flush=True)


if __name__ == "__main__":
    main()
