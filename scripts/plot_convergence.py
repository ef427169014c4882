#!/usr/bin/python3
"""Convergence of Tribos runs: residuals and Hessian multiplications against
outer iterations, several runs in one figure.

usage: scripts/plot_convergence.py DIR [DIR ...] [--label TEXT ...] [--base NAME]
                                   [--out FILE.png] [--title TEXT]

Each DIR is the output directory of a run (`tribos ... --output DIR`), which
holds the iteration history BASE.history.csv beside the summary BASE.json
(BASE: the only *.history.csv of DIR, or --base). Left: the residuals of
each run against its outer iterations (log scale), one colour per run:

  solid   relative_residual   ||g^P||/||b|| (contact), the projected CG or
                              monolithic residual, the semismooth* residual
  dashed  G_lambda_rel        ||G lambda||/||b|| (FETI contact)
  dotted  slip_bound_change   ||g(l+1) - g(l)||/||g|| (Coulomb)

Right: the Hessian multiplications n_A so far. An outer iteration is the
outer algorithm's own: an Algorithm 2 loop, an MSA step (each a whole Tresca
solve), a Newton step; linear solvers record their final state only (one
point). --label gives each DIR its legend entry, in order (default: the
directory name with the algorithm and the mesh level from the summary and
parameters). --out defaults to convergence.png in the first DIR.

Examples:
  # Algorithm 2 against MSA + Algorithm 1 on the brick, F = 0.3:
  scripts/plot_convergence.py output/a2 output/msa --label "Algorithm 2" --label "MSA+Algorithm1"
  # bounded n_A: Algorithm 2 at levels k = 4..12
  scripts/plot_convergence.py output/k4 output/k8 output/k12 --out docs/images/convergence.png
"""
import argparse
import csv
import glob
import json
import math
import os
import sys
import xml.etree.ElementTree as ET

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402

COLUMNS = ["outer_iteration", "relative_residual", "G_lambda_rel", "slip_bound_change", "n_A", "time_s"]
RESIDUALS = [("relative_residual", "-", "relative residual"), ("G_lambda_rel", "--", "||G lambda||/||b||"),
             ("slip_bound_change", ":", "slip-bound change")]


def fail(message):
    sys.exit("plot_convergence.py: " + message)


def history_file(directory, base):
    if not os.path.isdir(directory):
        fail("%s is not a directory" % directory)
    if base is not None:
        path = os.path.join(directory, base + ".history.csv")
        if not os.path.exists(path):
            fail("%s holds no iteration history %s.history.csv (files there: %s)"
                 % (directory, base, ", ".join(sorted(os.listdir(directory))) or "none"))
        return path
    found = sorted(glob.glob(os.path.join(directory, "*.history.csv")))
    if not found:
        fail("%s holds no iteration history (*.history.csv): not the output directory of a tribos run, or a "
             "result written before runs wrote their history; run it again" % directory)
    if len(found) > 1:
        fail("%s holds %d histories (%s); name one with --base"
             % (directory, len(found), ", ".join(os.path.basename(f) for f in found)))
    return found[0]


def read_history(path):
    """The columns of a history file as lists of floats (NaN: an empty field)."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows or rows[0][:len(COLUMNS)] != COLUMNS:
        fail("%s is not an iteration history (header %s, expected %s)"
             % (path, ",".join(rows[0]) if rows else "missing", ",".join(COLUMNS)))
    if len(rows) < 2:
        fail("%s has a header and no iteration" % path)
    data = {c: [] for c in COLUMNS}
    for line, row in enumerate(rows[1:], start=2):
        if len(row) < len(COLUMNS):
            fail("%s line %d has %d fields, expected %d" % (path, line, len(row), len(COLUMNS)))
        for c, v in zip(COLUMNS, row):
            try:
                data[c].append(float(v) if v.strip() else math.nan)
            except ValueError:
                fail("%s line %d: %s = %r is not a number" % (path, line, c, v))
    return data


def default_label(directory, path):
    """The directory's name, with the algorithm and mesh level the run used."""
    base = path[:-len(".history.csv")]
    parts = []
    try:
        with open(base + ".json") as f:
            s = json.load(f)
        parts.append(s.get("outer_algorithm") or s.get("algorithm") or "")
    except (OSError, ValueError):
        pass
    try:
        root = ET.parse(base + ".parameters.xml").getroot()
        mesh = next((c for c in root if c.tag == "ParameterList" and c.get("name") == "Mesh"), None)
        level = None if mesh is None else next(
            (c.get("value") for c in mesh if c.tag == "Parameter" and c.get("name") == "Level"), None)
        if level is not None and int(level) > 0:
            parts.append("k = %s" % level)
    except (OSError, ET.ParseError, ValueError):
        pass
    name = os.path.basename(os.path.normpath(directory))
    extra = ", ".join(p for p in parts if p)
    return "%s (%s)" % (name, extra) if extra else name


def positive(values):
    """Values for a log axis: non-positive and missing ones are not drawn."""
    return [v if v > 0 else math.nan for v in values]


def plot(runs, out, title=None):
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.6))
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    drawn_styles = set()
    for k, (label, h) in enumerate(runs):
        colour = colours[k % len(colours)]
        it = h["outer_iteration"]
        marker = "o" if len(it) == 1 else None
        first = True
        for column, style, _ in RESIDUALS:
            y = positive(h[column])
            if all(math.isnan(v) for v in y):
                continue
            left.semilogy(it, y, style, color=colour, marker=marker, label=label if first else None)
            drawn_styles.add(column)
            first = False
        if not all(math.isnan(v) for v in h["n_A"]):
            right.plot(it, h["n_A"], "-", color=colour, marker=marker if marker else ".", markersize=4,
                       label="%s: n_A = %d" % (label, h["n_A"][-1]) if not math.isnan(h["n_A"][-1]) else label)
    left.set_xlabel("outer iteration")
    left.set_ylabel("residual (relative)")
    left.set_title("Residuals", loc="left")
    left.grid(True, which="major", alpha=0.3)
    # Line styles say which residual, colours which run.
    handles, labels = left.get_legend_handles_labels()
    for column, style, name in RESIDUALS:
        if column in drawn_styles:
            handles.append(plt.Line2D([], [], color="0.3", linestyle=style))
            labels.append(name)
    left.legend(handles, labels, fontsize=8)
    right.set_xlabel("outer iteration")
    right.set_ylabel("Hessian multiplications n_A (cumulative)")
    right.set_title("Work", loc="left")
    right.grid(True, alpha=0.3)
    right.legend(fontsize=8)
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("directories", nargs="+", metavar="DIR")
    ap.add_argument("--label", action="append", default=[], help="legend entry of the next DIR (repeat, in order)")
    ap.add_argument("--base", help="result name (default: the only *.history.csv of each DIR)")
    ap.add_argument("--out", help="the PNG to write (default: DIR/convergence.png of the first DIR)")
    ap.add_argument("--title", help="title of the figure")
    a = ap.parse_args()
    if len(a.label) > len(a.directories):
        fail("%d labels for %d directories" % (len(a.label), len(a.directories)))
    runs = []
    for k, d in enumerate(a.directories):
        path = history_file(d, a.base)
        runs.append((a.label[k] if k < len(a.label) else default_label(d, path), read_history(path)))
    out = a.out or os.path.join(a.directories[0], "convergence.png")
    plot(runs, out, a.title)
    print(out)


if __name__ == "__main__":
    main()
