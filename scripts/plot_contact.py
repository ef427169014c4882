#!/usr/bin/python3
"""Contact-face maps of a Tribos result, as PNG files beside it.

usage: scripts/plot_contact.py DIR [--base NAME] [--out DIR]

DIR is the output directory of a run (`tribos ... --output DIR`); the result
is DIR/NAME.h5 with DIR/NAME.parameters.xml (NAME: the only *.h5 of DIR, or
--base). Written, for the contact surface of the result:

  NAME_contact_pressure.png  normal pressure p = normal force / nodal area [Pa]
  NAME_contact_status.png    no contact / stick / slip per node, the tangential displacement as arrows
  NAME_contact_ratio.png     Coulomb: |t_T| / (F t_N) (1 on the slip zone)

The nodal area of a contact node is its share of the contact face: the
boundary facets of the mesh in the plane of the contact points, each facet's
area split equally among its nodes (what the solver's slip bounds use for a
planar face). The face is drawn in its own plane
(coordinates along two orthonormal in-plane directions), so any plane
orientation works.
"""
import argparse
import glob
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.tri as mtri  # noqa: E402

# Faces of a cell by local node index, in Tribos' (VTK) ordering.
HEX_FACES = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
TET_FACES = [(0, 2, 1), (0, 1, 3), (1, 2, 3), (0, 3, 2)]


def fail(message):
    sys.exit("plot_contact.py: " + message)


def parameter(root, path):
    """The value of Sublist/.../Name in a Tribos parameter file, or None."""
    node = root
    for part in path.split("/")[:-1]:
        node = next((c for c in node if c.tag == "ParameterList" and c.get("name") == part), None)
        if node is None:
            return None
    name = path.split("/")[-1]
    p = next((c for c in node if c.tag == "Parameter" and c.get("name") == name), None)
    return None if p is None else p.get("value")


def read_result(directory, base):
    if base is None:
        found = sorted(glob.glob(os.path.join(directory, "*.h5")))
        if len(found) != 1:
            fail("%s holds %d result files (*.h5); name one with --base" % (directory, len(found)))
        base = os.path.splitext(os.path.basename(found[0]))[0]
    h5 = os.path.join(directory, base + ".h5")
    if not os.path.exists(h5):
        fail("no result %s" % h5)
    with h5py.File(h5, "r") as f:
        if "points/contact/geometry" not in f:
            fail("%s has no contact points (a problem without contact)" % h5)
        r = {
            "coords": f["mesh/geometry"][...],
            "cells": f["mesh/topology"][...].astype(int),
            "x": f["points/contact/geometry"][...],
            "normal_force": f["points/contact/normal_force"][...].ravel(),
            "tangential_force": f["points/contact/tangential_force"][...],
            "slip": f["points/contact/slip"][...],
            "status": f["points/contact/status"][...].ravel().astype(int),
        }
    r["law"], r["F"] = "Frictionless", 0.0
    params = os.path.join(directory, base + ".parameters.xml")
    if os.path.exists(params):
        root = ET.parse(params).getroot()
        r["law"] = parameter(root, "Contact/Friction Law") or r["law"]
        r["F"] = float(parameter(root, "Contact/Friction Coefficient") or 0.0)
    return base, r


def contact_index(r):
    """For each mesh node, its index among the contact points (-1: none).
    Contact points are mesh nodes: they are matched by coordinates."""
    coords = r["coords"]
    scale = max(np.ptp(coords, axis=0).max(), 1e-300)
    key = lambda p: tuple(np.round(p / scale, 9))  # noqa: E731
    index = {key(p): i for i, p in enumerate(r["x"])}
    return np.array([index.get(key(p), -1) for p in coords])


def face_facets(r):
    """The boundary facets of the mesh that lie in the plane of the contact
    points (mesh node ids): the whole contact face, including the facets
    at nodes that a Dirichlet condition takes out of the contact set."""
    coords, cells, x = r["coords"], r["cells"], r["x"]
    centre = x.mean(axis=0)
    normal = np.linalg.svd(x - centre)[2][2]
    tol = 1e-9 * max(np.ptp(coords, axis=0).max(), 1e-300)
    on_plane = np.abs((coords - centre) @ normal) <= tol
    faces = HEX_FACES if cells.shape[1] == 8 else TET_FACES
    count = {}
    for cell in cells:
        for face in faces:
            nodes = cell[list(face)]
            if on_plane[nodes].all():
                k = tuple(sorted(nodes))
                count[k] = (count.get(k, (0, None))[0] + 1, list(nodes))
    return [nodes for n, nodes in count.values() if n == 1]


def plane_frame(x):
    """Two orthonormal in-plane directions of the contact points and their
    axis labels: the two other coordinate axes when the plane is normal to
    one (so the map shows the model's own coordinates), else the principal
    directions of the points."""
    centre = x.mean(axis=0)
    _, _, vt = np.linalg.svd(x - centre)
    normal = vt[2]
    axis = int(np.argmax(np.abs(normal)))
    if abs(normal[axis]) > 1 - 1e-9:
        a, b = [k for k in range(3) if k != axis]
        e = np.eye(3)
        return e[a], e[b], "xyz"[a] + " [m]", "xyz"[b] + " [m]"
    return vt[0], vt[1], "in-plane coordinate 1 [m]", "in-plane coordinate 2 [m]"


def nodal_areas(coords, facets):
    """Each facet's area split equally among its nodes (per mesh node)."""
    area = np.zeros(len(coords))
    for f in facets:
        p = coords[f]
        # Area of a planar polygon: half the norm of the summed cross products.
        s = np.zeros(3)
        for i in range(len(f)):
            s += np.cross(p[i] - p[0], p[(i + 1) % len(f)] - p[0])
        area[f] += 0.5 * np.linalg.norm(s) / len(f)
    return area


def contact_areas(r):
    """The contact face's facets (mesh ids), the nodal area of every contact
    point, and the facets drawn (those whose nodes are all contact points,
    in contact indices)."""
    facets = face_facets(r)
    index = contact_index(r)
    area = np.zeros(len(r["x"]))
    mesh_area = nodal_areas(r["coords"], facets)
    area[index[index >= 0]] = mesh_area[index >= 0]
    drawn = [list(index[f]) for f in facets if (index[f] >= 0).all()]
    return facets, area, drawn


def triangulation(u, v, facets):
    tris = []
    for f in facets:
        for i in range(1, len(f) - 1):  # fan: quads become two triangles
            tris.append([f[0], f[i], f[i + 1]])
    return mtri.Triangulation(u, v, np.array(tris))


def figure(title, u, v, labels):
    fig, ax = plt.subplots(figsize=(7.5, 4.5 * max(0.5, min(2.0, np.ptp(v) / max(np.ptp(u), 1e-300))) + 1.0))
    ax.set_aspect("equal")
    ax.set_title(title, loc="left")
    ax.set_xlabel(labels[0])
    ax.set_ylabel(labels[1])
    return fig, ax


def plot(directory, base, r, out):
    x = r["x"]
    _, area, facets = contact_areas(r)
    if not facets:
        fail("no mesh facet lies in the contact set; cannot draw the contact face")
    pressure = np.where(area > 0, r["normal_force"] / np.maximum(area, 1e-300), 0.0)
    e1, e2, l1, l2 = plane_frame(x)
    labels = (l1, l2)
    u, v = x @ e1, x @ e2
    tri = triangulation(u, v, facets)
    written = []

    fig, ax = figure("Normal contact pressure", u, v, labels)
    m = ax.tripcolor(tri, pressure, shading="gouraud", cmap="viridis")
    fig.colorbar(m, ax=ax, label="normal pressure [Pa]")
    written.append(save(fig, out, base + "_contact_pressure.png"))

    fig, ax = figure("Contact status (arrows: tangential displacement)", u, v, labels)
    colours = {0: ("lightgrey", "no contact"), 1: ("tab:blue", "stick"), 2: ("tab:orange", "slip")}
    for s, (c, label) in colours.items():
        sel = r["status"] == s
        ax.scatter(u[sel], v[sel], c=c, s=18, label="%s (%d)" % (label, sel.sum()), zorder=2)
    su, sv = r["slip"] @ e1, r["slip"] @ e2
    longest = float(np.hypot(su, sv).max())
    if longest > 0:
        # The largest slip drawn as 8 % of the face's extent.
        scale = longest / (0.08 * max(np.ptp(u), np.ptp(v)))
        q = ax.quiver(u, v, su, sv, color="black", zorder=3, width=0.003, angles="xy", scale_units="xy", scale=scale)
        ax.quiverkey(q, 0.75, 1.06, longest, "largest %.2e m" % longest, labelpos="E", fontproperties={"size": 8})
    ax.triplot(tri, color="0.85", lw=0.5, zorder=1)
    ax.legend(loc="upper right", fontsize=8)
    written.append(save(fig, out, base + "_contact_status.png"))

    if r["law"] == "Coulomb" and r["F"] > 0:
        tN = r["normal_force"]
        tT = np.linalg.norm(r["tangential_force"], axis=1)
        ratio = np.where(tN > 1e-12 * max(tN.max(), 1e-300), tT / (r["F"] * np.maximum(tN, 1e-300)), np.nan)
        fig, ax = figure("Coulomb: |t_T| / (F t_N)   (F = %g; 1 on the slip zone)" % r["F"], u, v, labels)
        m = ax.tripcolor(tri, np.nan_to_num(ratio, nan=0.0), shading="gouraud", cmap="magma", vmin=0.0, vmax=1.0)
        fig.colorbar(m, ax=ax, label="|t_T| / (F t_N)  (0 where no contact)")
        written.append(save(fig, out, base + "_contact_ratio.png"))
    return written


def save(fig, out, name):
    path = os.path.join(out, name)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("directory")
    ap.add_argument("--base", help="result name (default: the only *.h5 of the directory)")
    ap.add_argument("--out", help="where the PNGs go (default: the result's directory)")
    a = ap.parse_args()
    if not os.path.isdir(a.directory):
        fail("%s is not a directory" % a.directory)
    base, r = read_result(a.directory, a.base)
    for path in plot(a.directory, base, r, a.out or a.directory):
        print(path)


if __name__ == "__main__":
    main()
