#!/usr/bin/python3
"""The energies and the contact force of a Dynamics run against time, as a
PNG (docs/dynamics.md).

usage: scripts/plot_dynamics.py DIR [--base NAME] [--out FILE.png] [--check]

DIR is the output directory of a run with Dynamics/Enabled: its summary
BASE.json and steps table BASE.steps.jsonl, whose rows carry "time" and
"dynamics" {"kinetic_energy", "strain_energy", "external_work",
"friction_dissipation", "contact_force"} (scripts/tribos_summary.py reads
them). BASE: the only summary of DIR beside an index, or --base. Written to
--out (default DIR/BASE_dynamics.png), two panels over time:

  energies       kinetic, strain, their sum, the work of the loads and the
                 energy friction dissipated since t = 0; and the balance
                 kinetic + strain + dissipated - work, which stays at the
                 initial kinetic energy but for what the scheme dissipates
                 at contact
  contact force  the resultant of the normal contact forces, the mean over
                 each step

--check: exit 1 unless every step has its figures and the figure was written.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tribos_summary  # noqa: E402


def fail(message):
    sys.exit("plot_dynamics.py: " + message)


def summary_path(directory, base):
    try:
        return tribos_summary.find(directory, base)
    except ValueError as e:
        fail(str(e))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("directory")
    ap.add_argument("--base")
    ap.add_argument("--out")
    ap.add_argument("--check", action="store_true")
    a = ap.parse_args()
    path = summary_path(a.directory, a.base)
    try:
        steps = tribos_summary.load(path)["steps"]
    except (OSError, ValueError, KeyError) as e:
        fail("cannot read the summary %s: %s" % (path, e))
    rows = [s for s in steps if isinstance(s.get("dynamics"), dict)]
    if not rows or len(rows) != len(steps):
        fail("%s: %d of its %d steps carry Dynamics figures; is it a Dynamics run?" % (path, len(rows), len(steps)))
    t = [s["time"] for s in rows]
    d = [s["dynamics"] for s in rows]
    kinetic = [x["kinetic_energy"] for x in d]
    strain = [x["strain_energy"] for x in d]
    work = [x["external_work"] for x in d]
    dissipated = [x["friction_dissipation"] for x in d]
    balance = [k + e + q - w for k, e, q, w in zip(kinetic, strain, dissipated, work)]
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(8, 7))
    top.plot(t, kinetic, label="kinetic")
    top.plot(t, strain, label="strain")
    top.plot(t, [k + e for k, e in zip(kinetic, strain)], label="kinetic + strain")
    top.plot(t, work, label="work of the loads")
    top.plot(t, dissipated, label="dissipated by friction")
    top.plot(t, balance, "k--", label="kinetic + strain + dissipated - work")
    top.set_ylabel("energy [J]")
    top.legend(fontsize="small")
    top.grid(alpha=0.3)
    bottom.plot(t, [x["contact_force"] for x in d], drawstyle="steps-pre")
    bottom.set_ylabel("contact force [N]")
    bottom.set_xlabel("time [s]")
    bottom.grid(alpha=0.3)
    fig.suptitle(os.path.basename(path)[:-len(".json")] + ": energies and contact force")
    out = a.out or path[:-len(".json")] + "_dynamics.png"
    fig.savefig(out, dpi=120)
    print(out)
    if a.check and not (os.path.exists(out) and os.path.getsize(out) > 0):
        fail("%s was not written" % out)


if __name__ == "__main__":
    main()
