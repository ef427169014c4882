#!/usr/bin/python3
"""Bodies that only their contact holds, solved by the Newton method that
Outer Algorithm = Auto chooses, checked from the driver's files:

  check_newton_held_by_contact.py --work DIR --input TWO_BLOCKS_FRETTING.xml -- MPIEXEC NPFLAG EXTRA... TRIBOS

The two blocks of input/two_blocks_fretting.xml: nothing but friction holds
either block along x (the symmetry plane holds y, the contact z), and the
shear on the upper block goes out, back and out again while the pressure is
held (its first six steps: pressed, sheared out, the reversal and back).
On 1, 2 and 3 ranks:

  - Auto solves every load step by the semismooth Newton method (no step
    handed over to Algorithm 2), and every KKT residual of every written
    step is within the result check;
  - step by step, its displacement and the resultant of each contact pair
    agree with Algorithm 2's (both asked for 1e-9; agreement limit 1e-6 of
    the largest value) and so do its contact counts where no node is near
    the stick/slip boundary;
  - a Newton solve cut short (Maximum Iterations = 2) hands the step over
    to Algorithm 2, which solves it, and the summary says so
    (newton_handover: the first step, the reason, the count; the step's
    row: handover).
"""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_load_history import check, driver_arguments, displacements, failures, pair_forces, relative, run  # noqa: E402

TIGHT = ["Solver/Algorithm 2/Relative Tolerance=1e-9",
         "Load Steps/Times={0.5, 1, 1.5, 2, 2.5, 3}"]  # pressed, sheared out, the reversal and back
ALGORITHM2 = ["Solver/Outer Algorithm=Algorithm2"] + TIGHT
AUTO = ["Solver/Outer Algorithm=Auto"] + TIGHT
KKT = ("equilibrium", "dirichlet", "nonpenetration", "complementarity", "friction_law")


def main():
    args = driver_arguments()

    ref_out, ref, _ = run(args, "algorithm2", 2, ALGORITHM2, input_file=args.input)
    if not ref:
        return
    ref_u, ref_f = displacements(ref_out), pair_forces(ref)
    for np_ in (1, 2, 3):
        out, s, _ = run(args, "auto_np%d" % np_, np_, AUTO, input_file=args.input)
        if not s:
            continue
        rows = s["steps"]
        check(len(rows) == len(ref["steps"]) and all(r["converged"] for r in rows),
              "%d ranks: every step converged (%s)" % (np_, s["stop_reason"]))
        algorithms = sorted({r.get("outer_algorithm") for r in rows})
        check(algorithms == ["Semismooth Newton"] and "newton_handover" not in s,
              "%d ranks: Auto solved every step by the Newton method (%s)" % (np_, algorithms))
        worst = max(max(r["kkt"][k] for k in KKT) for r in rows)
        check(worst <= s["kkt"]["limit"], "%d ranks: every KKT residual %.2e <= %.2e" % (np_, worst, s["kkt"]["limit"]))
        du = max(relative(a, b) for a, b in zip(displacements(out), ref_u))
        df = max(float(np.max(np.abs(a - b)) / np.max(np.abs(b))) for a, b in zip(pair_forces(s), ref_f))
        check(du < 1e-6 and df < 1e-6, "%d ranks: agrees with Algorithm 2 in every step: displacement %.2e, "
              "pair forces %.2e" % (np_, du, df))
        counts = [(r["contact"], q["contact"]) for r, q in zip(rows, ref["steps"])]
        check(all(a == b for a, b in counts), "%d ranks: the contact counts of Algorithm 2 in every step" % np_)

    # The safety net: a Newton solve that stops short is followed by
    # Algorithm 2, and the summary names the step and the reason.
    out, s, _ = run(args, "handover", 2, AUTO + ["Solver/Semismooth Newton/Maximum Iterations=2",
                                                  "Load Steps/Times={0.5, 1}"], input_file=args.input)
    if s:
        h = s.get("newton_handover")
        check(s["converged"] and h is not None and h["first_step"] == 1 and h["steps"] == 2
              and "maximum" in h["reason"].lower() and s["steps"][0].get("handover") == h["reason"]
              and s["steps"][0].get("outer_algorithm") == "Algorithm2",
              "a Newton solve cut short: Algorithm 2 solved the step, the summary says why: %s" % h)


if __name__ == "__main__":
    main()
    print("%d failure(s)" % len(failures))
    sys.exit(1 if failures else 0)
