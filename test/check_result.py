#!/usr/bin/python3
"""Runs the tribos driver on a contact problem with an exact solution and
checks the written result (HDF5) against it, independently of the solver:

  check_result.py --out DIR [options] -- COMMAND ...

--exact UX UY UZ     exact displacement, Python expressions in x, y, z
--utol T             max |u - exact| <= T max |exact|            (default 1e-5)
--contact-nodes N    number of contact nodes written
--status S           every contact node has status S (1 stick, 2 slip)
--active-only        --status and --ratio look at the nodes in contact only
--ratio R            |t_T| / t_N = R at every contact node        (abs 1e-4)
--total-normal P     sum of the normal forces = P                 (rel 1e-5)
--coulomb F          the friction law is Coulomb with coefficient F
--gap D              the initial gap against the rigid plane (face zmin, plane
                     z = -D below it); contacts between bodies take theirs
                     from the written master nodes and weights
--exit E             expected exit code (default 0; 2 = not converged)
--same-as DIR        the displacement equals that of the result in DIR
--same-tol T         ... to T max |u| (default 1e-5)

The KKT figures non-penetration, complementarity and friction law are
recomputed from the HDF5 file alone (with the summary's force and
displacement scales) and must agree with the summary's. A result without
contact (a linear problem) gets the checks of the displacement only.
"""
import argparse
import json
import subprocess
import sys

import h5py
import numpy as np

sep = sys.argv.index("--")
ap = argparse.ArgumentParser()
ap.add_argument("--out", required=True)
ap.add_argument("--exact", nargs=3)
ap.add_argument("--utol", type=float, default=1e-5)
ap.add_argument("--contact-nodes", type=int)
ap.add_argument("--status", type=int)
ap.add_argument("--active-only", action="store_true")
ap.add_argument("--ratio", type=float)
ap.add_argument("--total-normal", type=float)
ap.add_argument("--coulomb", type=float, default=0.0)
ap.add_argument("--gap", type=float, default=0.0)
ap.add_argument("--exit", type=int, default=0)
ap.add_argument("--same-as")
ap.add_argument("--same-tol", type=float, default=1e-5)
a = ap.parse_args(sys.argv[1:sep])
cmd = sys.argv[sep + 1:]

failed = []


def check(cond, what):
    print(("ok: " if cond else "FAILED: ") + what)
    if not cond:
        failed.append(what)


rc = subprocess.run(cmd).returncode
check(rc == a.exit, f"exit code {rc} == {a.exit}")
with open(f"{a.out}/summary.json") as f:
    s = json.load(f)
check(s["converged"] == (a.exit == 0), f"converged = {s['converged']}")
h = h5py.File(f"{a.out}/solution.h5", "r")
X = h["mesh/geometry"][:]
U = h["nodes/displacement"][:]
has_contact = "points/contact" in h
if has_contact:
    c = h["points/contact"]
    lamN = c["normal_force"][:].ravel()
    phiT = c["tangential_force"][:]
    status = c["status"][:].ravel()
    Xc = c["geometry"][:]

if a.exact:
    x, y, z = X[:, 0], X[:, 1], X[:, 2]
    ex = np.column_stack([np.broadcast_to(eval(e, {"np": np}, {"x": x, "y": y, "z": z}), x.shape) for e in a.exact])
    err = np.abs(U - ex).max() / np.abs(ex).max()
    check(err <= a.utol, f"max |u - exact| / max |exact| = {err:.3g} <= {a.utol}")
if a.same_as:
    # Node by node at the same position (the reference may be another mesh
    # of the same nodes, e.g. one body where this result has two).
    ref = h5py.File(f"{a.same_as}/solution.h5", "r")
    V, Y = ref["nodes/displacement"][:], ref["mesh/geometry"][:]
    # Bodies may touch: a node is its position and its body (the cells'
    # "body" field; the reference may have one body where this has two).
    def node_bodies(f, n):
        b = np.zeros(n, dtype=int)
        if "cells/body" in f:
            b[f["mesh/topology"][:].astype(int)] = f["cells/body"][:].astype(int)
        return b
    key = lambda p, b: tuple(np.round(p, 10)) + (b,)
    bodies, bodies_ref = node_bodies(h, len(X)), node_bodies(ref, len(Y))
    if bodies.max(initial=0) == 0 or bodies_ref.max(initial=0) == 0:
        bodies[:], bodies_ref[:] = 0, 0  # one body on either side: positions alone
    at = {}
    for i, p in enumerate(Y):
        at.setdefault(key(p, bodies_ref[i]), []).append(i)
    check(all(len(v) == 1 for v in at.values()), "the reference's nodes are at distinct positions in each body")
    match = [at.get(key(p, bodies[i]), [-1])[0] for i, p in enumerate(X)]
    check(min(match) >= 0, "every node has a node of the reference at its position")
    diff = np.abs(U - V[match]).max() / np.abs(V).max()
    check(diff <= a.same_tol, f"max |u - u_ref| / max |u_ref| = {diff:.3g} <= {a.same_tol}")
if not has_contact:
    check(a.contact_nodes is None and a.status is None and a.ratio is None and a.total_normal is None,
          "no contact checks asked of a result without contact")
    sys.exit(1 if failed else 0)
if a.contact_nodes is not None:
    check(len(lamN) == a.contact_nodes, f"{len(lamN)} contact nodes == {a.contact_nodes}")
sel = status > 0 if a.active_only else np.ones(len(status), dtype=bool)
if a.active_only:
    check(sel.any(), f"{sel.sum()} of {len(sel)} contact nodes in contact")
if a.status is not None:
    check(np.all(status[sel] == a.status), f"every contact node has status {a.status} (got {sorted(set(status[sel].tolist()))})")
if a.ratio is not None:
    r = np.linalg.norm(phiT[sel], axis=1) / lamN[sel]
    check(np.abs(r - a.ratio).max() <= 1e-4, f"|t_T| / t_N = {a.ratio} at every node (max dev {np.abs(r - a.ratio).max():.3g})")
if a.total_normal is not None:
    t = lamN.sum()
    check(abs(t - a.total_normal) <= 1e-5 * abs(a.total_normal), f"total normal force {t:.8g} == {a.total_normal}")

# KKT of the written result from the file alone. Each contact node s (its
# row in /nodes: the field "node", else looked up by position) meets its
# partner: master nodes i with weights N_i ("master_node", "master_weight"),
# or none for the rigid plane. w = u_s - sum N_i u_i, normal n: the written
# one, which must be (0, 0, -1) against the plane z = -gap (--gap); the
# initial gap d is the geometric one, (x_p - x_s).n with x_p = sum N_i x_i.
# On a second-order slave surface a mid-edge node's row acts on its value in
# mortar's transformed basis, sum S_b u_b over the nodes "slave_node" with
# the weights "slave_weight" (x_s likewise), where the file lists them.
k = s["kkt"]
Usc, Psc = max(k["displacement_scale"], 1e-300), max(k["force_scale"], 1e-300)
if "node" in c:
    rows = c["node"][:].ravel().astype(int)
else:
    index = {tuple(np.round(p, 12)): i for i, p in enumerate(X)}
    rows = np.array([index[tuple(np.round(p, 12))] for p in Xc], dtype=int)
n_c = len(rows)
normal = c["normal"][:] if "normal" in c else np.tile([0.0, 0.0, -1.0], (n_c, 1))
mnode = c["master_node"][:].astype(int) if "master_node" in c else -np.ones((n_c, 4), dtype=int)
mweight = c["master_weight"][:] if "master_weight" in c else np.zeros((n_c, 4))
snode = c["slave_node"][:].astype(int) if "slave_node" in c else -np.ones((n_c, 1), dtype=int)
sweight = c["slave_weight"][:] if "slave_weight" in c else np.zeros((n_c, 1))
W = U[rows].copy()
Xs = X[rows].copy()
for j in np.flatnonzero((snode >= 0).any(axis=1)):
    on = snode[j] >= 0
    W[j] = (sweight[j][on, None] * U[snode[j][on]]).sum(axis=0)
    Xs[j] = (sweight[j][on, None] * X[snode[j][on]]).sum(axis=0)
check(np.abs(sweight.sum(axis=1)[(snode >= 0).any(axis=1)] - 1).max(initial=0) <= 1e-12, "slave weights sum to 1")
d = np.full(n_c, a.gap)
for j in range(n_c):
    has = mnode[j] >= 0
    if not has.any():
        check_plane = np.abs(normal[j] - [0, 0, -1]).max() <= 1e-12
        if not check_plane:
            check(False, f"contact node {rows[j]}: a rigid-plane contact with normal {normal[j]} (the check knows z = -gap only)")
        continue
    W[j] -= (mweight[j][has, None] * U[mnode[j][has]]).sum(axis=0)
    xp = (mweight[j][has, None] * X[mnode[j][has]]).sum(axis=0)
    d[j] = (xp - Xs[j]) @ normal[j]
check(np.abs(mweight.sum(axis=1)[(mnode >= 0).any(axis=1)] - 1).max(initial=0) <= 1e-12, "master weights sum to 1")
wn = (W * normal).sum(axis=1)
gap_left = d - wn
pen = max(np.maximum(-gap_left, 0).max(initial=0), 0) / Usc
comp = np.abs(np.minimum(lamN / Psc, gap_left / Usc)).max(initial=0)
slip = W - wn[:, None] * normal
# A tangential axis that a Dirichlet condition fixes at the slave node (a
# symmetry plane) carries no friction row and is left out, as the summary's
# check does (docs/friction.md); the file shows it as a coordinate axis in
# the tangent plane along which the friction force is zero to the last bit
# (no row; a row's force is never exactly zero where the node moves).
held = (phiT == 0.0) & (np.abs(normal) <= 1e-12)
slip = np.where(held, 0.0, slip)
g = a.coulomb * np.maximum(lamN, 0)
trial = phiT - (Psc / Usc) * slip
nt = np.linalg.norm(trial, axis=1)
proj = trial * np.minimum(1, g / np.maximum(nt, 1e-300))[:, None]
fric = (np.linalg.norm(phiT - proj, axis=1) / Psc).max(initial=0)
for name, mine in [("nonpenetration", pen), ("complementarity", comp), ("friction_law", fric)]:
    check(abs(mine - k[name]) <= 1e-8 + 1e-3 * k[name], f"kkt {name}: file {mine:.4g} == summary {k[name]:.4g}")
    if a.exit == 0:
        check(k[name] <= k["limit"], f"kkt {name} {k[name]:.3g} <= limit {k['limit']:.3g}")
sys.exit(1 if failed else 0)
