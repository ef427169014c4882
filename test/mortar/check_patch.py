#!/usr/bin/python3
"""The contact patch test read node by node from a result file:

  check_patch.py --out DIR --pressure P [--tol T] -- CHECK_RESULT_ARGS ...

runs test/check_result.py with CHECK_RESULT_ARGS (the run, the exact
displacement, the KKT figures from the file), then checks that every contact
node carries the uniform pressure P: its normal force divided by its area
int N_s dA (over the contact facets around it: the boundary faces of its
body's cells whose nodes are all contact nodes) equals P to T relative
(default 1e-8). Contact nodes are those of every pair, on the rigid plane
as between the bodies.

On second-order cells (Tet10, Hex20; flat facets; bodies may differ in
order, the topology then XDMF's Mixed list) the area is that of
mortar's transformed basis, int N~_s dA with a fifth of each mid-edge
function moved to its edge's corners: 2A/15 at a 6-node triangle's corners
and A/5 at its mid-edge nodes, A/20 and A/5 on an 8-node parallelogram.
The written normal_traction must carry P too.
"""
import argparse
import os
import subprocess
import sys

import h5py
import numpy as np

sep = sys.argv.index("--")
ap = argparse.ArgumentParser()
ap.add_argument("--out", required=True)
ap.add_argument("--pressure", type=float, required=True)
ap.add_argument("--tol", type=float, default=1e-8)
a = ap.parse_args(sys.argv[1:sep])
here = os.path.dirname(os.path.abspath(__file__))
rc = subprocess.run([sys.executable, os.path.join(here, "..", "check_result.py")] + sys.argv[sep + 1:]).returncode
failed = rc != 0

HEX_FACES = [(0, 1, 2, 3), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
TET_FACES = [(0, 1, 2), (0, 1, 3), (1, 2, 3), (0, 2, 3)]
# The mid-edge nodes of the written second-order cells (VTK's order).
TET10_EDGES = [(0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3)]
HEX20_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
G = 1 / np.sqrt(3)
# The nodes of each cell type of XDMF's Mixed topology (a mesh whose bodies
# differ in cell type): Tet4, Hex8, Tet10, Hex20.
XDMF_MIXED_NODES = {6: 4, 9: 8, 38: 10, 48: 20}


def cells_of(h):
    """The node lists of the written cells: the rows of /mesh/topology, or
    its Mixed list (each cell's type number, then its nodes)."""
    T = h["mesh/topology"][:].astype(int)
    if T.shape[1] > 1:
        return list(T)
    flat, cells, i = T.ravel(), [], 0
    while i < len(flat):
        n = XDMF_MIXED_NODES[flat[i]]
        cells.append(flat[i + 1:i + 1 + n])
        i += 1 + n
    return cells


def cell_shape(cell):
    """Corners, faces, mid-edge edges (empty for first order) of a cell."""
    corners = 8 if len(cell) in (8, 20) else 4
    edges = (HEX20_EDGES if corners == 8 else TET10_EDGES) if len(cell) > corners else []
    return corners, HEX_FACES if corners == 8 else TET_FACES, edges


def nodal_areas(P):
    """int N_a dA of each node of a facet (triangle: area / 3; bilinear
    quadrilateral: 2 x 2 Gauss, exact for a planar one)."""
    if len(P) == 3:
        return np.full(3, 0.5 * np.linalg.norm(np.cross(P[1] - P[0], P[2] - P[0])) / 3)
    s = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]], dtype=float)
    w = np.zeros(4)
    for xi, eta in s * G:
        N = (1 + s[:, 0] * xi) * (1 + s[:, 1] * eta) / 4
        dxi = (s[:, 0] * (1 + s[:, 1] * eta) / 4) @ P
        deta = (s[:, 1] * (1 + s[:, 0] * xi) / 4) @ P
        w += N * np.linalg.norm(np.cross(dxi, deta))
    return w


h = h5py.File(f"{a.out}/solution.h5", "r")
X = h["mesh/geometry"][:]
T = cells_of(h)
body = h["cells/body"][:].astype(int).ravel() if "cells/body" in h else np.zeros(len(T), dtype=int)
c = h["points/contact"]
rows = c["node"][:].astype(int).ravel()
force = c["normal_force"][:].ravel()
# The contact facets: faces of a body's cells that no other cell of the body
# shares (boundary faces) and whose nodes are all contact nodes.
contact = set(rows.tolist())
seen = {}
mids = {}  # a facet's corners -> the mid-edge nodes of its edges
for cell, b in zip(T, body):
    corners, faces, edges = cell_shape(cell)
    mid = {frozenset((cell[i], cell[j])): cell[corners + k] for k, (i, j) in enumerate(edges)}
    for f in faces:
        nodes = cell[list(f)]
        if contact.issuperset(nodes.tolist()):
            key = (b, tuple(sorted(nodes.tolist())))
            seen[key] = None if key in seen else nodes
            if mid:
                mids[key] = [mid[frozenset((nodes[i], nodes[(i + 1) % len(nodes)]))] for i in range(len(nodes))]
area = {}
for key, nodes in seen.items():
    if nodes is None:
        continue
    b = key[0]
    w = nodal_areas(X[nodes])
    if key in mids:
        A = w.sum()  # flat facet: its area
        share = (2 / 15, 1 / 5) if len(nodes) == 3 else (1 / 20, 1 / 5)
        w = np.full(len(nodes), share[0] * A)
        for n in mids[key]:
            area[(n, b)] = area.get((n, b), 0.0) + share[1] * A
    for n, wn in zip(nodes, w):
        area[(n, b)] = area.get((n, b), 0.0) + wn
node_body = {}
for cell, b in zip(T, body):
    for n in cell:
        node_body[n] = b
p = np.array([force[j] / area[(n, node_body[n])] for j, n in enumerate(rows)])
err = np.abs(p - a.pressure).max() / abs(a.pressure)
ok = err <= a.tol
print(("ok: " if ok else "FAILED: ") + f"{len(p)} contact nodes carry the pressure {a.pressure:g}: "
      f"max |p_s - p| / p = {err:.3g} <= {a.tol}")
written = c["normal_traction"][:].ravel()
err_t = np.abs(written - a.pressure).max() / abs(a.pressure)
ok_t = err_t <= a.tol
print(("ok: " if ok_t else "FAILED: ") + f"the written normal_traction: max |t_s - p| / p = {err_t:.3g} <= {a.tol}")
sys.exit(1 if failed or not ok or not ok_t else 0)
