#!/usr/bin/python3
"""Subdomain-size benchmark: each geometry of the table run with every
`Mesh/Subdomain Size` of the list (Auto first), everything else at the
input's defaults, one after the other in one run of this script.

usage: scripts/bench_subdomain_size.py [--sizes Auto 4 5 6 8] [--ranks 2]
           [--cases NAME ...] [--repeat 1] [--tribos build/drivers/tribos]

The geometries (meshes that the input files do not ship are made from
their .geo files by gmsh into a temporary directory):

  brick       input/brick_coulomb_F03.xml at Level 16 (a box: a grid of boxes)
  lap_1.7     input/lap_joint.xml, the shipped mesh (h = 1.7 mm, 2335 nodes),
              the whole 21-step fretting history; plates 3 mm thick
  lap_1.25    the same at h = 1.25 mm (4690 nodes)
  lap_1.0     the same at h = 1.0 mm (7683 nodes)
  hertz       input/hertz_sphere.xml (Level 1 mesh), one step
  hertz_2     the same on hertz_sphere.geo's Level 2
  cm_1 .. cm_3  input/cattaneo_mindlin.xml at Levels 1 to 3, its first 5 steps
  two_blocks  input/two_blocks_fretting.xml, two_blocks.geo with 10^3 and
              12^3 hexahedra, the whole history

For every geometry it prints a row: the nodes, and for each size the wall
seconds of the run (the driver's whole run: mesh, setup, every step, no
result files) with its subdomain count and the n_A of all steps, then the
best of the fixed sizes and Auto's wall over it. docs/scaling.md holds the
table and the rule it gave.
"""
import argparse
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from bench_scaling import mpirun, run  # noqa: E402 (one way to run the driver for every benchmark)

STEPS5 = "Load Steps/Times={1, 2, 3, 4, 5}"


def gmsh(geo, out, numbers):
    cmd = ["gmsh", "-3", "-format", "msh4", os.path.join(ROOT, "input", geo), "-o", out]
    for k, v in numbers.items():
        cmd += ["-setnumber", k, str(v)]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return out


def cases(tmp):
    """name -> (input file, --set entries); meshes made on demand."""
    lap = "input/lap_joint.xml"
    return {
        "brick": lambda: ("input/brick_coulomb_F03.xml", ["Mesh/Level=16"]),
        "lap_1.7": lambda: (lap, []),
        "lap_1.25": lambda: (lap, ["Mesh/File=" + gmsh("lap_joint.geo", os.path.join(tmp, "lap_1.25.msh"), {"h": 1.25})]),
        "lap_1.0": lambda: (lap, ["Mesh/File=" + gmsh("lap_joint.geo", os.path.join(tmp, "lap_1.0.msh"), {"h": 1.0})]),
        "hertz": lambda: ("input/hertz_sphere.xml", []),
        "cm_1": lambda: ("input/cattaneo_mindlin.xml", [STEPS5]),
        "cm_2": lambda: ("input/cattaneo_mindlin.xml", ["Mesh/File=cattaneo_mindlin_2.msh", STEPS5]),
        "cm_3": lambda: ("input/cattaneo_mindlin.xml", ["Mesh/File=cattaneo_mindlin_3.msh", STEPS5]),
        "hertz_2": lambda: ("input/hertz_sphere.xml",
                            ["Mesh/File=" + gmsh("hertz_sphere.geo", os.path.join(tmp, "hertz_2.msh"), {"Level": 2})]),
        "two_blocks": lambda: ("input/two_blocks_fretting.xml",
                               ["Mesh/File=" + gmsh("two_blocks.geo", os.path.join(tmp, "two_blocks_10_12.msh"),
                                                    {"nl": 10, "nu": 12})]),
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sizes", nargs="+", default=["Auto", "4", "5", "6", "8"])
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--cases", nargs="+", default=None)
    ap.add_argument("--repeat", type=int, default=1, help="runs per size; the fastest counts")
    ap.add_argument("--set", action="append", default=[], help="extra NAME=VALUE for every run")
    ap.add_argument("--tribos", default=os.path.join(ROOT, "build/drivers/tribos"))
    args = ap.parse_args()
    if not os.access(args.tribos, os.X_OK):
        sys.exit("bench_subdomain_size: %s is not built (scripts/build.sh builds it)" % args.tribos)
    fixed = [s for s in args.sizes if s != "Auto"]
    print("| geometry | nodes | " + " | ".join("%s: wall s (S, n_A)" % s for s in args.sizes) +
          " | best fixed | Auto / best |")
    print("|---" * (len(args.sizes) + 4) + "|")
    with tempfile.TemporaryDirectory() as tmp:
        table = cases(tmp)
        for name in args.cases or list(table):
            if name not in table:
                sys.exit("bench_subdomain_size: no case %r (cases: %s)" % (name, ", ".join(table)))
            xml, sets = table[name]()
            walls, cells, nodes = {}, [], 0
            for size in args.sizes:
                cmd = mpirun(args.ranks) + [args.tribos, os.path.join(ROOT, xml), "--quiet"]
                for s in sets + args.set + ["Mesh/Subdomain Size=" + size]:
                    cmd += ["--set", s]
                best = None
                for _ in range(args.repeat):
                    summary, wall = run(cmd)
                    if not summary.get("converged"):
                        sys.exit("bench_subdomain_size: %s at size %s did not converge" % (name, size))
                    if best is None or wall < best[1]:
                        best = (summary, wall)
                summary, wall = best
                nodes = summary.get("nodes", 0)
                walls[size] = wall
                cells.append("%.1f (%d, %d)" % (wall, summary["subdomains"],
                                                summary.get("n_A_total", summary["n_A"])))
            bestFixed = min(fixed, key=lambda s: walls[s]) if fixed else None
            ratio = "%.2f" % (walls["Auto"] / walls[bestFixed]) if bestFixed and "Auto" in walls else "-"
            print("| %s | %d | %s | %s | %s |" % (name, nodes, " | ".join(cells), bestFixed or "-", ratio),
                  flush=True)


if __name__ == "__main__":
    main()
