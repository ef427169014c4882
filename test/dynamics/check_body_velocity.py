#!/usr/bin/python3
"""Per-body initial velocities through the driver (docs/dynamics.md, "The driver"):

  check_body_velocity.py --out DIR [--set S ...] -- MPIEXEC ... TRIBOS INPUT

runs the command (test/dynamics/two_blocks_dynamics.xml: the blocks "lower"
and "upper" of input/two_blocks.msh, Hex8 boxes, "upper" leaving "lower"
at its own Bodies/upper/Initial Velocity, "lower" at Initial
Conditions/Velocity; --set: more parameters), then reads the parameters
file, the steps table and every step file. Both bodies are in free flight
(no load, the contacts open or without force), so each moves rigidly at its
initial velocity, and at every step:

  - each body's momentum, sum over its nodes of m_a v_a (m_a the row sums
    of the consistent mass, rho V / 8 from each of a node's Hex8 cells,
    boxes along the axes), is m v0 of that body, to 1e-10 of the largest |m v0|;
  - every node's written velocity is its body's v0, to 1e-8 of the largest
    |v0| (the solves' tolerance: v = v_n + 2 (u_{n+1} - u_pred) / dt);
  - the kinetic energy of the steps table is the sum of m |v0|^2 / 2, to
    1e-9 relative, and no contact force acts.

The bodies are numbered as the mesh orders them (their physical volumes'
tags): --bodies gives their names in that order (default: lower upper).
"""
import argparse
import json
import subprocess
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np

from dynamics_checks import check, failed, numbers, parameter

sep = sys.argv.index("--")
ap = argparse.ArgumentParser()
ap.add_argument("--out", required=True)
ap.add_argument("--set", action="append", default=[], dest="sets")
ap.add_argument("--bodies", nargs="+", default=["lower", "upper"])
a = ap.parse_args(sys.argv[1:sep])
cmd = sys.argv[sep + 1:] + ["--output", a.out, "--quiet"]
for s in a.sets:
    cmd += ["--set", s]
rc = subprocess.run(cmd).returncode


check(rc == 0, f"exit code {rc} == 0")
if rc != 0:
    sys.exit(1)


def vector(text):
    items = [v for v in text.strip("{} ").split(",") if v.strip()]
    return np.array([float(v) for v in items]) if items else None


root = ET.parse(f"{a.out}/solution.parameters.xml").getroot()
rho = float(parameter(root, "Material/Density"))
v_global = vector(parameter(root, "Initial Conditions/Velocity"))
v0 = []
for name in a.bodies:
    own = parameter(root, f"Bodies/{name}/Initial Velocity")
    v0.append(vector(own) if own is not None and vector(own) is not None else v_global)
v0 = np.array(v0)

rows = [json.loads(line) for line in open(f"{a.out}/solution.steps.jsonl")]
check(len(rows) >= 1 and all(r["converged"] for r in rows), f"all {len(rows)} steps converged")

with h5py.File(f"{a.out}/{rows[0]['file']}", "r") as h:
    x = np.array(h["mesh/geometry"])
    cells = np.array(h["mesh/topology"])
    body = np.array(h["cells/body"]).ravel().astype(int)
check(cells.shape[1] == 8, "Hex8 cells")
# The cells of the two boxes are boxes along the axes: the volume is the
# product of their extents.
corners = x[cells]
volume = np.prod(corners.max(axis=1) - corners.min(axis=1), axis=1)
share = np.zeros(len(x))
np.add.at(share, cells.ravel(), np.repeat(rho * volume / 8, 8))
node_body = np.full(len(x), -1)
node_body[cells.ravel()] = np.repeat(body, 8)
mass = np.array([rho * volume[body == b].sum() for b in range(len(v0))])
p_ref = max(float(np.max(mass[:, None] * np.abs(v0))), 1e-300)
v_ref = max(float(np.max(np.abs(v0))), 1e-300)
energy = 0.5 * float((mass * (v0 ** 2).sum(axis=1)).sum())
print("bodies: " + ", ".join(f"{n} m = {m:.6g} kg, v0 = {tuple(v)}" for n, m, v in zip(a.bodies, mass, v0)))

worst_p = worst_v = worst_e = worst_f = 0.0
for r in rows:
    with h5py.File(f"{a.out}/{r['file']}", "r") as h:
        v = np.array(h["nodes/velocity"])
    for b in range(len(v0)):
        mine = node_body == b
        p = (share[mine, None] * v[mine]).sum(axis=0)
        worst_p = max(worst_p, float(np.max(np.abs(p - mass[b] * v0[b]))) / p_ref)
        worst_v = max(worst_v, float(np.max(np.abs(v[mine] - v0[b]))) / v_ref)
    worst_e = max(worst_e, abs(r["dynamics"]["kinetic_energy"] - energy) / energy)
    worst_f = max(worst_f, abs(r["dynamics"]["contact_force"]))
check(worst_p <= 1e-10, f"each body's momentum is its m v0 at every step: {worst_p:.1e} of the largest |m v0| (<= 1e-10)")
check(worst_v <= 1e-8, f"every node's velocity is its body's v0: {worst_v:.1e} of the largest |v0| (<= 1e-8)")
check(worst_e <= 1e-9, f"the kinetic energy is sum m |v0|^2 / 2 = {energy:.6g} J: {worst_e:.1e} relative (<= 1e-9)")
check(worst_f <= 1e-9 * p_ref, f"no contact force: {worst_f:.1e} N")
sys.exit(1 if failed() else 0)
