#!/usr/bin/python3
"""Signorini's bar through the driver (input/bar_impact.xml, docs/dynamics.md):

  check_bar.py --out DIR [--tol-duration T] [--tol-force T] [--tol-energy T] -- MPIEXEC ... TRIBOS INPUT ...

runs the command, then reads the steps table (BASE.steps.jsonl) and the last
step file: every step converged; the contact lasted 2 L / c (within
--tol-duration, counted in whole steps from the step before the first with
a contact force to the last), its mean force (the impulse of the steps'
forces over that time) is rho c v0 A (--tol-force), the energy after
separation (kinetic + strain) is the initial kinetic energy
(--tol-energy), and the last step file's velocity field carries the
bar's momentum: -v0 plus the contact impulse over its mass, to 1e-4 v0. The bar's data are read from the run's
parameters file (BASE.parameters.xml).
"""
import argparse
import json
import math
import subprocess
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np

from dynamics_checks import check, failed, numbers, parameter

sep = sys.argv.index("--")
ap = argparse.ArgumentParser()
ap.add_argument("--out", required=True)
ap.add_argument("--tol-duration", type=float, default=0.05)
ap.add_argument("--tol-force", type=float, default=0.05)
ap.add_argument("--tol-energy", type=float, default=0.02)
a = ap.parse_args(sys.argv[1:sep])
cmd = sys.argv[sep + 1:] + ["--output", a.out, "--summary", f"{a.out}/summary.json", "--quiet"]
rc = subprocess.run(cmd).returncode


check(rc == 0, f"exit code {rc} == 0")
if rc != 0:
    sys.exit(1)


root = ET.parse(f"{a.out}/solution.parameters.xml").getroot()
E = float(parameter(root, "Material/Young's Modulus"))
rho = float(parameter(root, "Material/Density"))
x, y, z = (numbers(parameter(root, f"Mesh/{c} Range")) for c in "XYZ")
v0 = -numbers(parameter(root, "Initial Conditions/Velocity"))[2]
dt = float(parameter(root, "Dynamics/Time Step"))
L, A = z[1] - z[0], (x[1] - x[0]) * (y[1] - y[0])
c = math.sqrt(E / rho)
duration, force, energy = 2 * L / c, rho * c * v0 * A, 0.5 * rho * L * A * v0 ** 2

rows = [json.loads(line) for line in open(f"{a.out}/solution.steps.jsonl")]
check(all(r["converged"] for r in rows), f"all {len(rows)} steps converged")
F = np.array([r["dynamics"]["contact_force"] for r in rows])
t = np.array([r["time"] for r in rows])
on = np.nonzero(F > 1e-6 * force)[0]
measured = t[on[-1]] - (t[on[0]] - dt)
impulse = F.sum() * dt
err_d = measured / duration - 1
err_f = impulse / measured / force - 1
last = rows[-1]["dynamics"]
err_e = (last["kinetic_energy"] + last["strain_energy"]) / energy - 1
check(abs(err_d) <= a.tol_duration, f"contact duration {measured:.4g} s against 2L/c = {duration:.4g} s: {err_d:+.3%}")
check(abs(err_f) <= a.tol_force, f"mean contact force {impulse / measured:.4g} N against rho c v0 A = {force:.4g} N: {err_f:+.3%}")
check(abs(err_e) <= a.tol_energy, f"energy after separation against the initial {energy:.4g} J: {err_e:+.3%}")
# Momentum: the bar's mass-weighted velocity after the contact is -v0 plus
# the contact impulse over its mass (Hex8 row sums of M: half a node's
# share at the two ends of the bar; other cells' row sums are not such
# shares, and the check is left out for them).
if parameter(root, "Mesh/Element") != "Hex8":
    print("skipped: the momentum of the velocity field (nodal shares of the mass known for Hex8 only)")
    sys.exit(1 if failed() else 0)
with h5py.File(f"{a.out}/{rows[-1]['file']}", "r") as h:
    zs = h["mesh/geometry"][:, 2]
    vz = h["nodes/velocity"][:, 2]
w = np.where((np.abs(zs - z[0]) < 1e-9 * L) | (np.abs(zs - z[1]) < 1e-9 * L), 0.5, 1.0)
mean = (w * vz).sum() / w.sum()
expected = -v0 + impulse / (rho * A * L)
check(abs(mean - expected) <= 1e-4 * v0,
      f"the last step's velocity field: the bar leaves at {mean:.6g} m/s, -v0 + impulse / m = {expected:.6g}")
sys.exit(1 if failed() else 0)
