#!/usr/bin/python3
"""Hertz impact through the driver (input/hertz_impact.xml, docs/dynamics.md):

  check_hertz_impact.py --out DIR [--copies N] [--tol-duration T] [--tol-force T]
                        [--tol-penetration T] -- MPIEXEC ... TRIBOS INPUT ...

runs the command (or, with no command after --, reads DIR as it is), then
reads the steps table (BASE.steps.jsonl) and the step files, and compares
the impact of the elastic ball on the rigid plane z = 0 with Hertz's
quasi-static solution: with E* = E / (1 - nu^2), m the mass of the whole
ball and v0 its initial speed,

  delta_max = (15 m v0^2 / (16 E* sqrt(R)))^(2/5),
  F_max     = (4/3) E* sqrt(R) delta_max^(3/2),
  t_c       = 2.87 (m^2 / (R E*^2 v0))^(1/5).

The model is the part of the ball that the mesh holds, 1 / --copies of it
(4: the quarter of the symmetry planes x = 0 and y = 0): its mass is rho
times the volume of the mesh's tetrahedra, and m and the contact force of
the whole ball are --copies times the model's. R is half the mesh's height,
E, nu, rho, v0 and dt are read from the run's parameters file
(BASE.parameters.xml).

Checked: exit 0 and every step converged; the contact lasted t_c (within
--tol-duration; counted in whole steps, from the start of the first step
with a contact force to the end of the last, as check_bar.py does); the
largest of the steps' contact forces (each the step's mean, impulse / dt)
is F_max (--tol-force); no node of any step file lies below the plane by
more than --tol-penetration x delta_max; the ball has left the plane at the
last step. Also printed, not checked: the largest approach of the ball's
centre of mass against delta_max, the rebound speed and the energy after
separation against the initial kinetic energy.

  check_hertz_impact.py --static --out DIR [-- MPIEXEC ... TRIBOS INPUT --set Dynamics/Enabled=false
                        --set "Boundary Conditions/Volume Force={0, 0, -b}"]

reads a static run instead (the ball held on the plane by a uniform volume
force, as at the peak of the impact, where its acceleration is F / m): the
force F it transmits (--copies x the model's contact forces), and the
approach of its centre of mass and the contact radius against Hertz's for
that force, delta = (9 F^2 / (16 R E*^2))^(1/3) and a = sqrt(R delta)
(printed, not checked; docs/dynamics.md, "Hertz impact").
"""
import argparse
import json
import math
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np

from dynamics_checks import check, failed, numbers, parameter

sep = sys.argv.index("--") if "--" in sys.argv else len(sys.argv)
ap = argparse.ArgumentParser()
ap.add_argument("--out", required=True)
ap.add_argument("--base", default="solution")
ap.add_argument("--copies", type=int, default=4, help="the whole ball is this many copies of the model (4: quarter)")
ap.add_argument("--tol-duration", type=float, default=0.05)
ap.add_argument("--tol-force", type=float, default=0.05)
ap.add_argument("--tol-penetration", type=float, default=1e-3)
ap.add_argument("--static", action="store_true", help="a static run: the approach for its force against Hertz's")
ap.add_argument("--json", help="write the measured figures to this file")
a = ap.parse_args(sys.argv[1:sep])


cmd = sys.argv[sep + 1:]
if cmd:
    cmd += ["--output", a.out, "--summary", f"{a.out}/summary.json", "--quiet"]
    rc = subprocess.run(cmd).returncode
    check(rc == 0, f"exit code {rc} == 0")
    if rc != 0:
        sys.exit(1)


def volumes(X, cells):
    """The volume of each tetrahedron: Tet4 in closed form; Tet10 (curved:
    Gmsh puts the mid-edge nodes of a second-order mesh on the sphere) by a
    collapsed 5x5x5 Gauss rule, exact for its quadratic map, each mid-edge
    node matched to its edge by position (no node order assumed)."""
    corner = X[cells[:, :4]]
    d1, d2, d3 = (corner[:, i] - corner[:, 0] for i in (1, 2, 3))
    if cells.shape[1] == 4:
        return np.abs(np.einsum("ij,ij->i", d1, np.cross(d2, d3))) / 6
    edges = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]
    mids = np.stack([(corner[:, i] + corner[:, j]) / 2 for i, j in edges], axis=1)
    mid = np.empty((len(cells), 6, 3))
    for k in range(4, 10):
        e = np.argmin(np.linalg.norm(mids - X[cells[:, k]][:, None, :], axis=2), axis=1)
        mid[np.arange(len(cells)), e] = X[cells[:, k]]
    g, w = np.polynomial.legendre.leggauss(5)
    g, w = (g + 1) / 2, w / 2
    dL = np.array([[-1, -1, -1], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)  # d L_i / d xi_k
    total = np.zeros(len(cells))
    for iu, s in enumerate(g):
        for iv, t in enumerate(g):
            for iw, q in enumerate(g):
                xi = np.array([s, t * (1 - s), q * (1 - s) * (1 - t)])  # the cube onto the tetrahedron
                L = np.r_[1 - xi.sum(), xi]
                J = sum(np.einsum("ci,k->cik", corner[:, i], (4 * L[i] - 1) * dL[i]) for i in range(4))
                for e, (i, j) in enumerate(edges):
                    J += np.einsum("ci,k->cik", mid[:, e], 4 * (L[i] * dL[j] + L[j] * dL[i]))
                total += w[iu] * w[iv] * w[iw] * (1 - s) ** 2 * (1 - t) * np.abs(np.linalg.det(J))
    return total


def cell_mean_weights(cells):
    """The weights of the nodal values in a cell's mean over its volume:
    the corners' mean on Tet4, -1/20 of each corner's and 1/5 of each
    mid-edge node's on Tet10 (exact on straight-sided cells)."""
    return np.full(4, 0.25) if cells.shape[1] == 4 else np.r_[np.full(4, -0.05), np.full(6, 0.2)]


def centre_approach(u):
    """How far the model's centre of mass has moved down."""
    return -(vol * (u[cells, 2] @ cell_mean_weights(cells))).sum() / vol.sum()


root = ET.parse(os.path.join(a.out, a.base + ".parameters.xml")).getroot()
E = float(parameter(root, "Material/Young's Modulus"))
nu = float(parameter(root, "Material/Poisson's Ratio"))
rho = float(parameter(root, "Material/Density"))
Estar = E / (1 - nu ** 2)
if a.static:
    rows = []
    data = a.base + ".h5"
else:
    rows = [json.loads(line) for line in open(os.path.join(a.out, a.base + ".steps.jsonl"))]
    data = rows[0]["file"]

# The model's mesh: its volume, mass and height (every step file holds the mesh).
with h5py.File(os.path.join(a.out, data), "r") as h:
    X = h["mesh/geometry"][...]
    cells = h["mesh/topology"][...].astype(int)
vol = volumes(X, cells)
check(X[:, 0].min() >= -1e-9 and X[:, 1].min() >= -1e-9 and abs(X[:, 2].min()) < 1e-9,
      "the model lies in x >= 0, y >= 0 and touches z = 0")
R = (X[:, 2].max() - X[:, 2].min()) / 2
m_model = rho * vol.sum()
m = a.copies * m_model

if a.static:
    with h5py.File(os.path.join(a.out, data), "r") as h:
        u = h["nodes/displacement"][...]
        fn = h["points/contact/normal_force"][...].ravel()
        xc = h["points/contact/geometry"][...]
    F = a.copies * fn.sum()
    delta = (9 * F ** 2 / (16 * R * Estar ** 2)) ** (1 / 3)
    approach = centre_approach(u)
    r = np.hypot(xc[:, 0], xc[:, 1])
    a_h = math.sqrt(2.5 * np.sum(fn * r * r) / fn.sum())  # the second moment of the forces, as scripts/hertz.py
    print(f"static: {len(X)} nodes, F = {F:.6g}, Hertz delta = {delta:.5g}, a = {math.sqrt(R * delta):.4g} "
          f"(a / R = {math.sqrt(delta / R):.3f}); the centre of mass approaches by {approach:.5g} "
          f"({approach / delta - 1:+.3%}), a_h = {a_h:.4g} ({a_h / math.sqrt(R * delta) - 1:+.3%})")
    sys.exit(1 if failed() else 0)

velocity = numbers(parameter(root, "Initial Conditions/Velocity"))
dt = float(parameter(root, "Dynamics/Time Step"))
check(velocity[0] == 0 and velocity[1] == 0 and velocity[2] < 0, f"the ball moves down onto the plane: {velocity}")
v0 = -velocity[2]
check(all(r["converged"] for r in rows), f"all {len(rows)} steps converged")

delta = (15 * m * v0 ** 2 / (16 * Estar * math.sqrt(R))) ** 0.4
F_max = 4.0 / 3.0 * Estar * math.sqrt(R) * delta ** 1.5
t_c = 2.87 * (m ** 2 / (R * Estar ** 2 * v0)) ** 0.2
c = math.sqrt(E / rho)
print(f"R = {R:.6g}, m = {a.copies} x {m_model:.6g} = {m:.6g} (the exact ball: {4 / 3 * math.pi * R ** 3 * rho:.6g}), "
      f"E* = {Estar:.6g}, v0 = {v0:.6g}, v0 / c = {v0 / c:.3g}")
print(f"Hertz: delta_max = {delta:.6g}, a = sqrt(R delta) = {math.sqrt(R * delta):.4g} (a / R = "
      f"{math.sqrt(delta / R):.3f}), F_max = {F_max:.6g} (the model's share {F_max / a.copies:.6g}), "
      f"t_c = {t_c:.6g} = {t_c / dt:.1f} steps")

t = np.array([r["time"] for r in rows])
F = a.copies * np.array([r["dynamics"]["contact_force"] for r in rows])
on = np.nonzero(F > 1e-6 * F_max)[0]
check(len(on) > 0, "the ball touched the plane")
if len(on) == 0:
    sys.exit(1)
measured = t[on[-1]] - (t[on[0]] - dt)
err_d = measured / t_c - 1
peak = F.max()
err_f = peak / F_max - 1
check(abs(err_d) <= a.tol_duration,
      f"contact duration {measured:.5g} ({len(on)} steps, {on[0] + 1} to {on[-1] + 1}) against Hertz's t_c = {t_c:.5g}: "
      f"{err_d:+.3%}")
check(abs(err_f) <= a.tol_force,
      f"peak contact force {peak:.5g} (step {F.argmax() + 1}, t = {t[F.argmax()]:.4g}) against Hertz's F_max = "
      f"{F_max:.5g}: {err_f:+.3%}")
check(on[-1] < len(rows) - 1 and F[-1] == 0, f"the ball left the plane (the last {len(rows) - 1 - on[-1]} steps "
                                              "without contact force)")

# Penetration, and the approach of the ball's centre of mass.
deepest, approach = 0.0, 0.0
for r in rows:
    with h5py.File(os.path.join(a.out, r["file"]), "r") as h:
        u = h["nodes/displacement"][...]
    deepest = max(deepest, -(X[:, 2] + u[:, 2]).min())
    approach = max(approach, centre_approach(u))
check(deepest <= a.tol_penetration * delta,
      f"deepest penetration {max(deepest, 0.0):.3g} = {max(deepest, 0.0) / delta:.2e} delta_max "
      f"(at most {a.tol_penetration:g})")
err_delta = approach / delta - 1
print(f"largest approach of the centre of mass {approach:.5g} against delta_max = {delta:.5g}: {err_delta:+.3%}")
last = rows[-1]["dynamics"]
energy = 0.5 * m_model * v0 ** 2
err_e = (last["kinetic_energy"] + last["strain_energy"]) / energy - 1
impulse = F.sum() * dt
print(f"rebound speed (impulse / m - v0) {impulse / m - v0:.5g}, restitution {impulse / m / v0 - 1:.4f}; "
      f"energy after separation against the initial {energy:.5g}: {err_e:+.3%}")
if a.json:
    with open(a.json, "w") as f:
        json.dump({"t_c": t_c, "duration": measured, "err_duration": err_d, "F_max": F_max, "peak_force": peak,
                   "err_force": err_f, "delta_max": delta, "approach": approach, "err_approach": err_delta,
                   "penetration": deepest / delta, "restitution": impulse / m / v0 - 1, "err_energy": err_e,
                   "steps": len(rows), "contact_steps": len(on)}, f, indent=1)
sys.exit(1 if failed() else 0)
