#!/usr/bin/python3
"""The stick-slip oscillator through the driver (input/stick_slip.xml,
docs/dynamics.md, "Stick-slip oscillator"):

  check_stick_slip.py --out DIR [--spring-input FILE] [--tribos BIN] [--plot FILE.png] [--json FILE]
                      [--tol-stick T] [--tol-period T] [--tol-velocity T] [--tol-dissipation T]
                      -- MPIEXEC ... TRIBOS INPUT ...

runs the command (or, with no command after --, reads DIR as it is), then
the static run of the spring alone (--spring-input, default
stick_slip_spring.xml beside INPUT, or the repository's input/ when there
is no command; with the same MPIEXEC ... TRIBOS, or --tribos BIN on one
rank when there is no command) into DIR_spring, and
compares the run with the one-degree-of-freedom model of a mass m held by a
spring k on a plane with Coulomb friction F (equal static and kinetic
coefficients), the spring's far end driven at v_d from t0 on:

  stick    for t_stick = F N / (k v_d) after t0: the block at rest, the
           friction force k v_d (t - t0);
  slip     tau = t - t0 - t_stick, omega = sqrt(k / m), T = 2 pi / omega:
           the block's velocity v_d (1 - cos(omega tau)), between 0 and
           2 v_d, at rest for an instant at the end of each period and
           slipping again at once (the spring force is F N there and
           rising); the friction force F N, the spring force
           F N + (k v_d / omega) sin(omega tau), the slid distance
           x = v_d tau - (v_d / omega) sin(omega tau) and the energy
           friction dissipated F N x.

The model's figures come from the run and its input, none written here:
  m   the block's density times its cells' volume, plus a third of the
      spring's mass (Rayleigh's correction for a spring's own mass);
  k   the static run of the spring body (its material, extent and cells
      read from the oscillator's run, its end held as the driver holds
      it): the resultant of sigma_xx over a section (the cells' mean times
      the section) over the end's displacement;
  N   the traction on the block's top times the block's plan area;
  F   the pair's friction coefficient; v_d and t0 the driver's Value and
      curve (0 up to t0, linear after).
The block is the body with the contact nodes, the spring the other one.

A step's contact forces (the steps table's) are its means, impulse / dt,
and stand at the middle of the step, t - dt / 2.

Checked: both runs exit 0 and every step converged; the stick phase lasts
t_stick (--tol-stick; measured as where the line through the friction force
of the stick steps, below 80 % of the slip's, reaches the slip's median
friction force, so between steps); the period of the block's velocity
(from its successive crossings of v_d, each interpolated between steps) is T
(--tol-period); its largest value is 2 v_d (--tol-velocity); the friction
force of the slip steps is F N (--tol-velocity, of F N); the energy
friction dissipated (the steps table's friction_dissipation) is F N_slip
times the slid distance of the contact nodes (--tol-dissipation) and the
model's F N x (2 --tol-dissipation). Printed besides: the stiffness the
stick phase shows (the slope of its friction force over v_d) against k,
the time of the first crossing against the model's, and the normal force's
spread.

The block's velocity and displacement are the volume means over its cells
(each cell's mean of its nodes, exact on its parallelepipeds for the
trilinear field), read from every step file.
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
ap.add_argument("--spring-input", help="the static run of the spring (default: stick_slip_spring.xml beside INPUT)")
ap.add_argument("--tribos", help="the driver for the static run when no command is given")
ap.add_argument("--tol-stick", type=float, default=0.01)
ap.add_argument("--tol-period", type=float, default=0.01)
ap.add_argument("--tol-velocity", type=float, default=0.03)
ap.add_argument("--tol-dissipation", type=float, default=0.01)
ap.add_argument("--plot", help="draw the block's velocity and the forces against the model into this PNG")
ap.add_argument("--json", help="write the measured figures to this file")
a = ap.parse_args(sys.argv[1:sep])


def sublists(root, path):
    node = root
    for name in path.split("/"):
        node = next(c for c in node if c.tag == "ParameterList" and c.get("name") == name)
    return [c for c in node if c.tag == "ParameterList"]


cmd = sys.argv[sep + 1:]
if cmd:
    with open(f"{a.out}.log", "w") as log:  # the summary the driver prints
        rc = subprocess.run(cmd + ["--output", a.out, "--summary", f"{a.out}/summary.json", "--quiet"],
                            stdout=log).returncode
    check(rc == 0, f"exit code {rc} == 0")
    if rc != 0:
        sys.exit(1)

root = ET.parse(os.path.join(a.out, a.base + ".parameters.xml")).getroot()
rows = [json.loads(line) for line in open(os.path.join(a.out, a.base + ".steps.jsonl"))]
check(all(r["converged"] for r in rows), f"all {len(rows)} steps converged")
dt = float(parameter(root, "Dynamics/Time Step"))
t = np.array([r["time"] for r in rows])

# The mesh, its bodies, and which is the block (the one with contact nodes).
with h5py.File(os.path.join(a.out, rows[0]["file"]), "r") as h:
    X = h["mesh/geometry"][...]
    cells = h["mesh/topology"][...].astype(int)
    body = h["cells/body"][...].ravel().astype(int)
    contact_nodes = h["points/contact/node"][...].ravel().astype(int)
check(cells.shape[1] == 8, "Hex8 cells")
g = np.array([-1, 1]) / math.sqrt(3)
corners = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1], [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]])


def hex_volumes(Xc):
    """The volume of each Q1 hexahedron by 2x2x2 Gauss (exact for its trilinear map)."""
    vol = np.zeros(len(Xc))
    for xi in g:
        for eta in g:
            for zeta in g:
                dN = np.stack([corners[:, 0] * (1 + corners[:, 1] * eta) * (1 + corners[:, 2] * zeta),
                               corners[:, 1] * (1 + corners[:, 0] * xi) * (1 + corners[:, 2] * zeta),
                               corners[:, 2] * (1 + corners[:, 0] * xi) * (1 + corners[:, 1] * eta)], axis=1) / 8
                vol += np.abs(np.linalg.det(np.einsum("cai,ak->cik", Xc, dN)))
    return vol


vol = hex_volumes(X[cells])
block_ids = set(body[np.isin(cells, contact_nodes).sum(axis=1) >= 4])  # cells with a face on the plane
check(len(block_ids) == 1 and len(set(body)) == 2, f"two bodies, one of them (body {sorted(block_ids)}) in contact")
block = body == next(iter(block_ids))
spring = ~block
body_names = {c.get("name") for c in sublists(root, "Bodies")}
spring_name = "spring" if "spring" in body_names else None


def material(name, key):
    return float(parameter(root, f"Bodies/{name}/Material/{key}", "") or parameter(root, f"Material/{key}")) \
        if name else float(parameter(root, f"Material/{key}"))


rho_b = float(parameter(root, "Material/Density"))
rho_s = material(spring_name, "Density")
E_s = material(spring_name, "Young's Modulus")
nu_s = material(spring_name, "Poisson's Ratio")
V_b, V_s = vol[block].sum(), vol[spring].sum()
m = rho_b * V_b + rho_s * V_s / 3
bx = X[np.unique(cells[block])]
sx = X[np.unique(cells[spring])]
plan = np.ptp(bx[:, 0]) * np.ptp(bx[:, 1])

# The loads: the driver (the Dirichlet condition with a non-zero value) and the pressure.
curves = {c.get("name"): (numbers(parameter(c, "Times")), numbers(parameter(c, "Values")))
          for c in sublists(root, "Load Curves")}
drivers = [c for c in sublists(root, "Boundary Conditions/Dirichlet") if any(numbers(parameter(c, "Value")))]
check(len(drivers) == 1, "one driven Dirichlet condition")
drv = drivers[0]
value = numbers(parameter(drv, "Value"))
ct, cv = curves[parameter(drv, "Curve")]
i0 = max(i for i in range(len(cv)) if cv[i] == 0 and all(v == 0 for v in cv[:i + 1]))
t0 = ct[i0]
slope = (cv[i0 + 1] - cv[i0]) / (ct[i0 + 1] - ct[i0])
check(value[1] == 0 and value[2] == 0 and i0 + 2 == len(ct) and ct[-1] >= t[-1],
      f"the driver moves along x only, linearly from t0 = {t0:g} to the end")
v_d = value[0] * slope
tractions = sublists(root, "Boundary Conditions/Traction")
check(len(tractions) == 1, "one traction, the pressure on the block")
p = -numbers(parameter(tractions[0], "Value"))[2]
pt, pv = curves[parameter(tractions[0], "Curve")]
check(all(v == 1 for tt, v in zip(pt, pv) if tt >= t0), "the pressure is at its full value from t0 on")
N = p * plan
pair = sublists(root, "Contact/Pairs")[0]
F = float(parameter(pair, "Friction Coefficient", "") or parameter(root, "Contact/Friction Coefficient"))

# k: the static run of the spring alone.
spring_input = a.spring_input or os.path.join(
    os.path.dirname(os.path.abspath(cmd[-1])) if cmd else os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                                       "..", "..", "input"),
    "stick_slip_spring.xml")
spring_out = a.out.rstrip("/") + "_spring"
runner = cmd[:-1] if cmd else [a.tribos]
cells_s = [len(np.unique(np.round(sx[:, d], 12))) - 1 for d in range(3)]
static = runner + [spring_input, "--output", spring_out, "--summary", f"{spring_out}/summary.json", "--quiet",
                   "--set", f"Material/Young's Modulus={E_s!r}", "--set", f"Material/Poisson's Ratio={nu_s!r}",
                   "--set", "Mesh/X Range={%r, %r}" % (sx[:, 0].min(), sx[:, 0].max()),
                   "--set", "Mesh/Y Range={%r, %r}" % (sx[:, 1].min(), sx[:, 1].max()),
                   "--set", "Mesh/Z Range={%r, %r}" % (sx[:, 2].min(), sx[:, 2].max()),
                   "--set", "Mesh/Cells={%d, %d, %d}" % tuple(cells_s),
                   "--set", "Boundary Conditions/Dirichlet/driver/Components=" + parameter(drv, "Components")]
with open(f"{spring_out}.log", "w") as log:
    rc = subprocess.run(static, stdout=log).returncode
check(rc == 0, f"static run of the spring: exit code {rc} == 0")
if rc != 0:
    sys.exit(1)
sroot = ET.parse(os.path.join(spring_out, "solution.parameters.xml")).getroot()
d = numbers(parameter(sroot, "Boundary Conditions/Dirichlet/driver/Value"))[0]
with h5py.File(os.path.join(spring_out, "solution.h5"), "r") as h:
    sxx = h["cells/stress"][:, 0]
    svol = hex_volumes(h["mesh/geometry"][...][h["mesh/topology"][...].astype(int)])
section = np.ptp(sx[:, 1]) * np.ptp(sx[:, 2])
k = -(sxx * svol).sum() / svol.sum() * section / d
omega = math.sqrt(k / m)
T = 2 * math.pi / omega
t_stick = F * N / (k * v_d)
print(f"block: m = {rho_b:g} x {V_b:.6g} + {rho_s:g} x {V_s:.6g} / 3 = {m:.6g}; spring: E = {E_s:g}, nu = {nu_s:g}, "
      f"L = {np.ptp(sx[:, 0]):g}, section {section:.6g}, k = {k:.6g} (static run; E A / L = "
      f"{E_s * section / np.ptp(sx[:, 0]):.6g})")
print(f"N = {p:g} x {plan:.6g} = {N:.6g}, F = {F:g}, F N = {F * N:.6g}, v_d = {v_d:g} from t0 = {t0:g}")
print(f"model: t_stick = F N / (k v_d) = {t_stick:.6g} ({t_stick / dt:.1f} steps), omega = {omega:.6g}, "
      f"T = {T:.6g} ({T / dt:.1f} steps)")


def model(tt):
    """The model's block velocity, friction force, spring force and slid distance at the times tt."""
    tt = np.asarray(tt, float)
    tau = tt - t0 - t_stick
    s = np.clip(tau, 0, None)
    v = np.where(tau > 0, v_d * (1 - np.cos(omega * s)), 0.0)
    x = np.where(tau > 0, v_d * s - v_d / omega * np.sin(omega * s), 0.0)
    ramp = k * v_d * np.clip(tt - t0, 0, None)
    fric = np.where(tau > 0, F * N, ramp)
    spr = np.where(tau > 0, F * N + k * v_d / omega * np.sin(omega * s), ramp)
    return v, fric, spr, x


# The run: the friction and normal forces of the steps table, the block's
# velocity and displacement and the spring's force from the step files.
# A step's contact forces are its means (impulse / dt), set at its middle.
tm_ = t - dt / 2
fric = -np.array([r["pairs"][0]["tangential_force"][0] for r in rows])
normal = np.array([r["pairs"][0]["normal_force"] for r in rows])
dissipated = np.array([r["dynamics"]["friction_dissipation"] for r in rows])
vb, xb, fs = np.zeros(len(rows)), np.zeros(len(rows)), np.zeros(len(rows))
wb = vol[block] / V_b
for i, r in enumerate(rows):
    with h5py.File(os.path.join(a.out, r["file"]), "r") as h:
        v = h["nodes/velocity"][:, 0]
        u = h["nodes/displacement"][:, 0]
        s = h["cells/stress"][:, 0]
        if i == len(rows) - 1:
            slid = u[contact_nodes].mean()
    vb[i] = (v[cells[block]].mean(axis=1) * wb).sum()
    xb[i] = (u[cells[block]].mean(axis=1) * wb).sum()
    fs[i] = -(s[spring] * vol[spring]).sum() / V_s * section

# Stick: where the line through the stick steps' friction reaches the slip's.
late = t > t[len(t) // 2]
plateau = np.median(fric[late])
ramp = (tm_ > t0 + dt) & (fric < 0.8 * plateau) & (np.arange(len(t)) < np.argmax(fric > 0.8 * plateau))
s_fit, c_fit = np.polyfit(tm_[ramp], fric[ramp], 1)
measured_stick = (plateau - c_fit) / s_fit - t0
err_stick = measured_stick / t_stick - 1
check(abs(err_stick) <= a.tol_stick, f"stick phase {measured_stick:.6g} (the friction's line over {ramp.sum()} steps "
                                      f"reaches the slip's {plateau:.6g}) against F N / (k v_d) = {t_stick:.6g}: "
                                      f"{err_stick:+.3%}")
k_stick = s_fit / v_d
print(f"the stick phase's stiffness (slope / v_d) {k_stick:.6g} against k: {k_stick / k - 1:+.3%}")

# Slip: the period from the crossings of v_d, interpolated between steps.
slip = t > t0 + measured_stick
w = vb - v_d
up, down = [], []
for i in range(1, len(t)):
    if slip[i - 1] and w[i - 1] * w[i] < 0:
        tc = t[i - 1] + dt * w[i - 1] / (w[i - 1] - w[i])
        (up if w[i] > 0 else down).append(tc)
periods = np.r_[np.diff(up), np.diff(down)]
check(len(periods) >= 2, f"{len(up)} upward and {len(down)} downward crossings of v_d in the slip")
if len(periods) == 0:
    sys.exit(1)
measured_T = periods.mean()
err_T = measured_T / T - 1
check(abs(err_T) <= a.tol_period, f"period {measured_T:.6g} (mean of {len(periods)}: "
                                  f"{', '.join('%.5g' % q for q in periods)}) against 2 pi sqrt(m / k) = {T:.6g}: "
                                  f"{err_T:+.3%}")
first = up[0] - (t0 + t_stick + T / 4)
print(f"first crossing of v_d at {up[0]:.6g}, the model's at {t0 + t_stick + T / 4:.6g}: {first:+.4g} "
      f"({first / T:+.2%} of T)")
vmax = vb[slip].max()
err_v = vmax / (2 * v_d) - 1
check(abs(err_v) <= a.tol_velocity, f"largest velocity {vmax:.6g} against 2 v_d = {2 * v_d:g}: {err_v:+.3%}")
print(f"smallest velocity after the first crossing {vb[t > up[0]].min():.4g} ({vb[t > up[0]].min() / v_d:+.2%} of v_d)")
full = tm_ > t0 + measured_stick + dt
err_f = np.abs(fric[full] / (F * N) - 1).max()
check(err_f <= a.tol_velocity, f"friction force of the slip steps within {err_f:.3%} of F N "
                               f"(mean {fric[full].mean():.6g})")
print(f"normal force from t0 on: {normal[tm_ >= t0].min():.6g} to {normal[tm_ >= t0].max():.6g} against N = {N:.6g}")

# Dissipation.
N_slip = normal[full].mean()
err_d = dissipated[-1] / (F * N_slip * slid) - 1
check(abs(err_d) <= a.tol_dissipation, f"dissipated {dissipated[-1]:.6g} against F N_slip x slid distance "
                                       f"{F:g} x {N_slip:.6g} x {slid:.6g} = {F * N_slip * slid:.6g}: {err_d:+.3%}")
x_model = model(t[-1])[3]
err_dm = dissipated[-1] / (F * N * x_model) - 1
check(abs(err_dm) <= 2 * a.tol_dissipation, f"dissipated against the model's F N x = {F * N * x_model:.6g}: "
                                            f"{err_dm:+.3%} (slid {slid:.6g} against {x_model:.6g})")

if a.plot:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    tm = np.linspace(0, t[-1], 2000)
    mv, mf, ms, _ = model(tm)
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(8, 7))
    scale = 1e3
    top.plot(tm * scale, mv, "k-", lw=1, label="1-dof model")
    top.plot(t * scale, vb, "o", ms=3, label="block (mean over its cells)")
    top.axhline(v_d, color="gray", ls=":", lw=1, label="driver speed $v_d$")
    top.set_ylabel("block velocity [m/s]")
    top.legend(fontsize="small", loc="upper left")
    top.grid(alpha=0.3)
    bottom.plot(tm * scale, ms, "k-", lw=1, label="model: spring force")
    bottom.plot(tm * scale, mf, "k--", lw=1, label="model: friction force")
    bottom.plot(t * scale, fs, "s", ms=3, mfc="none", label="spring force (section of the bar)")
    bottom.plot(tm_ * scale, fric, "o", ms=3, label="friction force (contact pair, the step's mean)")
    bottom.set_ylabel("force along x [N]")
    bottom.set_xlabel("time [ms]")
    bottom.legend(fontsize="small", loc="lower right")
    bottom.grid(alpha=0.3)
    fig.suptitle(f"stick-slip oscillator: stick {measured_stick * 1e3:.2f} ms ({err_stick:+.2%}), "
                 f"period {measured_T * 1e3:.2f} ms ({err_T:+.2%})")
    fig.tight_layout()
    fig.savefig(a.plot, dpi=110)
    print("figure:", a.plot)

if a.json:
    with open(a.json, "w") as f:
        json.dump({"m": m, "k": k, "N": N, "F": F, "v_d": v_d, "t0": t0, "t_stick": t_stick, "T": T,
                   "stick": measured_stick, "err_stick": err_stick, "k_stick": k_stick, "period": measured_T,
                   "err_period": err_T, "periods": list(periods), "v_max": vmax, "err_v_max": err_v,
                   "err_friction": err_f, "dissipated": dissipated[-1], "err_dissipation": err_d,
                   "err_dissipation_model": err_dm, "steps": len(rows)}, f, indent=1)
sys.exit(1 if failed() else 0)
