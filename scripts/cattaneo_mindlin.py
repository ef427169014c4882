#!/usr/bin/python3
"""Cattaneo-Mindlin with Mindlin-Deresiewicz unloading: Tribos against the
analytic solution, over the mesh levels of input/cattaneo_mindlin.geo
(docs/cattaneo_mindlin.md).

usage: scripts/cattaneo_mindlin.py [-l LEVEL ...] [--np N] [--tribos EXE] [--out DIR]
                                   [--table FILE.md] [--plot FILE.png | --no-plot] [--no-run]
                                   [--set "Sublist/Key=value" ...]

For each level (default 1 2 3; the meshes input/cattaneo_mindlin_L.msh are
shipped, other levels are made by Gmsh into OUT) two runs:

    mpirun -np N TRIBOS input/cattaneo_mindlin.xml --set Mesh/File=MESH --output OUT/level_L
    mpirun -np N TRIBOS input/cattaneo_mindlin.xml --set Mesh/File=MESH --output OUT/level_L_stick
        --set "Contact/Pairs/sphere on block/Friction Coefficient=1000" --set "Load Steps/Times={1, 5}"

the load history of the input, and the same mesh pressed and sheared to the
largest tangential displacement with friction so high (F_ref = 5) that the
contact sticks but for a rim of 2 % of a: its compliance C_stick = delta / Q
is the linear (elastic) part of the tangential displacement of this mesh,
bulk of both bodies included (the rim's micro-slip, Q/(F_ref P) ~ 0.065,
0.3 % of its delta, is taken out by its analytic value; a larger F_ref
stalls Algorithm 2: 5000 iterations at F = 1000 on Level 2, more than 5
minutes at F = 20 on Level 3).

Per step of the history, from the result (BASE.json and BASE.stepNNNN.h5):

  P      2 x the pair's normal force (half model);
  Q      -2 x the pair's tangential force along x (the force on the sphere
         is the reaction to the load);
  delta  the tangential displacement of the sphere's top face against the
         fixed block bottom (the mean u_x of the top face's nodes);
  s      delta - C_stick Q: the part of delta due to micro-slip;
  c      the stick radius, area-equivalent: the stick zone's area is the
         sum of the nodal areas A_i (the node's third of the adjacent slave
         facets, projected on z = 0) of the stick nodes, c = sqrt(2 A / pi)
         (half disc); likewise a_area from the active nodes. This sum is the
         integral of the P1 interpolant of the stick indicator, whose ramp
         across the boundary elements puts the edge on average where it is:
         no bias of half an element, unlike the radius of the outermost
         stick node (c_max, reported too).
  x_P    the pressure centre, sum f_N,i x_i / sum f_N,i.

Analytic (Johnson, Contact Mechanics, 7.2-7.4; elastically similar bodies,
G = E / (2 (1 + nu)), 1/E* = 2 (1 - nu^2)/E, K = 2 (2 - nu)/G):

  a        = (3 P R / (4 E*))^(1/3)                       (Hertz)
  c        = a (1 - |Q|/(F P))^(1/3)                      (loading from 0)
  c        = a (1 - |Q_t - Q|/(2 F P))^(1/3)              (after a reversal at Q_t)
  delta(Q) = 3 F P K/(16 a) [1 - (1 - Q/(F P))^(2/3)]     (loading, Q >= 0; odd in Q)
  delta    = delta_t - 2 delta((Q_t - Q)/2)               (after a reversal at (Q_t, delta_t))
  s        = delta - K Q/(8 a)                            (K/(8 a): the compliance of the stuck contact)

Errors (over the steps of the tangential history):

  err_P_a    a_area / a - 1 after the normal load
  err_c      max |c - c_exact| / a        (radii measured in contact radii)
  err_c_max  the same for c_max
  err_s      max |s - s_exact| / s_exact(Q*)   (the loop, its linear part removed)
  err_w      the loop's width at Q = 0, delta_down(0) - delta_up(0), relative
  spurious   after the normal load alone (the step before the tangential
             history), sum |f_T,i| / (F sum f_N,i): the friction the contact
             carries where the exact tangential traction of elastically
             similar bodies is zero
             (independent of C_stick: the linear part cancels in the width)

Writes the table (stdout, and --table as Markdown), OUT/cattaneo_mindlin.json
and the picture (--plot, default OUT/cattaneo_mindlin.png). --no-run analyses
results already in OUT. The script exits 1 if a run fails or does not
converge.
"""
import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hertz import cell, default_tribos, nodal_areas, parameter, timed_run  # noqa: E402 (shared with the Hertz benchmark)
import tribos_summary  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
INPUT = os.path.join(ROOT, "input", "cattaneo_mindlin.xml")
GEO = os.path.join(ROOT, "input", "cattaneo_mindlin.geo")
RADIUS = 10.0  # R of input/cattaneo_mindlin.geo
PAIR = "sphere on block"
STICK_F = 5.0  # friction coefficient of the (nearly) stuck reference run
STICK_SETS = ("Contact/Pairs/%s/Friction Coefficient=%g" % (PAIR, STICK_F), "Load Steps/Times={1, 5}")


def fail(message):
    sys.exit("cattaneo_mindlin.py: " + message)


# ---------------------------------------------------------------- analytic


def material(input_file=INPUT):
    """E, nu (one material for both bodies) and the pair's friction
    coefficient, from the input file: never from the run's --set, so that a
    wrong model run against the right analytic answer fails."""
    root = ET.parse(input_file).getroot()
    E = float(parameter(root, "Material/Young's Modulus"))
    nu = float(parameter(root, "Material/Poisson's Ratio"))
    F = float(parameter(root, "Contact/Pairs/%s/Friction Coefficient" % PAIR))
    return E, nu, F


class Mindlin:
    """The analytic answers for a normal load P held and a tangential load
    cycled, elastically similar bodies (E, nu), sphere radius R, friction F."""

    def __init__(self, P, E, nu, F, R=RADIUS):
        self.P, self.F = P, F
        G = E / (2.0 * (1.0 + nu))
        self.Estar = E / (2.0 * (1.0 - nu * nu))
        self.a = (3.0 * P * R / (4.0 * self.Estar)) ** (1.0 / 3.0)
        self.K = 2.0 * (2.0 - nu) / G
        self.A = 3.0 * F * P * self.K / (16.0 * self.a)  # delta's scale
        self.C = self.K / (8.0 * self.a)                 # compliance of the stuck contact

    def virgin(self, Q):
        """delta(Q) on loading from Q = 0 (odd in Q)."""
        x = min(abs(Q) / (self.F * self.P), 1.0)
        return math.copysign(self.A * (1.0 - (1.0 - x) ** (2.0 / 3.0)), Q)

    def stick_radius(self, Q, turn=None):
        """c at Q, on loading from 0 (turn None) or after a reversal at Q_t."""
        x = abs(Q) / (self.F * self.P) if turn is None else abs(turn - Q) / (2.0 * self.F * self.P)
        return self.a * max(1.0 - x, 0.0) ** (1.0 / 3.0)

    def branch_delta(self, Q, turn=None, delta_turn=0.0):
        if turn is None:
            return self.virgin(Q)
        return delta_turn - 2.0 * self.virgin((turn - Q) / 2.0)


def branches(delta, start):
    """The branch of each step from `start` on: (None) on loading from 0, or
    the index of the step where the last reversal of delta happened."""
    turn, out, direction = None, [], 0
    for k in range(len(delta)):
        if k < start:
            out.append(None)
            continue
        d = np.sign(delta[k] - delta[k - 1]) if k > 0 else 0
        if direction and d and d != direction:
            turn = k - 1
        if d:
            direction = d
        out.append(turn)
    return out


# ------------------------------------------------------------- the result


def step_file(directory, base, k, n):
    return os.path.join(directory, "%s.h5" % base if n == 1 else "%s.step%04d.h5" % (base, k))


def read_run(directory, base="solution"):
    """Per step: P, Q, delta, the contact points (x, y, status, f_N) and the
    nodal areas; the summary."""
    import h5py

    path = os.path.join(directory, base + ".json")
    try:
        summary = tribos_summary.load(path)
    except (OSError, ValueError, KeyError) as e:
        fail("cannot read the summary %s: %s" % (path, e))
    rows = summary.get("steps")
    if not isinstance(rows, list) or not rows:
        fail("%s has no steps" % path)
    steps, area = [], None
    for k, row in enumerate(rows, 1):
        pair = next((p for p in row["pairs"] if p["name"] == PAIR), None)
        if pair is None:
            fail("step %d of %s has no pair '%s'" % (k, path, PAIR))
        with h5py.File(step_file(directory, base, k, len(rows)), "r") as f:
            if area is None:  # the mesh is the same in every step
                coords = f["mesh/geometry"][...]
                cells = f["mesh/topology"][...].astype(int)
                node = f["points/contact/node"][...].ravel().astype(int)
                top = coords[:, 2] > RADIUS - 1e-6
                area = nodal_areas(coords, cells, node)
                x = f["points/contact/geometry"][...]
            u = f["nodes/displacement"][...]
            status = f["points/contact/status"][...].ravel().astype(int)
            fn = f["points/contact/normal_force"][...].ravel()
            ft = f["points/contact/tangential_force"][...]
        steps.append({
            "time": row["time"],
            "P": 2.0 * pair["normal_force"],
            "Q": -2.0 * pair["tangential_force"][0],
            "delta": float(u[top, 0].mean()),
            "status": status,
            "fn": fn,
            "ft": ft.reshape(len(fn), -1),
            "converged": bool(row.get("converged")),
            "kkt": max((v for key, v in row.get("kkt", {}).items()
                        if key != "limit" and isinstance(v, (int, float))), default=float("nan")),
            "iterations": row.get("iterations"),
        })
    return {"summary": summary, "steps": steps, "x": x, "area": area, "node": node}


def radius_of(mask, area, r):
    """Area-equivalent radius of the half disc covered by the nodes of mask,
    and the radius of the outermost one."""
    A = float(area[mask].sum())
    return math.sqrt(2.0 * A / math.pi), float(r[mask].max()) if mask.any() else 0.0


def mesh_size(run, a):
    """h: the mean edge of the slave facets inside r < a, from the nodal
    areas (A_i ~ sqrt(3)/4 h^2 x 6/3 for a regular triangulation)."""
    r = np.hypot(run["x"][:, 0], run["x"][:, 1])
    inside = (r < a) & (run["area"] > 0)
    return float(np.sqrt(run["area"][inside].mean() * 2.0 / math.sqrt(3.0)))


def analyse(directory, stick_directory, input_file=INPUT):
    """The figures of one level: a dict (per-step lists included)."""
    E, nu, F = material(input_file)
    run = read_run(directory)
    stick = read_run(stick_directory)
    steps = run["steps"]
    delta = np.array([s["delta"] for s in steps])
    Q = np.array([s["Q"] for s in steps])
    # The tangential history starts after the last step with delta = 0.
    first = int(np.nonzero(np.abs(delta) > 1e-12 * max(np.abs(delta).max(), 1e-300))[0][0])
    P = float(np.mean([s["P"] for s in steps[first - 1:]]))
    P_var = float(np.ptp([s["P"] for s in steps[first - 1:]]) / P)
    m = Mindlin(P, E, nu, F)
    # The reference's own micro-slip (Q/(F_ref P) ~ 0.065: 0.3 % of its
    # delta) taken out by its analytic value, so C_stick is the stuck one.
    last = stick["steps"][-1]
    ref = Mindlin(last["P"], E, nu, STICK_F)
    C_stick = (last["delta"] - (ref.virgin(last["Q"]) - ref.C * last["Q"])) / last["Q"]
    r = np.hypot(run["x"][:, 0], run["x"][:, 1])
    xs = run["x"][:, 0]

    turns = branches(delta, first)
    exact_delta, exact_c, c_area, c_max, x_p = [], [], [], [], []
    turn_delta = {}
    for k, s in enumerate(steps):
        t = turns[k]
        if k < first:
            exact_delta.append(0.0)
            exact_c.append(float("nan"))
        else:
            if t is not None and t not in turn_delta:
                turn_delta[t] = exact_delta[t]
            dt = turn_delta.get(t, 0.0)
            exact_delta.append(m.branch_delta(Q[k], None if t is None else Q[t], dt))
            exact_c.append(m.stick_radius(Q[k], None if t is None else Q[t]))
        ca, cm = radius_of(s["status"] == 1, run["area"], r)
        c_area.append(ca)
        c_max.append(cm)
        x_p.append(float(np.sum(s["fn"] * xs) / s["fn"].sum()))
    exact_delta, exact_c = np.array(exact_delta), np.array(exact_c)
    c_area, c_max = np.array(c_area), np.array(c_max)
    s_fe = delta - C_stick * Q
    s_exact = exact_delta - m.C * Q
    hist = slice(first, None)
    peak = max(abs(s_exact[hist]).max(), 1e-300)
    a_area = radius_of(steps[first - 1]["status"] > 0, run["area"], r)[0]

    width_fe, width_exact = loop_width(Q, delta, exact_delta, turns)
    pressed = steps[first - 1]
    spurious = float(np.linalg.norm(pressed["ft"], axis=1).sum() / (F * pressed["fn"].sum()))
    row = {
        "directory": directory,
        "h": mesh_size(run, m.a),
        "dofs": run["summary"].get("primal_dofs"),
        "nodes": run["summary"].get("nodes"),
        "ranks": run["summary"].get("ranks"),
        "subdomains": run["summary"].get("subdomains"),
        "steps": len(steps),
        "converged": bool(run["summary"].get("converged")) and all(s["converged"] for s in steps)
        and bool(stick["summary"].get("converged")),
        "kkt": float(max(s["kkt"] for s in steps + stick["steps"])),
        "P": P, "P_var": P_var, "F": F, "a": m.a, "a_area": a_area, "err_a": a_area / m.a - 1.0,
        "Qstar": float(Q[hist].max()), "Qstar_FP": float(Q[hist].max() / (F * P)),
        "C_stick": C_stick, "C_contact": m.C, "C_stick_raw": last["delta"] / last["Q"],
        "err_c": float(np.nanmax(np.abs(c_area - exact_c)[hist]) / m.a),
        "err_c_max": float(np.nanmax(np.abs(c_max - exact_c)[hist]) / m.a),
        "err_s": float(np.max(np.abs(s_fe - s_exact)[hist]) / peak),
        "width": width_fe, "width_exact": width_exact,
        "err_w": None if width_fe is None else width_fe / width_exact - 1.0,
        "xp_max_a": float(np.max(np.abs(x_p)) / m.a),
        "spurious": spurious,
        "xp_tipping_a": float(Q[hist].max() * RADIUS / P / m.a),
        "time_s": run["summary"].get("time_setup_s", 0.0) + run["summary"].get("time_solve_s", 0.0),
        "first": first,
        "per_step": {
            "time": [s["time"] for s in steps], "P": [s["P"] for s in steps], "Q": Q.tolist(),
            "delta": delta.tolist(), "s": s_fe.tolist(), "s_exact": s_exact.tolist(),
            "delta_exact": exact_delta.tolist(), "c": c_area.tolist(), "c_max": c_max.tolist(),
            "c_exact": exact_c.tolist(), "x_p": x_p, "turn": turns,
            "stick": [int((s["status"] == 1).sum()) for s in steps],
            "slip": [int((s["status"] == 2).sum()) for s in steps],
        },
    }
    return row


def loop_width(Q, delta, exact, turns):
    """delta_down(0) - delta_up(0) on the closed loop, FE and exact, each by
    linear interpolation between the two steps of its branch around Q = 0
    (the exact curve sampled at the same Q, so that the interpolation is not
    counted as an error); None without a down and an up branch."""
    found = {}
    for k in range(1, len(Q)):
        t = turns[k]
        if t is None or not (turns[k - 1] == t or k - 1 == t):
            continue  # not two steps of one branch after a reversal
        if (Q[k - 1] > 0) != (Q[k] > 0):
            w = Q[k - 1] / (Q[k - 1] - Q[k])
            key = "down" if Q[k] < Q[k - 1] else "up"
            if key not in found:
                found[key] = (delta[k - 1] + w * (delta[k] - delta[k - 1]), exact[k - 1] + w * (exact[k] - exact[k - 1]))
    if "down" not in found or "up" not in found:
        return None, None
    return found["down"][0] - found["up"][0], found["down"][1] - found["up"][1]


# ----------------------------------------------------------------- running


def mesh_for(level, out, order=1):
    shipped = os.path.join(ROOT, "input", "cattaneo_mindlin_%d.msh" % level)
    if os.path.exists(shipped) and order == 1:
        return shipped
    msh = os.path.join(out, "cattaneo_mindlin_%d%s.msh" % (level, "" if order == 1 else "_order%d" % order))
    if not os.path.exists(msh):
        gmsh = shutil.which("gmsh") or fail("gmsh not found (apt-get install gmsh)")
        subprocess.run([gmsh, "-3", "-order", str(order), "-format", "msh4", "-setnumber", "Level", str(level), GEO,
                        "-o", msh], check=True, stdout=subprocess.DEVNULL)
    return msh


def run(level, args, stick):
    directory = os.path.join(args.out, "level_%d%s" % (level, "_stick" if stick else ""))
    cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(args.np), args.tribos, INPUT,
           "--set", "Mesh/File=" + mesh_for(level, args.out, args.order), "--output", directory, "--quiet"]
    for s in list(args.set) + (list(STICK_SETS) if stick else []):
        cmd += ["--set", s]
    return directory, timed_run(cmd, directory, level, fail)


COLUMNS = [("level", "%d"), ("h", "%.3f"), ("dofs", "%d"), ("P", "%.0f"), ("Qstar_FP", "%.3f"), ("a", "%.4f"),
           ("err_a", "%+.1f%%"), ("err_c", "%.1f%%"), ("err_c_max", "%.1f%%"), ("err_s", "%.1f%%"),
           ("err_w", "%+.1f%%"), ("xp_max_a", "%.4f"), ("spurious", "%.3f"), ("kkt", "%.1e"),
           ("wall_s", "%.0f")]


def table(rows, markdown):
    head = [k for k, _ in COLUMNS]
    if markdown:
        lines = ["| " + " | ".join(head) + " |", "|" + "---:|" * len(head)]
        lines += ["| " + " | ".join(cell(r, k, f) for k, f in COLUMNS) + " |" for r in rows]
    else:
        lines = ["  ".join("%9s" % k for k in head)]
        lines += ["  ".join("%9s" % cell(r, k, f) for k, f in COLUMNS) for r in rows]
    return "\n".join(lines)


# ----------------------------------------------------------------- picture


def plot(rows, path):
    import matplotlib

    matplotlib.use("Agg")  # files only, no display
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 2, figsize=(12.5, 10))
    (ax1, ax2), (ax3, ax4) = axes
    E, nu, F = material()
    colours = ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple"]
    for row, col in zip(rows, colours):
        ps = row["per_step"]
        first = row["first"]
        m = Mindlin(row["P"], E, nu, F)
        Q = np.array(ps["Q"])[first - 1:]
        FP = F * row["P"]
        # The loop, the bulk compliance of the mesh replaced by the stuck
        # contact's K/(8a): delta - (C_stick - K/(8a)) Q = s + K Q/(8a).
        d = (np.array(ps["s"]) + m.C * np.array(ps["Q"]))[first - 1:]
        ax1.plot(1e3 * d, Q / FP, "o", ms=4, color=col, label="level %d (h = %.2f mm)" % (row["level"], row["h"]))
        c = np.array(ps["c"])[first:] / m.a
        ax2.plot(np.arange(first, len(ps["c"])) + 1, c, "o", ms=4, color=col, label="level %d" % row["level"])
    # The exact loop and stick radius along the finest level's history.
    fine = rows[-1]
    ps, first = fine["per_step"], fine["first"]
    m = Mindlin(fine["P"], E, nu, F)
    FP = F * fine["P"]
    Q, turns = np.array(ps["Q"]), ps["turn"]
    pieces = []
    k = first
    while k < len(Q):
        t = turns[k]
        end = k
        while end + 1 < len(Q) and turns[end + 1] == t:
            end += 1
        start_q = 0.0 if t is None else Q[t]
        pieces.append((t, start_q, Q[end]))
        k = end + 1
    for t, q0, q1 in pieces:
        qs = np.linspace(q0, q1, 200)
        ds = [m.branch_delta(q, None if t is None else Q[t], 0.0 if t is None else ps["delta_exact"][t]) for q in qs]
        ax1.plot(1e3 * np.array(ds), qs / FP, "k-", lw=1)
    ax1.plot([], [], "k-", lw=1, label="Mindlin-Deresiewicz")
    ax1.set_xlabel("tangential displacement delta [um] (bulk compliance replaced by K/(8a))")
    ax1.set_ylabel("Q / (F P)")
    ax1.set_title("force-displacement loop")
    ax1.grid(alpha=0.3)
    ax1.legend(fontsize=8)
    steps = np.arange(first, len(Q)) + 1
    ax2.plot(steps, np.array(ps["c_exact"])[first:] / m.a, "k-", lw=1, label="c/a exact (Q of the finest level)")
    ax2.set_xlabel("load step")
    ax2.set_ylabel("stick radius c / a (area-equivalent)")
    ax2.set_title("stick zone: shrinking on loading, reset on each reversal")
    ax2.grid(alpha=0.3)
    ax2.legend(fontsize=8)
    # Contact maps of the finest level: the end of loading, and Q = 0 on the way down.
    down = [k for k in range(first, len(Q)) if turns[k] is not None and turns[turns[k]] is None]
    virgin = [k for k in range(first, len(Q)) if turns[k] is None]
    peak = max(virgin, key=lambda k: Q[k])
    zero = min(down, key=lambda k: abs(Q[k])) if down else peak
    status = read_statuses(fine["directory"], (peak, zero))
    x = status["x"]
    for ax, k in ((ax3, peak), (ax4, zero)):
        st = status[k]
        for code, col, name in ((0, "lightgrey", "no contact"), (1, "tab:blue", "stick"), (2, "tab:red", "slip")):
            sel = st == code
            ax.plot(x[sel, 0], x[sel, 1], "o", ms=3, color=col, label=name)
        th = np.linspace(0, math.pi, 100)
        ax.plot(m.a * np.cos(th), m.a * np.sin(th), "k-", lw=1, label="a (Hertz)")
        cr = ps["c_exact"][k]
        ax.plot(cr * np.cos(th), cr * np.sin(th), "k--", lw=1, label="c exact")
        ax.set_aspect("equal")
        ax.set_xlim(-1.4 * m.a, 1.4 * m.a)
        ax.set_ylim(-0.05, 1.4 * m.a)
        ax.set_xlabel("x [mm]")
        ax.set_ylabel("y [mm]")
        ax.set_title("level %d, step %d: Q/(FP) = %+.2f%s" % (fine["level"], k + 1, Q[k] / FP,
                                                               " (loading)" if turns[k] is None else " (after a reversal)"))
        ax.legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    fig.savefig(path, dpi=90)
    plt.close(fig)


def read_statuses(directory, ks, base="solution"):
    import h5py

    out = {}
    for k in ks:
        with h5py.File(os.path.join(directory, "%s.step%04d.h5" % (base, k + 1)), "r") as f:
            out[k] = f["points/contact/status"][...].ravel().astype(int)
            out["x"] = f["points/contact/geometry"][...]
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("-l", "--levels", type=int, nargs="+", default=[1, 2, 3])
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--order", type=int, choices=(1, 2), default=1,
                    help="element order of the meshes: 2 makes Gmsh write Tet10 (gmsh -order 2)")
    ap.add_argument("--tribos", default=default_tribos())
    ap.add_argument("--out", default=os.path.join(ROOT, "output", "cattaneo_mindlin"))
    ap.add_argument("--table")
    ap.add_argument("--plot")
    ap.add_argument("--no-plot", action="store_true")
    ap.add_argument("--no-run", action="store_true")
    ap.add_argument("--set", action="append", default=[])
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rows = []
    for level in args.levels:
        directory = os.path.join(args.out, "level_%d" % level)
        stick_dir = directory + "_stick"
        wall = None
        if not args.no_run:
            directory, wall = run(level, args, stick=False)
            stick_dir, _ = run(level, args, stick=True)
        elif os.path.exists(os.path.join(directory, "wall_s.txt")):
            with open(os.path.join(directory, "wall_s.txt")) as f:
                wall = float(f.read())
        row = analyse(directory, stick_dir)
        row["level"], row["wall_s"] = level, wall
        rows.append(row)
    print(table(rows, markdown=False))
    if args.table:
        with open(args.table, "w") as f:
            f.write(table(rows, markdown=True) + "\n")
    with open(os.path.join(args.out, "cattaneo_mindlin.json"), "w") as f:
        json.dump(rows, f, indent=1)
    if not args.no_plot:
        plot(rows, args.plot or os.path.join(args.out, "cattaneo_mindlin.png"))
    if not all(r["converged"] for r in rows):
        fail("a run did not converge")


if __name__ == "__main__":
    main()
