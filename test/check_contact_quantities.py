#!/usr/bin/python3
"""What an engineer reads of a result, against closed forms and balances:

  check_contact_quantities.py --work DIR --data TEST_DATA --inputs INPUT -- MPIEXEC NPFLAG EXTRA... TRIBOS

(MPIEXEC NPFLAG: the launcher and its rank-count flag; the rank count is
inserted after NPFLAG.) docs/load_history_output.md defines each quantity.

The sliding block in a load history (TEST_DATA/load_history/sliding_block.xml,
1 rank; exact at every step: the bottom at u_x = b, the shear stress tau,
the pressure p = 1e7 on the unit contact face, Coulomb F = 0.3, G = 5e8):
  - every cell's stress tensor (xx, xy, xz, yy, yz, zz: XDMF's Tensor6, as
    the index declares it) is (0, 0, tau, 0, 0, -p), its von Mises stress sqrt(p^2 + 3 tau^2), its principal
    stresses -p/2 + r, 0, -p/2 - r with r = sqrt(p^2/4 + tau^2);
  - the reactions of the supports: "press" (0, 0, -p), "drag" (tau, 0, 0),
    "symmetry y" 0; the reaction field sums to them; with the contact force
    on the body (normal_force e_z + tangential_force) and the side
    tractions (which cancel) they balance;
  - every contact node's normal traction p and tangential traction
    (-tau, 0, 0); its slip increment b_k - b_(k-1) along x, the increments
    summing over the steps to its slip; its slip amplitude max |b| so far;
    its dissipated energy its share (its area, normal_force / p) of the
    pair's;
  - the pair's relative tangential displacement (b, 0, 0), its dissipation
    F p |b_k - b_(k-1)| (slip steps: 9e3, 9e3, 1.2e4; stick steps 0) and
    its dissipated energy, 3e4 = F N times the slip travel 0.01 at the end;
  - the summary's totals are the sums of the steps' iterations and n_A, its
    reactions and pairs the last step's;
  - restarted after step 4 (as a run killed there leaves it), the running
    quantities continue: the pairs' dissipated energy and every node's
    dissipated energy and slip amplitude at steps 5-8 are those of the
    uninterrupted run, the totals the sums of the restarted table; the same
    restart from a step 4 whose nodes' dissipated energy is set to zero in
    its file (its digest recorded anew) ends at 3e4 - 1.8e4 = 1.2e4: the
    running total is the one read back;
  - scripts/plot_history.py draws the pair's loop from the summary: the
    relative tangential displacement b and the force the pair transmits,
    tau, along x, axes with units; scripts/plot_contact.py draws a step named
    by --base BASE.stepNNNN, --step or --time (the Coulomb map included:
    the series' parameters are found), creates --out, refuses a step that
    is not there in one line.
The seed brick (INPUT/brick_linear.xml, Level 2: clamped end and support,
top traction 4e7 on 3 x 1, end traction 2e7 on 1 x 1), by TFETI (2 ranks),
FETI-1 and the monolithic solve (1 rank): the reactions sum to the applied
loads with the sign turned, (2e7, 0, 1.2e8).
The contact patch test (TEST_DATA/two_blocks_pressure.xml, mortar, Hex8 3^3
under 4^3, 1 rank): every contact node of both pairs carries the normal
traction 1e7 and no tangential traction; the lower block's ground contact
balances the pressure, the symmetry planes take nothing.
The block pressed by a prescribed displacement, by the semismooth* method
(TEST_DATA/block_displacement.xml, 1 rank): the normal traction 1e7 at every
contact node, the stress zz = -1e7 (the others 0), the reaction of the top
(0, 0, -1e7).
"""
import argparse
import hashlib
import json
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPTS = os.path.join(HERE, "..", "scripts")
sys.path.insert(0, SCRIPTS)
import tribos_summary  # noqa: E402

failures = []
BASE = "solution"

# The sliding block's history (test/data/load_history/sliding_block.xml).
P, F, DELTA = 1e7, 0.3, 0.01
TAU = np.array([0, 2, 3, 3, 1, -1, -2.5, -3]) * 1e6
B = np.array([0, 0, 3, 6, 6, 6, 6, 2]) * 1e-3
STEPS, KILLED_AFTER = len(B), 4


def check(ok, what):
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        failures.append(what)
    return ok


def tribos(args, np_, input_file, out, sets=(), extra=()):
    cmd = args.launcher[:2] + [str(np_)] + args.launcher[2:] + [input_file, "--output", out, "--quiet"] + list(extra)
    for s in sets:
        cmd += ["--set", s]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    if p.returncode != 0:
        check(False, "%s exits 0 (%d: %s)" % (" ".join(cmd), p.returncode, p.stderr.strip()[-2000:]))
    return p.returncode == 0


def summary(d):
    return tribos_summary.load(os.path.join(d, BASE + ".json"))


def step_file(d, k):
    return os.path.join(d, "%s.step%04d.h5" % (BASE, k))


def read(path):
    with h5py.File(path, "r") as f:
        out = {"stress": f["cells/stress"][...], "von_mises": f["cells/von_mises"][...].ravel(),
               "principal": f["cells/principal_stress"][...], "reaction": f["nodes/reaction"][...]}
        if "points/contact" in f:
            c = f["points/contact"]
            for name in ("normal_force", "normal_traction", "tangential_force", "tangential_traction", "slip",
                         "slip_increment", "slip_amplitude", "dissipated_energy", "node", "pair"):
                out[name] = c[name][...]
                if out[name].shape[1] == 1:
                    out[name] = out[name].ravel()
    return out


def attribute_types(xmf):
    """Every attribute name of an XDMF index with the set of its AttributeTypes."""
    types = {}
    for a in ET.parse(xmf).iter("Attribute"):
        types.setdefault(a.get("Name"), set()).add(a.get("AttributeType"))
    return types


def worst(a, b):
    return float(np.max(np.abs(np.asarray(a, dtype=float) - np.asarray(b, dtype=float)), initial=0.0))


def reactions(row):
    return {r["name"]: np.array(r["force"], dtype=float) for r in row["reactions"]}


def digest(path):
    with open(path, "rb") as f:
        return hashlib.sha256(f.read()).hexdigest()


# ---------------------------------------------------------------------------
# The sliding block


def check_sliding_block(d, what):
    s = summary(d)
    rows = s["steps"]
    if not check(len(rows) == STEPS and all(r["converged"] for r in rows), "%s: %d steps, converged" % (what, STEPS)):
        return
    force_tol, length_tol, energy_tol = 1e-8 * P, 1e-8 * DELTA, 1e-8 * F * P * DELTA
    e_stress = e_reaction = e_balance = e_traction = e_increment = e_amplitude = e_share = e_pair = 0.0
    e_field = e_motion = 0.0
    energy_so_far, amplitude = 0.0, 0.0
    slip_sum = None
    for k, row in enumerate(rows):
        tau, b = TAU[k], B[k]
        db = b - (B[k - 1] if k else 0.0)
        energy_so_far += F * P * abs(db)
        amplitude = max(amplitude, abs(b))
        r = read(step_file(d, k + 1))
        # The uniform stress state and what is derived from it.
        exact = np.array([0, 0, tau, 0, 0, -P])
        radius = np.sqrt(P * P / 4 + tau * tau)
        e_stress = max(e_stress, worst(r["stress"], exact[None, :]),
                       worst(r["von_mises"], np.sqrt(P * P + 3 * tau * tau)),
                       worst(r["principal"], np.array([-P / 2 + radius, 0, -P / 2 - radius])[None, :]))
        # The reactions per condition, the field, the balance.
        rea = reactions(row)
        e_reaction = max(e_reaction, worst(rea["press"], [0, 0, -P]), worst(rea["drag"], [tau, 0, 0]),
                         worst(rea["symmetry y"], [0, 0, 0]))
        e_field = max(e_field, worst(r["reaction"].sum(axis=0), sum(rea.values())))
        pair = row["pairs"][0]
        contact_on_body = np.array(pair["tangential_force"]) + np.array([0, 0, pair["normal_force"]])
        e_balance = max(e_balance, worst(sum(rea.values()) + contact_on_body, [0, 0, 0]))
        # Node by node.
        n = len(r["normal_traction"])
        e_traction = max(e_traction, worst(r["normal_traction"], P),
                         worst(r["tangential_traction"], np.tile([-tau, 0, 0], (n, 1))))
        e_increment = max(e_increment, worst(r["slip_increment"], np.tile([db, 0, 0], (n, 1))))
        slip_sum = r["slip_increment"].copy() if slip_sum is None else slip_sum + r["slip_increment"]
        e_amplitude = max(e_amplitude, worst(r["slip_amplitude"], amplitude))
        area = r["normal_force"] / P
        e_share = max(e_share, worst(r["dissipated_energy"], area * energy_so_far),
                      abs(r["dissipated_energy"].sum() - pair["dissipated_energy"]))
        # The pair.
        e_motion = max(e_motion, worst(pair["relative_tangential_displacement"], [b, 0, 0]))
        e_pair = max(e_pair, abs(pair["dissipation"] - F * P * abs(db)), abs(pair["dissipated_energy"] - energy_so_far))
    print("%s: largest deviations: stress %.3g, reactions %.3g, reaction field %.3g, balance %.3g, tractions %.3g, "
          "slip increments %.3g, amplitude %.3g, nodal energy %.3g, pair's displacement %.3g, pair's energy %.3g"
          % (what, e_stress, e_reaction, e_field, e_balance, e_traction, e_increment, e_amplitude, e_share, e_motion,
             e_pair))
    check(e_stress <= 1e-8 * P, "%s: every cell's stress tensor, von Mises and principal stresses are the exact "
                                "ones at every step (%.3g)" % (what, e_stress))
    check(e_reaction <= force_tol, "%s: the reactions of press, drag and symmetry y are (0, 0, -p), (tau, 0, 0), 0 "
                                   "at every step (%.3g)" % (what, e_reaction))
    check(e_field <= 1e-9 * P, "%s: the reaction field sums to the conditions' resultants (%.3g)" % (what, e_field))
    check(e_balance <= force_tol, "%s: the reactions and the contact force on the body balance (%.3g)"
          % (what, e_balance))
    check(e_traction <= force_tol, "%s: every contact node's traction is (-tau, 0, 0) and p (%.3g)" % (what, e_traction))
    check(e_increment <= length_tol, "%s: every node's slip increment is b_k - b_(k-1) (%.3g)" % (what, e_increment))
    last = read(step_file(d, STEPS))
    check(worst(slip_sum, last["slip"]) <= length_tol,
          "%s: the slip increments sum over the steps to the slip (%.3g)" % (what, worst(slip_sum, last["slip"])))
    check(e_amplitude <= length_tol, "%s: the slip amplitude is max |b| so far (%.3g)" % (what, e_amplitude))
    types = attribute_types(os.path.join(d, BASE + ".xmf"))
    check(types.get("stress") == {"Tensor6"} and types.get("master_node") == {"Matrix"} and
          types.get("displacement") == {"Vector"} and types.get("von_mises") == {"Scalar"},
          "%s: the index declares stress a Tensor6, master_node a Matrix, displacement a Vector, von_mises a "
          "Scalar (%s)" % (what, {k: sorted(v) for k, v in types.items()}))
    check(e_share <= energy_tol, "%s: every node's dissipated energy is its area's share of the pair's (%.3g)"
          % (what, e_share))
    check(e_motion <= length_tol, "%s: the pair's relative tangential displacement is (b, 0, 0) (%.3g)"
          % (what, e_motion))
    check(e_pair <= energy_tol, "%s: the pair's dissipation is F p |b_k - b_(k-1)|, its dissipated energy their sum "
                                "(%.3g)" % (what, e_pair))
    total = rows[-1]["pairs"][0]["dissipated_energy"]
    travel = np.abs(np.diff(np.concatenate([[0.0], B]))).sum()
    check(abs(total - F * P * travel) <= energy_tol,
          "%s: the dissipated energy %.10g is F N times the slip travel %g, %g" % (what, total, travel, F * P * travel))
    check(s["n_A_total"] == sum(r["n_A"] for r in rows) and
          s["outer_iterations_total"] == sum(r["iterations"] for r in rows),
          "%s: the summary's totals n_A %d and iterations %d are the sums of the steps'"
          % (what, s["n_A_total"], s["outer_iterations_total"]))
    check(s["reactions"] == rows[-1]["reactions"] and s["pairs"] == rows[-1]["pairs"],
          "%s: the summary's reactions and pairs are the last step's" % what)


def killed_copy(full, d, k):
    """The uninterrupted result as a run killed after step k leaves it."""
    shutil.rmtree(d, ignore_errors=True)
    shutil.copytree(full, d)
    path = os.path.join(d, BASE + ".json")
    with open(path) as f:
        s = json.load(f)
    s["steps_completed"] = k
    with open(path, "w") as f:
        json.dump(s, f, indent=2)
    for step in range(k + 1, STEPS + 1):
        os.remove(step_file(d, step))


def check_restart(args, block, full, work):
    d = os.path.join(work, "sliding_block_restarted")
    killed_copy(full, d, KILLED_AFTER)
    if not tribos(args, 1, block, d, extra=["--restart", d]):
        return
    s, ref = summary(d), summary(full)
    energies = [r["pairs"][0]["dissipated_energy"] for r in s["steps"]]
    ref_energies = [r["pairs"][0]["dissipated_energy"] for r in ref["steps"]]
    check(worst(energies, ref_energies) <= 1e-8 * F * P * DELTA,
          "restart after step %d: the pair's dissipated energy continues as in the uninterrupted run (%s)"
          % (KILLED_AFTER, ", ".join("%g" % e for e in energies)))
    deviation = 0.0
    for k in range(KILLED_AFTER + 1, STEPS + 1):
        a, b = read(step_file(d, k)), read(step_file(full, k))
        deviation = max(deviation, worst(a["dissipated_energy"], b["dissipated_energy"]) / (F * P * DELTA),
                        worst(a["slip_amplitude"], b["slip_amplitude"]) / DELTA)
    check(deviation <= 1e-8, "restart: every node's dissipated energy and slip amplitude at steps %d-%d are the "
                             "uninterrupted run's (%.3g relative)" % (KILLED_AFTER + 1, STEPS, deviation))
    check(s["n_A_total"] == sum(r["n_A"] for r in s["steps"]) and
          s["outer_iterations_total"] == sum(r["iterations"] for r in s["steps"]),
          "restart: the totals are the sums over the whole table, the steps before the restart included")
    # The running total is the one read back from the last step's file.
    z = os.path.join(work, "sliding_block_restarted_zeroed")
    killed_copy(full, z, KILLED_AFTER)
    with h5py.File(step_file(z, KILLED_AFTER), "r+") as f:
        f["points/contact/dissipated_energy"][...] = 0.0
    table = os.path.join(z, BASE + ".steps.jsonl")
    with open(table) as f:
        rows = [json.loads(line) for line in f]
    rows[KILLED_AFTER - 1]["sha256"] = digest(step_file(z, KILLED_AFTER))
    with open(table, "w") as f:
        f.write("".join(json.dumps(r) + "\n" for r in rows))
    if tribos(args, 1, block, z, extra=["--restart", z]):
        end = summary(z)["steps"][-1]["pairs"][0]["dissipated_energy"]
        expected = F * P * (np.abs(np.diff(B[KILLED_AFTER - 1:])).sum())
        check(abs(end - expected) <= 1e-8 * F * P * DELTA,
              "restart from a step whose dissipated energy reads 0: it ends at %.10g, the energy of steps %d-%d, "
              "%g" % (end, KILLED_AFTER + 1, STEPS, expected))


def refusal(call):
    """The message a script's call ends with (sys.exit), None when it ends normally."""
    try:
        call()
    except SystemExit as e:
        return str(e.code)
    return None


def check_plots(d, work):
    """The scripts called in this process (one import of matplotlib)."""
    import plot_contact
    import plot_history
    h = plot_history.load_history(d)
    direction, x, y = plot_history.curve(h["pairs"][0])
    check(worst(direction, [1, 0, 0]) <= 1e-8 and worst(x, B) <= 1e-8 * DELTA and worst(y, TAU) <= 1e-8 * P,
          "plot_history: the loop of the pair along x is (b, tau) at every step, from the summary")
    xlabel, ylabel = plot_history.axis_labels(h, "N", "m")
    check("relative tangential displacement" in xlabel and xlabel.endswith("[m]") and
          "force the pair transmits" in ylabel and ylabel.endswith("[N]"),
          "plot_history: the axes say what they draw and their units (%s; %s)" % (xlabel, ylabel))
    maps = os.path.join(work, "maps")
    shutil.rmtree(maps, ignore_errors=True)
    os.makedirs(maps)
    path = plot_history.plot_load_displacement(h, maps)
    check(os.path.getsize(path) > 0, "plot_history draws the loop")

    def contact(*options):
        sys.argv = ["plot_contact.py", d] + list(options)
        return refusal(plot_contact.main)

    out = os.path.join(maps, "new")
    message = contact("--base", BASE + ".step0003", "--out", out)
    names = ["%s.step0003_contact_%s.png" % (BASE, m) for m in ("pressure", "status", "ratio")]
    check(message is None and all(os.path.exists(os.path.join(out, n)) for n in names),
          "plot_contact --base %s.step0003 finds the series' parameters (Coulomb: the ratio map too) and creates "
          "--out (%s)" % (BASE, message))
    message = contact("--time", "5", "--out", out)
    check(message is None and os.path.exists(os.path.join(out, "%s.step0005_contact_ratio.png" % BASE)),
          "plot_contact --time 5 draws step 5 (%s)" % message)
    message = contact("--step", "9", "--out", out)
    check(message is not None and "steps 1 to 8" in message, "plot_contact --step 9 refused in words (%s)" % message)
    message = contact("--out", "/proc/no/such/directory")
    check(message is not None and "cannot create --out" in message,
          "plot_contact: an --out it cannot create refused in words (%s)" % message)


# ---------------------------------------------------------------------------
# Static results


def check_brick(args, work):
    brick = os.path.join(args.inputs, "brick_linear.xml")
    applied = np.array([-2e7, 0, -4e7 * 3])  # end traction on 1 x 1, top traction on 3 x 1
    for name, np_, sets in (("TFETI", 2, []), ("FETI-1", 1, ["Solver/FETI/Formulation=FETI-1"]),
                            ("Monolithic", 1, ["Solver/Type=Monolithic"])):
        d = os.path.join(work, "brick_" + name)
        if not tribos(args, np_, brick, d, ["Mesh/Level=2"] + sets):
            continue
        s = summary(d)
        total = sum(reactions(s).values())
        field = read(os.path.join(d, BASE + ".h5"))["reaction"].sum(axis=0)
        check(worst(total, -applied) <= 1e-8 * 1.2e8 and worst(field, total) <= 1e-9 * 1.2e8,
              "brick by %s: the reactions (%s) sum to the applied loads with the sign turned, (2e7, 0, 1.2e8) "
              "(%.3g)" % (name, ", ".join("%s %s" % (r["name"], r["force"]) for r in s["reactions"]),
                          worst(total, -applied)))


def check_patch(args, work):
    d = os.path.join(work, "patch")
    if not tribos(args, 1, os.path.join(args.data, "two_blocks_pressure.xml"), d,
                  ["Mesh/File=../../input/two_blocks.geo", "Contact/Pairs/interface/Discretization=Mortar",
                   "Solver/Algorithm 1/SMALBE/Relative Tolerance=1e-10"]):
        return
    r = read(os.path.join(d, BASE + ".h5"))
    error = worst(r["normal_traction"], P) / P
    check(error <= 1e-8 and worst(r["tangential_traction"], 0) <= 1e-8 * P,
          "patch test: the %d contact nodes of both pairs carry the normal traction 1e7 (%.3g relative), no "
          "tangential traction" % (len(r["normal_traction"]), error))
    s = summary(d)
    ground = [p for p in s["pairs"] if p["name"] == "ground"][0]
    total = sum(reactions(s).values()) + np.array([0, 0, ground["normal_force"]]) + np.array([0, 0, -P])
    check(worst(total, 0) <= 1e-8 * P, "patch test: the ground balances the pressure, the symmetry planes take "
                                       "nothing (%.3g)" % worst(total, 0))


def check_semismooth(args, work):
    d = os.path.join(work, "semismooth")
    if not tribos(args, 1, os.path.join(args.data, "block_displacement.xml"), d,
                  ["Solver/Outer Algorithm=SemismoothStarNewton"]):
        return
    r, s = read(os.path.join(d, BASE + ".h5")), summary(d)
    check(worst(r["normal_traction"], P) <= 1e-8 * P,
          "semismooth*: every contact node's normal traction is 1e7 (%.3g)" % worst(r["normal_traction"], P))
    check(worst(r["stress"], np.array([0, 0, 0, 0, 0, -P])[None, :]) <= 1e-8 * P and
          worst(r["principal"], np.array([0, 0, -P])[None, :]) <= 1e-8 * P and worst(r["von_mises"], P) <= 1e-8 * P,
          "semismooth*: the stress of the uniaxial state (zz = -1e7), von Mises 1e7")
    rea = reactions(s)
    check(worst(rea["press"], [0, 0, -P]) <= 1e-8 * P and
          worst(rea["symmetry x"], 0) <= 1e-8 * P and worst(rea["symmetry y"], 0) <= 1e-8 * P,
          "semismooth*: the top's reaction is (0, 0, -1e7), the symmetry planes' 0")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--work", required=True)
    parser.add_argument("--data", required=True, help="test/data")
    parser.add_argument("--inputs", required=True, help="input/")
    parser.add_argument("launcher", nargs=argparse.REMAINDER)
    args = parser.parse_args()
    if args.launcher[:1] == ["--"]:
        args.launcher = args.launcher[1:]
    os.makedirs(args.work, exist_ok=True)
    # Relative mesh paths of the inputs are read from their directory.
    args.data, args.inputs = os.path.abspath(args.data), os.path.abspath(args.inputs)

    block = os.path.join(args.data, "load_history", "sliding_block.xml")
    full = os.path.join(args.work, "sliding_block")
    if tribos(args, 1, block, full):
        check_sliding_block(full, "sliding block")
        check_restart(args, block, full, args.work)
        check_plots(full, args.work)
    check_brick(args, args.work)
    check_patch(args, args.work)
    check_semismooth(args, args.work)
    if failures:
        sys.exit("%d check(s) failed:\n  %s" % (len(failures), "\n  ".join(failures)))
    print("all checks passed")


if __name__ == "__main__":
    main()
