#!/usr/bin/python3
"""The automatic search distance (Contact/Pairs/NAME/Search Distance = 0)
and the check of the nodes it leaves out, from the driver's files:

  check_search_distance.py --work DIR --input TILTED_PLANE.xml -- MPIEXEC NPFLAG EXTRA... TRIBOS

test/data/search_distance/tilted_plane.xml: the brick bends onto a rigid
plane tilted towards its free end; Auto leaves out the bottom nodes nearer
the clamp (gap above 5 % of the face's diagonal). On 1, 2 and 3 ranks:

  - the run converges with nodes left out and some in contact, and its
    displacement is that of the run where every node takes a row
    (Search Distance = 1e300) to 1e-6 of the largest value, with the same
    contact nodes active;
  - the plane tilted the other way and the brick softened 1000-fold, the
    brick bends through the plane where no node takes a row: the run is not
    converged (exit 2), and its reason names the pair, a left-out node and
    the parameter to set; with every node taking part it converges.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_load_history import check, driver_arguments, displacements, failures, relative, run  # noqa: E402

TIGHT = ["Solver/Algorithm 1/SMALBE/Relative Tolerance=1e-10"]
EVERY_NODE = ["Contact/Pairs/ground/Search Distance=1e300"]
THROUGH = ["Contact/Pairs/ground/Plane Point={0, 0, 0}", "Contact/Pairs/ground/Plane Normal={0.1, 0, 1}",
           "Material/Young's Modulus=21.2e7"]


def main():
    args = driver_arguments()

    ref_out, ref, _ = run(args, "every_node", 2, EVERY_NODE + TIGHT, input_file=args.input)
    for np_ in (1, 2, 3):
        out, s, _ = run(args, "auto_np%d" % np_, np_, TIGHT, input_file=args.input)
        if not (s and ref):
            continue
        search = s["contact_search"][0]
        check(s["converged"] and search["automatic"] and search["left_out"] > 0 and s["contact"]["active"] > 0,
              "%d ranks: converged with %d of %d nodes left out, %d in contact"
              % (np_, search["left_out"], search["slave_nodes"], s["contact"]["active"]))
        d = relative(displacements(out)[0], displacements(ref_out)[0])
        check(d < 1e-6 and s["contact"]["active"] == ref["contact"]["active"],
              "%d ranks: the displacement of every node taking part (%.2e), the same %d contacts" % (np_, d, s["contact"]["active"]))
    for np_ in (1, 2):
        _, s, _ = run(args, "through_np%d" % np_, np_, THROUGH, expect=2, input_file=args.input)
        if s:
            reason = s["stop_reason"]
            check(not s["converged"] and "'ground'" in reason and "slave node" in reason and "Search Distance" in reason,
                  "%d ranks: bent through the plane where nodes were left out: not converged: %s" % (np_, reason))
    _, s, _ = run(args, "through_every_node", 2, THROUGH + EVERY_NODE, input_file=args.input)
    if s:
        check(s["converged"], "every node taking part, the same bending converges (%s)" % s["stop_reason"])


if __name__ == "__main__":
    main()
    print("%d failure(s)" % len(failures))
    sys.exit(1 if failures else 0)
