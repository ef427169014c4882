#!/usr/bin/python3
"""Accuracy per degree of freedom of the four cell types on the seed brick
(docs/quadratic_elements.md, "Accuracy per degree of freedom").

usage: scripts/bench_quadratic.py [--ranks R] [--levels K ...] [--reference K] [--tribos PATH]

Runs input/brick_linear.xml (clamped at x = 0, loaded on its top and free
end; linear elasticity, FETI with the user's defaults) as a box of Tet4 and
Hex8 cells at Mesh/Level 2K and of Tet10 and Hex20 cells at Level K, for
each K: a first-order box at Level 2K has the nodes of the second-order box
at Level K (Tet4 and Tet10 exactly). Prints one table row per run: its
dofs, the largest displacement max |u| (the free end's corner), its
difference from a reference run (Hex20 at Level --reference), and the wall
time of the run.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(tribos, ranks, element, level, tmp):
    out = os.path.join(tmp, "%s_%d" % (element, level))
    cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks), tribos,
           os.path.join(ROOT, "input/brick_linear.xml"), "--quiet", "--output", out,
           "--summary", os.path.join(out, "summary.json"),
           "--set", "Mesh/Element=" + element, "--set", "Mesh/Level=%d" % level]
    t0 = time.monotonic()
    p = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall = time.monotonic() - t0
    if p.returncode != 0:
        sys.exit("bench_quadratic: the run failed (exit %d): %s\n%s" % (p.returncode, " ".join(cmd), p.stderr[-2000:]))
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    if not s["converged"]:
        sys.exit("bench_quadratic: %s at Level %d did not converge" % (element, level))
    return s, wall


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--levels", type=int, nargs="+", default=[1, 2, 4, 8])
    ap.add_argument("--reference", type=int, default=16)
    ap.add_argument("--tribos", default=os.path.join(ROOT, "build/drivers/tribos"))
    args = ap.parse_args()
    if not os.access(args.tribos, os.X_OK):
        sys.exit("bench_quadratic: %s is not built (scripts/build.sh builds it)" % args.tribos)
    with tempfile.TemporaryDirectory() as tmp:
        ref, _ = run(args.tribos, args.ranks, "Hex20", args.reference, tmp)
        u_ref = ref["max_abs_displacement"]
        print("reference: Hex20 at Level %d, %d dofs, max |u| = %.10g" % (args.reference, 3 * ref["nodes"], u_ref))
        print("| element | Level | dofs | max abs u | relative difference | wall s |")
        print("|---|---|---|---|---|---|")
        for element, factor in (("Tet4", 2), ("Tet10", 1), ("Hex8", 2), ("Hex20", 1)):
            for k in args.levels:
                s, wall = run(args.tribos, args.ranks, element, factor * k, tmp)
                u = s["max_abs_displacement"]
                print("| %s | %d | %d | %.6e | %.2e | %.1f |"
                      % (element, factor * k, 3 * s["nodes"], u, abs(u - u_ref) / u_ref, wall), flush=True)


if __name__ == "__main__":
    main()
