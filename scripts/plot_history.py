#!/usr/bin/python3
"""Load history of a Tribos run in load steps: the friction loop of each
contact pair and the stick/slip counts over the steps, as PNG files beside
the result.

usage: scripts/plot_history.py DIR [--base NAME] [--output DIR] [--force-unit UNIT] [--length-unit UNIT]

DIR is the output directory of a run (`tribos ... --output DIR`): the summary
BASE.json with its steps (tribos_summary.py: one object per completed step
in the steps table BASE.steps.jsonl: "time",
"contact" {"nodes", "active", "stick", "slip"}, "pairs" [{"name",
"normal_force", "tangential_force", "relative_tangential_displacement",
"dissipation", "dissipated_energy"}], ...; docs/load_history_output.md).
BASE: the only summary of DIR with an index beside it, or --base. Written
(to --output, default DIR):

  BASE_load_displacement.png  per contact pair, the tangential force the
                              pair transmits (the friction force on its master
                              side: -tangential_force, the resultant on the
                              slave side; it points along the slave side's
                              motion, so that the loop rises to the right as
                              a load-displacement curve does) against its
                              relative tangential
                              displacement (relative_tangential_displacement:
                              the area-weighted mean slip of its slave nodes),
                              one point per step joined in step order: the
                              fretting loop of a load cycle, whose area is the
                              energy friction dissipates (the legend gives the
                              pair's dissipated_energy at the last step)
  BASE_stick_slip.png         the numbers of contact, stick and slip nodes
                              against the step's time

Both quantities are vectors in the contact plane; a curve draws their
components along one direction d, the line of the tangential load: the
direction of the pair's largest friction resultant over the steps (its
largest relative displacement if the friction is zero throughout), turned
so that its largest component is positive; a reversed load changes sign.
Forces are in the input's force unit (--force-unit, default N), lengths in
its length unit (--length-unit, default m). A summary written before the
pairs had their relative tangential displacement draws the mean tangential
displacement of the slave nodes instead, from the step files the index names
(their displacement, /nodes/displacement at the row the contact point set's
field `node` gives, less its part along the node's contact normal `normal`;
the field `slip` where those are missing). Only the steps the summary lists
are drawn: those are complete (the index may list one more while a step is
being written).
"""
import argparse
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tribos_summary  # noqa: E402


def fail(message):
    sys.exit("plot_history.py: " + message)


def summary_file(directory, base):
    """DIR/BASE.json: given by --base, else the only summary with an index beside it."""
    try:
        return tribos_summary.find(directory, base)
    except ValueError as e:
        fail(str(e))


def read_steps(path):
    """The summary's list of steps, each checked for what the plots need."""
    try:
        summary = tribos_summary.load(path)
    except (OSError, ValueError, KeyError) as e:
        fail("cannot read the summary %s: %s" % (path, e))
    steps = summary.get("steps")
    if not isinstance(steps, list) or not steps:
        fail("the summary %s has no list \"steps\": a result written before runs had load steps, or not a "
             "tribos summary" % path)
    for k, s in enumerate(steps, 1):
        for key in ("time", "contact"):
            if not isinstance(s, dict) or key not in s:
                fail("step %d of the summary %s has no \"%s\"" % (k, path, key))
    return steps


def data_files(index_path):
    """The data file of each step of the index, in step order, with its time:
    a temporal collection (one spatial collection per step), or the grids of
    a one-step result (time None)."""
    try:
        root = ET.parse(index_path).getroot()
    except (OSError, ET.ParseError) as e:
        fail("cannot read the index %s: %s" % (index_path, e))
    directory = os.path.dirname(index_path)

    def file_of(grid):
        item = grid.find(".//DataItem")
        if item is None or ":" not in (item.text or ""):
            fail("the index %s has a grid without a data file" % index_path)
        return os.path.join(directory, item.text.strip().split(":", 1)[0])

    domain = root.find("Domain")
    grids = [] if domain is None else domain.findall("Grid")
    series = [g for g in grids if g.get("CollectionType") == "Temporal"]
    if series:
        steps = []
        for g in series[0].findall("Grid"):
            time = g.find("Time")
            steps.append((float(time.get("Value")) if time is not None else None, file_of(g)))
        return steps
    if not grids:
        fail("the index %s names no grid" % index_path)
    return [(None, file_of(grids[0]))]


def read_contact(path):
    """The contact point set of one data file: pair index, slave node
    tangential displacement (3 per point) and status per point."""
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        fail("cannot read the data file %s: %s" % (path, e))
    with f:
        if "points/contact" not in f:
            fail("%s holds no contact point set (/points/contact): a run without contact has no load history to "
                 "draw" % path)
        c = f["points/contact"]
        n = c["geometry"].shape[0]
        pair = c["pair"][...].ravel().astype(int) if "pair" in c else np.zeros(n, dtype=int)
        status = c["status"][...].ravel().astype(int) if "status" in c else np.zeros(n, dtype=int)
        if "node" in c and "normal" in c and "nodes/displacement" in f:
            u = f["nodes/displacement"][...][c["node"][...].ravel().astype(int)]
            normal = c["normal"][...].reshape(n, 3)
            tangential = u - np.sum(u * normal, axis=1)[:, None] * normal
        elif "slip" in c:
            tangential = c["slip"][...].reshape(n, 3)
        else:
            fail("%s: the contact point set has neither node and normal nor slip" % path)
        force = c["tangential_force"][...].reshape(n, 3) if "tangential_force" in c else np.zeros((n, 3))
    return {"pair": pair, "tangential": tangential, "status": status, "tangential_force": force}


def load_history(directory, base=None):
    """Everything drawn: per step its time and contact counts; per pair its
    name and, per step, the friction resultant (3), the relative tangential
    displacement (3) and the dissipated energy so far (NaN where the summary
    has none)."""
    summary = summary_file(directory, base)
    base = os.path.basename(summary)[:-len(".json")]
    steps = read_steps(summary)
    n_pairs = max([len(s.get("pairs", [])) for s in steps] + [0])
    given = n_pairs > 0 and all(len(s.get("pairs", [])) == n_pairs and
                                all("relative_tangential_displacement" in p for p in s["pairs"]) for s in steps)
    contact = None
    if not given:
        # An older summary: the slave nodes' displacement from the step files.
        files = data_files(os.path.join(directory, base + ".xmf"))
        if len(files) < len(steps):
            fail("the summary %s lists %d steps but the index %s.xmf only %d" % (summary, len(steps), base, len(files)))
        contact = [read_contact(path) for _, path in files[:len(steps)]]
        n_pairs = max([n_pairs] + [int(c["pair"].max()) + 1 for c in contact if c["pair"].size])
    pairs = []
    for p in range(n_pairs):
        rows = [s["pairs"][p] if len(s.get("pairs", [])) > p else {} for s in steps]
        names = [r["name"] for r in rows if "name" in r]
        force, displacement = [], []
        for k, row in enumerate(rows):
            sel = None if contact is None else contact[k]["pair"] == p
            if given:
                displacement.append(np.asarray(row["relative_tangential_displacement"], dtype=float))
            else:
                displacement.append(contact[k]["tangential"][sel].mean(axis=0) if sel.any() else np.full(3, np.nan))
            # The pair's total as the summary gives it; else the nodal forces summed.
            if row.get("tangential_force") is not None:
                force.append(np.asarray(row["tangential_force"], dtype=float))
            else:
                force.append(contact[k]["tangential_force"][sel].sum(axis=0))
        energy = np.array([float(r["dissipated_energy"]) if r.get("dissipated_energy") is not None else np.nan
                           for r in rows])
        pairs.append({"name": names[0] if names else "pair %d" % p, "force": np.array(force),
                      "displacement": np.array(displacement), "dissipated_energy": energy, "relative": given})
    counts = {key: np.array([s["contact"].get(key, np.nan) for s in steps], dtype=float)
              for key in ("nodes", "active", "stick", "slip")}
    return {"base": base, "time": np.array([s["time"] for s in steps], dtype=float), "pairs": pairs,
            "counts": counts}


def curve(pair):
    """The loop of one pair along its direction: (direction, displacement, transmitted force)."""
    force, displacement = pair["force"], pair["displacement"]
    magnitude = np.linalg.norm(force, axis=1)
    source = force if np.nanmax(magnitude, initial=0) > 0 else np.nan_to_num(displacement)
    k = int(np.argmax(np.linalg.norm(source, axis=1)))
    norm = np.linalg.norm(source[k])
    direction = source[k] / norm if norm > 0 else np.array([1.0, 0.0, 0.0])
    if direction[np.argmax(np.abs(direction))] < 0:  # the same direction for a loop and its mirror image
        direction = -direction
    return direction, displacement @ direction, -(force @ direction)


def axis_labels(h, force_unit="N", length_unit="m"):
    """The labels of the loop's axes (x, y), with their units."""
    relative = all(p.get("relative", False) for p in h["pairs"])
    x = ("relative tangential displacement of the pair along d [%s]" if relative
         else "mean tangential displacement of the slave nodes along d [%s]") % length_unit
    return x, "force the pair transmits along d [%s]" % force_unit


def plot_load_displacement(h, out, force_unit="N", length_unit="m"):
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    for pair in h["pairs"]:
        d, x, y = curve(pair)
        label = "%s (d = %s)" % (pair["name"], ", ".join("%.2g" % (v if abs(v) > 1e-9 else 0.0) for v in d))
        energy = pair.get("dissipated_energy")
        if energy is not None and len(energy) and np.isfinite(energy[-1]):
            label += ", dissipated %.3g %s %s" % (energy[-1], force_unit, length_unit)
        ax.plot(x, y, "o-", markersize=3, label=label)
        if len(x) > 1:  # the way round the loop
            ax.annotate("", xy=(x[1], y[1]), xytext=(x[0], y[0]), arrowprops={"arrowstyle": "->"})
    xlabel, ylabel = axis_labels(h, force_unit, length_unit)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.axhline(0, color="0.8", linewidth=0.8)
    ax.axvline(0, color="0.8", linewidth=0.8)
    ax.set_title("%s: friction loops, %d steps" % (h["base"], len(h["time"])))
    ax.legend(fontsize="small")
    return save(fig, out, h["base"] + "_load_displacement.png")


def plot_stick_slip(h, out):
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    t = h["time"]
    for key, style in (("active", "k--"), ("stick", "b-"), ("slip", "r-")):
        label = "in contact" if key == "active" else key
        ax.plot(t, h["counts"][key], style, marker="o", markersize=3, label=label)
    ax.set_xlabel("time (load step)")
    ax.set_ylabel("contact nodes")
    ax.set_ylim(bottom=0)
    nodes = h["counts"]["nodes"]
    total = " of %d" % nodes[0] if nodes.size and np.all(nodes == nodes[0]) and np.isfinite(nodes[0]) else ""
    ax.set_title("%s: stick and slip nodes%s" % (h["base"], total))
    ax.legend(fontsize="small")
    return save(fig, out, h["base"] + "_stick_slip.png")


def save(fig, out, name):
    path = os.path.join(out, name)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    print(path)
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("directory", metavar="DIR")
    parser.add_argument("--base", help="the Base Name of the result (default: the only one in DIR)")
    parser.add_argument("--output", help="directory of the PNG files, created if needed (default: DIR)")
    parser.add_argument("--force-unit", default="N", help="the unit of force of the input (default N)")
    parser.add_argument("--length-unit", default="m", help="the unit of length of the input (default m)")
    args = parser.parse_args()
    out = args.output or args.directory
    h = load_history(args.directory, args.base)
    try:
        os.makedirs(out, exist_ok=True)  # as plot_contact.py --out
    except OSError as e:
        fail("cannot create --output %s: %s" % (out, e.strerror or e))
    if not os.access(out, os.W_OK):
        fail("--output %s is not writable" % out)
    plot_load_displacement(h, out, args.force_unit, args.length_unit)
    plot_stick_slip(h, out)


if __name__ == "__main__":
    main()
