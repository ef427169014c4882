#!/usr/bin/python3
"""The pressure of a Hertz result node by node against Hertz's profile:

  hertz_pressure.py DIR ... [--max-l2 E] [--max-centre E] [--falling]

For each result directory of input/hertz_sphere.xml (scripts/hertz.py's
analyse gives the force F, Hertz's a and p0 for it, and the nodal pressures
p_i = f_i / A_i, A_i the node's share of the slave facets projected on the
contact plane), prints

  l2      the relative L2 error of p(r) over the contact, node by node,
          sqrt(sum A_i (p_i - p_H(r_i))^2 / sum A_i p_H(r_i)^2) over the
          slave nodes with r_i < a, p_H = p0 sqrt(1 - r^2/a^2);
  l2_surf the relative L2 error of the pressure field, ||p_h - p_H|| /
          ||p_H|| over the whole slave surface projected on z = 0, p_h the
          P1 interpolant of the nodal p_i and p_H zero beyond a (the norm
          of finite element error analysis; both integrals by the midpoints
          of 64 sub-triangles per facet, where p_H's square root is smooth
          enough that 4 times as many change it by 0.01 points on Level 3);
  centre  p_centre / p0 - 1, the node at the contact point;
  spread  the largest |p_i / p_H(r_i) - 1| over the nodes with r_i < a/2
          (where p_H varies by less than 14 %: the scatter of the nodes).

--max-l2 (both L2 errors) and --max-centre fail (exit 1) when the last
directory's figures exceed them; --falling fails unless both L2 errors fall
from each directory to the next (a refinement sequence, coarse first).
"""
import argparse
import math
import os
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
import hertz  # noqa: E402

ap = argparse.ArgumentParser()
ap.add_argument("dirs", nargs="+")
ap.add_argument("--max-l2", type=float)
ap.add_argument("--max-centre", type=float)
ap.add_argument("--falling", action="store_true")
args = ap.parse_args()


def surface_l2(coords, cells, node, p, a, p0, n=8):
    """||p_h - p_H|| / ||p_H|| over the slave facets projected on z = 0; p_h
    interpolates the nodal pressures with the facets' own functions (linear
    on 3-node facets, quadratic on the 6-node facets of Tet10 cells)."""
    facets = hertz.slave_facets(cells, node, len(coords))
    value = np.zeros(len(coords))
    value[node] = p
    P = coords[facets][:, :, :2]
    e1, e2 = P[:, 1] - P[:, 0], P[:, 2] - P[:, 0]
    area = 0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
    second_order = cells.shape[1] == 10
    if second_order:  # each facet's mid-edge nodes on its edges 0-1, 1-2, 2-0
        mid = {}
        for c in cells:
            for k, (i, j) in enumerate(hertz.TET10_EDGES):
                mid[(min(c[i], c[j]), max(c[i], c[j]))] = c[4 + k]
        mids = np.array([[mid[(min(f[i], f[j]), max(f[i], f[j]))] for i, j in ((0, 1), (1, 2), (2, 0))]
                         for f in facets]).reshape(-1, 3)
    # the centroids of the n^2 congruent sub-triangles of the reference triangle
    points = [((i + 1 / 3) / n, (j + 1 / 3) / n) for i in range(n) for j in range(n - i)]
    points += [((i + 2 / 3) / n, (j + 2 / 3) / n) for i in range(n) for j in range(n - i - 1)]
    num = den = 0.0
    for s_, t_ in points:
        lam = np.array([1 - s_ - t_, s_, t_])
        x = np.einsum("k,fkd->fd", lam, P)
        pH = p0 * np.sqrt(np.clip(1 - (np.hypot(x[:, 0], x[:, 1]) / a) ** 2, 0, None))
        if second_order:
            corner = lam * (2 * lam - 1)
            edge = 4 * np.array([lam[0] * lam[1], lam[1] * lam[2], lam[2] * lam[0]])
            ph = value[facets] @ corner + value[mids] @ edge
        else:
            ph = value[facets] @ lam
        num += np.sum(area * (ph - pH) ** 2)
        den += np.sum(area * pH ** 2)
    return math.sqrt(num / den)


print("%-40s %8s %10s %10s %10s %10s" % ("result", "h", "l2", "l2_surf", "centre", "spread"))
errors = []
for d in args.dirs:
    row = hertz.analyse(d)
    with h5py.File(os.path.join(d, "solution.h5"), "r") as f:
        coords = f["mesh/geometry"][...]
        cells = f["mesh/topology"][...].astype(int)
        node = f["points/contact/node"][...].ravel().astype(int)
    A = hertz.nodal_areas(coords, cells, node)
    r, p = np.array(row["r"]), np.array(row["pressure"])
    a, p0 = row["a"], row["p0"]
    inside = r < a
    pH = p0 * np.sqrt(np.clip(1 - (r / a) ** 2, 0, None))
    l2 = math.sqrt(np.sum(A[inside] * (p[inside] - pH[inside]) ** 2) / np.sum(A[inside] * pH[inside] ** 2))
    centre = row["p_centre"] / p0 - 1
    near = r < a / 2
    spread = np.abs(p[near] / pH[near] - 1).max()
    l2_surf = surface_l2(coords, cells, node, p, a, p0)
    print("%-40s %8.4f %9.2f%% %9.2f%% %+9.2f%% %9.2f%%"
          % (d, row["h"], 100 * l2, 100 * l2_surf, 100 * centre, 100 * spread))
    errors.append((l2, l2_surf))
failures = []
if args.max_l2 is not None and max(l2, l2_surf) > args.max_l2:
    failures.append("an L2 error of the last result exceeds %g" % args.max_l2)
if args.max_centre is not None and abs(centre) > args.max_centre:
    failures.append("the centre node of the last result is off by more than %g" % args.max_centre)
if args.falling and any(b[k] >= a[k] for a, b in zip(errors, errors[1:]) for k in (0, 1)):
    failures.append("the L2 errors do not fall from each result to the next")
for f in failures:
    print("hertz_pressure.py: FAILED: " + f)
sys.exit(1 if failures else 0)
