#!/usr/bin/python3
"""The matrix-free semismooth Newton method on the FETI dual, checked from the
driver's files:

  check_newton_matrix_free.py --work DIR --input BRICK.xml -- MPIEXEC NPFLAG EXTRA... TRIBOS

On the seed Coulomb brick (level 4, F = 0.3, a dual small enough for the
dense variant too), on 1, 2 and 3 ranks:

  - Semismooth Newton with Linear Solver = Projected CG (the Newton systems
    by CG through applications of F, never formed) converges, every KKT
    residual of the written result within the result check, and its
    displacement and contact forces agree with those of the dense variant
    (Linear Solver = Dense LU) and of Algorithm 2, both solved tightly;
  - with each preconditioner (Auto, the default: Slip Curvature with the
    augmented Lagrangian, FETI's Lumped with the face projection; each of
    Slip Curvature, None, Lumped and Dirichlet) and each way of holding
    G x = 0 (Augmented Lagrangian, the default here; Face Projection) it
    reaches the same solution;
  - with the coarse problem split among 2 and 3 ranks (192 subdomains) it
    reaches the same solution;
  - at F = 0.6, where Newton steps that lag the slip bound cycle, the
    steps with the slip bounds frozen reach Algorithm 2's solution;
  - the load history of test/check_load_history.py (pressed, sheared out,
    back, out the other way) solved by it agrees step by step with
    Algorithm 2's.
The agreement limit 1e-6 is relative to the largest nodal value; the
solvers are asked for 1e-10 (Newton) and 1e-9 (Algorithm 2).
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_load_history import HISTORY, check, driver_arguments, displacements, failures, pair_forces, relative, run  # noqa: E402

NEWTON = ["Solver/Outer Algorithm=Semismooth Newton", "Solver/Semismooth Newton/Relative Tolerance=1e-10"]
MATRIX_FREE = NEWTON + ["Solver/Semismooth Newton/Linear Solver=Projected CG"]
DENSE = NEWTON + ["Solver/Semismooth Newton/Linear Solver=Dense LU"]
ALGORITHM2 = ["Solver/Outer Algorithm=Algorithm2", "Solver/Algorithm 2/Relative Tolerance=1e-9"]
LEVEL = ["Mesh/Level=4"]


def main():
    args = driver_arguments()

    ref_out, ref, _ = run(args, "algorithm2", 2, LEVEL + ALGORITHM2)
    dense_out, dense, _ = run(args, "dense", 2, LEVEL + DENSE)
    if not (ref and dense):
        return
    ref_u = displacements(ref_out)[0]
    check(relative(displacements(dense_out)[0], ref_u) < 1e-6, "the dense Newton agrees with Algorithm 2")
    for np_ in (1, 2, 3):
        out, s, _ = run(args, "matrix_free_np%d" % np_, np_, LEVEL + MATRIX_FREE)
        if not s:
            continue
        check(s["converged"], "%d ranks: converged (%s), KKT %s" % (np_, s["stop_reason"], s["kkt"]))
        u = displacements(out)[0]
        check(relative(u, ref_u) < 1e-6 and relative(u, displacements(dense_out)[0]) < 1e-6,
              "%d ranks: the matrix-free Newton agrees with Algorithm 2 (%.2e) and the dense Newton (%.2e)"
              % (np_, relative(u, ref_u), relative(u, displacements(dense_out)[0])))
        check(s["contact"] == dense["contact"], "%d ranks: the contact counts of the dense Newton: %s against %s"
              % (np_, s["contact"], dense["contact"]))
    # The coarse problem split among the ranks (FETI/Coarse Problem = Split,
    # docs/feti.md): 192 subdomains of one cube, so that every rank holds a
    # part of GG' besides the separator; the solution of Algorithm 2 on the
    # input's 3 subdomains.
    for np_ in (2, 3):
        out, s, _ = run(args, "split_coarse_np%d" % np_, np_,
                        LEVEL + MATRIX_FREE + ["Mesh/Subdomain Size=1", "Solver/FETI/Coarse Problem=Split"])
        if s:
            check(s["converged"] and relative(displacements(out)[0], ref_u) < 1e-6,
                  "%d ranks, the coarse problem split (%d subdomains): converged to the same solution (%.2e)"
                  % (np_, s["subdomains"], relative(displacements(out)[0], ref_u)))
    for equality in ("Face Projection", "Augmented Lagrangian"):
        for pc in ("Slip Curvature", "None", "Lumped", "Dirichlet"):
            if equality == "Augmented Lagrangian" and pc == "Slip Curvature":
                continue  # the default: run above
            name = "matrix_free_%s_%s" % (equality.split()[0], pc.replace(" ", ""))
            out, s, _ = run(args, name, 2, LEVEL + MATRIX_FREE + ["Solver/Semismooth Newton/Preconditioner=" + pc,
                                                                  "Solver/Semismooth Newton/Equality Constraint=" + equality])
            if s:
                check(s["converged"] and relative(displacements(out)[0], ref_u) < 1e-6,
                      "%s, Preconditioner %s: converged to the same solution (%.2e)"
                      % (equality, pc, relative(displacements(out)[0], ref_u)))

    # High friction (F = 0.6, Auto's subdomains of 4 cells): the Newton steps,
    # which lag the slip bound, cycle between two points there (a contact
    # changing state back and forth) and stalled after 30 steps; with the
    # slip bounds frozen once the measure stops halving (Slip Bound Freeze
    # Steps) they converge to Algorithm 2's solution, on 1 and 2 ranks.
    high = LEVEL + ["Contact/Friction Coefficient=0.6", "Mesh/Subdomain Size=Auto"]
    hf_out, hf, _ = run(args, "high_friction_algorithm2", 2, high + ALGORITHM2)
    for np_ in (1, 2) if hf else ():
        out, s, _ = run(args, "high_friction_np%d" % np_, np_, high + MATRIX_FREE)
        if s:
            d = relative(displacements(out)[0], displacements(hf_out)[0])
            check(s["converged"] and s["outer_algorithm"] == "Semismooth Newton" and d < 1e-6,
                  "%d ranks, F = 0.6: the Newton method converged (%s) to Algorithm 2's solution (%.2e)"
                  % (np_, s["stop_reason"], d))

    # The load history, step by step against Algorithm 2's.
    href_out, href, _ = run(args, "history_algorithm2", 2, LEVEL + HISTORY + ALGORITHM2)
    hout, hs, _ = run(args, "history_matrix_free", 2, LEVEL + HISTORY + MATRIX_FREE)
    if href and hs:
        check(all(r["converged"] for r in hs["steps"]) and len(hs["steps"]) == 4, "history: every step converged")
        du = max(relative(a, b) for a, b in zip(displacements(hout), displacements(href_out)))
        df = max(float(np.max(np.abs(a - b)) / np.max(np.abs(b))) for a, b in zip(pair_forces(hs), pair_forces(href)))
        check(du < 1e-6 and df < 1e-6, "history: agrees with Algorithm 2 in every step: displacement %.2e, forces %.2e"
              % (du, df))


if __name__ == "__main__":
    main()
    print("%d failure(s)" % len(failures))
    sys.exit(1 if failures else 0)
