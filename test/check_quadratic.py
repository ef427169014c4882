#!/usr/bin/python3
"""Runs the tribos driver on the patch test of second-order cells
(test/data/quadratic/block_patch.xml) and checks its result file alone:

  check_quadratic.py --out DIR --cell Tetrahedron_10|Hexahedron_20 [--q Q] [--curved] -- COMMAND ...

- exit 0 and converged; run with --verify, FETI's displacement is the
  monolithic solve's to 1e-8;
- every node's displacement is the exact one of the uniform stress
  sxx = q, szz = p (E, nu, p as in block_patch.xml, q its value or --q) to
  1e-8 of max |u|;
- every cell's stress (the cell field "stress", as written: xx xy xz yy yz zz) is
  that stress to 1e-8 of p;
- the XDMF index names the topology --cell, and the topology lists each
  cell's nodes in VTK's order: on these straight-sided meshes every
  mid-edge node is the midpoint of the edge VTK places it on (Gmsh's order
  would put Tet10's nodes 8 and 9, and most of Hex20's, on other edges);
  with --curved (mid-edge nodes on a curved boundary) within a quarter of
  the edge's length of that midpoint.
"""
import argparse
import json
import subprocess
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np

E, nu, p = 1e9, 0.3, 1e7
# VTK's quadratic cells: the mid-edge node k lies on edge EDGES[k - corners].
EDGES = {
    "Tetrahedron_10": (4, [(0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3)]),
    "Hexahedron_20": (8, [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
                          (0, 4), (1, 5), (2, 6), (3, 7)]),
}

sep = sys.argv.index("--")
ap = argparse.ArgumentParser()
ap.add_argument("--out", required=True)
ap.add_argument("--cell", required=True, choices=sorted(EDGES))
ap.add_argument("--q", type=float, default=4e6, help="the traction along x on side_x")
ap.add_argument("--curved", action="store_true")
a = ap.parse_args(sys.argv[1:sep])
q = a.q
failed = []


def check(cond, what):
    print(("ok: " if cond else "FAILED: ") + what)
    if not cond:
        failed.append(what)


rc = subprocess.run(sys.argv[sep + 1:]).returncode
check(rc == 0, f"exit code {rc} == 0")
if rc == 0:
    with open(f"{a.out}/summary.json") as f:
        summary = json.load(f)
    check(summary["converged"], "converged")
    if "verify_rel_diff_u" in summary:  # run with --verify: FETI against the monolithic solve
        check(summary["verify_rel_diff_u"] < 1e-8, f"FETI against monolithic: {summary['verify_rel_diff_u']:.3g} < 1e-8")
    topo = ET.parse(f"{a.out}/solution.xmf").getroot().find(".//Grid[@Name='body']/Topology")
    check(topo.get("TopologyType") == a.cell, f"topology {topo.get('TopologyType')} == {a.cell}")
    with h5py.File(f"{a.out}/solution.h5", "r") as h:
        X = h["mesh/geometry"][:]
        T = h["mesh/topology"][:].astype(int)
        U = h["nodes/displacement"][:]
        S = h["cells/stress"][:]
    x, y, z = X[:, 0], X[:, 1], X[:, 2]
    exact = np.column_stack([(q - nu * p) * x, -nu * (p + q) * y, (p - nu * q) * z]) / E
    err = np.abs(U - exact).max() / np.abs(exact).max()
    check(err < 1e-8, f"max |u - exact| / max |exact| = {err:.3g} < 1e-8 ({len(X)} nodes)")
    serr = np.abs(S - np.array([q, 0, 0, 0, 0, p])).max() / p
    check(serr < 1e-8, f"max |stress - exact| / p = {serr:.3g} < 1e-8 ({len(T)} cells)")
    corners, edges = EDGES[a.cell]
    check(T.shape[1] == corners + len(edges), f"{T.shape[1]} nodes per cell")
    worst = 0.0  # offset from the VTK edge's midpoint: absolute, or relative to the edge (--curved)
    for k, (i, j) in enumerate(edges):
        mid = 0.5 * (X[T[:, i]] + X[T[:, j]])
        offset = np.linalg.norm(X[T[:, corners + k]] - mid, axis=1)
        if a.curved:
            offset /= np.linalg.norm(X[T[:, i]] - X[T[:, j]], axis=1)
        worst = max(worst, offset.max())
    limit = 0.25 if a.curved else 1e-12
    check(worst < limit, f"every mid-edge node at the midpoint of its VTK edge (worst offset {worst:.3g} < {limit})")
print("quadratic checks", "FAILED: " + "; ".join(failed) if failed else "passed")
sys.exit(1 if failed else 0)
