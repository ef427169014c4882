#!/usr/bin/python3
"""The coarse level of the MueLu hierarchies, checked from the driver's files:

  check_coarse_level.py --work DIR --linear BRICK_LINEAR.xml --prism PRISM.xml -- MPIEXEC NPFLAG EXTRA... TRIBOS

The coarsest level is factored on one rank whatever the number of ranks
(MueLu moves it there first), so a preconditioned CG takes the same steps on
1, 2 and 3 ranks; a coarse level smoothed on several ranks took about twice
the steps (27 against 14 on the prism's linear solve at level 8).

  - The linear brick (level 8, 2793 dofs and more: a hierarchy of two
    levels), monolithic CG + MueLu, on 1, 2 and 3 ranks: the same
    displacement to 1e-8 of its largest value, and at most one CG step more
    on 2 or 3 ranks than on one.
  - The semismooth* prism (level 5, CG+MueLu Newton steps, 12 168 dofs) on 1
    and 2 ranks: the same displacement to 1e-6, and at most a tenth more
    CG steps (Newton steps and equilibrium corrections) on 2 ranks.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_load_history import check, displacements, failures, relative, run  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--work", required=True)
    ap.add_argument("--linear", required=True)
    ap.add_argument("--prism", required=True)
    ap.add_argument("launcher", nargs="+")
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)

    linear = {}
    for np_ in (1, 2, 3):
        out, s, _ = run(args, "linear_np%d" % np_, np_, ["Mesh/Level=8", "Solver/Type=Monolithic"],
                        input_file=args.linear)
        if s:
            linear[np_] = (displacements(out)[0], s["steps"][0]["iterations"])
    if 1 in linear:
        u1, it1 = linear[1]
        for np_ in (2, 3):
            if np_ in linear:
                u, it = linear[np_]
                check(relative(u, u1) < 1e-8, "linear, %d ranks: the displacement of one rank (%.2e)" % (np_, relative(u, u1)))
                check(it <= it1 + 1, "linear, %d ranks: %d CG steps against %d on one rank" % (np_, it, it1))

    prism = {}
    for np_ in (1, 2):
        out, s, _ = run(args, "prism_np%d" % np_, np_, ["Mesh/Level=5", "Solver/SemismoothStarNewton/Newton Solver=CG+MueLu"],
                        input_file=args.prism)
        if s:
            check(s["converged"], "prism, %d rank(s): converged, KKT %s" % (np_, s["kkt"]))
            prism[np_] = (displacements(out)[0], s["cg_iterations"])
    if 1 in prism and 2 in prism:
        (u1, cg1), (u2, cg2) = prism[1], prism[2]
        check(relative(u2, u1) < 1e-6, "prism, 2 ranks: the displacement of one rank (%.2e)" % relative(u2, u1))
        check(cg2 <= 1.1 * cg1, "prism, 2 ranks: %d CG steps against %d on one rank" % (cg2, cg1))


if __name__ == "__main__":
    main()
    print("%d failure(s)" % len(failures))
    sys.exit(1 if failures else 0)
