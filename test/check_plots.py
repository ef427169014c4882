#!/usr/bin/python3
"""The contact maps of scripts/plot_contact.py on a real result:

  check_plots.py --out DIR --face-area A -- COMMAND ...   (COMMAND: a tribos run writing to DIR)
  check_plots.py --out DIR --pair NAME=A [--pair NAME=A ...] -- COMMAND ...

Runs the command, draws the maps, and checks that
  - the three PNGs (per contact pair NAME with --pair) exist, are images of
    the expected size and are not blank;
  - the nodal areas of the surface drawn partition the contact face
    (they sum to its area A; per pair: the slave surface of that pair) and
    the pressure is positive where the written status says contact;
  - the pictures follow the data: the result with the normal forces of one
    half of the face set to zero and the status flipped gives different
    images (the pixels change), not a golden image compared to itself.
"""
import argparse
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPT = os.path.join(HERE, "..", "scripts", "plot_contact.py")
sys.path.insert(0, os.path.join(HERE, "..", "scripts"))
import plot_contact  # noqa: E402

NAMES = ["_contact_pressure.png", "_contact_status.png", "_contact_ratio.png"]
failures = []


def check(ok, what):
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        failures.append(what)


def picture_names(pairs):
    """The maps plot_contact.py writes: one set, or one set per pair."""
    if not pairs:
        return ["solution" + n for n in NAMES]
    return ["solution_contact_%s_%s" % (p, n[len("_contact_"):]) for p in pairs for n in NAMES]


def draw(directory, pairs):
    out = subprocess.run([sys.executable, SCRIPT, directory], capture_output=True, text=True)
    check(out.returncode == 0, "plot_contact.py %s exits 0 (%s)" % (directory, out.stderr.strip()))
    return [os.path.join(directory, n) for n in picture_names(pairs)]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", required=True)
    ap.add_argument("--face-area", type=float, help="area of the contact face (one surface)")
    ap.add_argument("--pair", action="append", default=[], help="NAME=A: a contact pair and its slave surface's area")
    ap.add_argument("command", nargs=argparse.REMAINDER)
    a = ap.parse_args()
    command = a.command[1:] if a.command[:1] == ["--"] else a.command
    pairs = dict((p.split("=")[0], float(p.split("=")[1])) for p in a.pair)
    if (a.face_area is None) == (not pairs):
        ap.error("give either --face-area or --pair")
    shutil.rmtree(a.out, ignore_errors=True)
    run = subprocess.run(command, capture_output=True, text=True)
    check(run.returncode == 0, "the run converged (exit %d)" % run.returncode)
    if run.returncode != 0:
        print(run.stderr)
        return 1

    pictures = draw(a.out, list(pairs))
    images = []
    for p in pictures:
        exists = os.path.exists(p) and os.path.getsize(p) > 5000
        check(exists, "%s written" % os.path.basename(p))
        if exists:
            img = mpimg.imread(p)
            images.append(img)
            check(img.ndim == 3 and img.shape[0] > 200 and img.shape[1] > 400, "%s is an image %s" % (os.path.basename(p), img.shape))
            check(float(img[..., :3].std()) > 0.05, "%s is not blank (pixel std %.3f)" % (os.path.basename(p), img[..., :3].std()))

    base, r = plot_contact.read_result(a.out, None)
    views = {None: r} if not pairs else {v["pair_name"]: v for v in plot_contact.pair_views(r)}
    check(set(views) == set(pairs) or not pairs, "the result has the pairs %s (%s)" % (sorted(pairs), sorted(views, key=str)))
    for name, expected in (pairs.items() if pairs else [(None, a.face_area)]):
        if name not in views:
            continue
        v = views[name]
        what = "" if name is None else "pair %s: " % name
        facets, area, _ = plot_contact.contact_areas(v)
        face = plot_contact.nodal_areas(v["coords"], facets).sum()
        pressure = v["normal_force"] / np.maximum(area, 1e-300)
        check(abs(face - expected) <= 1e-12 * expected,
              "%sthe facets found make up the contact face (area %.15g, expected %g)" % (what, face, expected))
        check(bool((area > 0).all()), "%severy contact node has a share of the face" % what)
        check(bool((pressure[v["status"] > 0] > 0).all()), "%spositive pressure wherever the status says contact" % what)

    # The same result with other data: the pictures must change.
    other = a.out + "_changed"
    shutil.rmtree(other, ignore_errors=True)
    shutil.copytree(a.out, other)
    for n in picture_names(list(pairs)):
        if os.path.exists(os.path.join(other, n)):
            os.remove(os.path.join(other, n))
    with h5py.File(os.path.join(other, "solution.h5"), "r+") as f:
        x = f["points/contact/geometry"][...]
        half = x[:, 0] > np.median(x[:, 0])
        # The pressure drawn is the written normal traction (normal_force
        # over the node's area): both changed alike.
        for name in ("normal_force", "normal_traction"):
            fn = f["points/contact/" + name]
            data = fn[...]
            data[half.reshape(data.shape[0], -1)[:, 0]] = 0.0
            fn[...] = data
        st = f["points/contact/status"]
        s = st[...]
        s[s > 0] = 3 - s[s > 0]  # stick <-> slip
        st[...] = s
    changed = draw(other, list(pairs))
    for p, q in zip(pictures, changed):
        if os.path.exists(p) and os.path.exists(q):
            before, after = mpimg.imread(p)[..., :3], mpimg.imread(q)[..., :3]
            # A legend or colour bar that grows changes the size: a change too.
            diff = float(np.abs(before - after).mean()) if before.shape == after.shape else 1.0
            check(diff > 1e-3, "%s changes with the data (mean pixel change %.4f)" % (os.path.basename(p), diff))
    shutil.rmtree(other, ignore_errors=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
