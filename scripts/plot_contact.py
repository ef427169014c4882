#!/usr/bin/python3
"""Contact-face maps of a Tribos result, as PNG files beside it.

usage: scripts/plot_contact.py DIR [--base NAME] [--step N | --time T] [--out DIR] [--pressure-unit UNIT]
                               [--length-unit UNIT] [--zoom]

DIR is the output directory of a run (`tribos ... --output DIR`). The result
drawn is a data file of DIR with the run's parameters file beside it
(BASE.parameters.xml, which gives each pair's friction law):

  - a run of one step: BASE.h5 (BASE: the only result of DIR, or --base);
  - a run in load steps (BASE.json with its steps table, BASE.step0001.h5,
    ...): the step --step N (1-based) or the step at time --time T, by
    default the last step the summary counts; --base BASE.stepNNNN names a
    step file directly. The series' parameters file BASE.parameters.xml
    serves every step.

A result whose parameters file is missing is drawn without the friction
map (a warning says so): its law is unknown. Written (to --out, created if
needed; default DIR), for each contact surface of the result (the slave
side of each contact pair: against a rigid plane or against another body):

  NAME_contact_pressure.png  normal pressure [Pa]: the written normal_traction
                             (the node's normal force over its area, the
                             integral of its shape function over the slave
                             surface; older results: the force over the
                             nodal area below)
  NAME_contact_status.png    no contact / stick / slip per node, and as arrows
                             the slip of the step at the slipping nodes
                             (slip_increment: the relative tangential
                             displacement of the step; older results: slip),
                             scaled so that the longest is 8 % of the map
  NAME_contact_ratio.png     Coulomb: |t_T| / (F t_N) (1 on the slip zone)

NAME is the data file's name without .h5 (BASE, or BASE.stepNNNN). A result
with several contact pairs gets one set per pair, named
NAME_contact_PAIR_pressure.png etc. (PAIR: the name of Contact/Pairs/PAIR);
a result with one contact surface keeps the names above.

The nodal area of a contact node (the maps' drawing, and the pressure of
results that have no normal_traction) is its share of the slave surface:
the boundary facets of the slave body on that surface, each facet's area
split equally among its nodes. A planar surface is found as every boundary
facet of the slave body in the plane of the pair's points (so facets at
nodes that a Dirichlet condition takes out of the contact set count too); a
curved one (a sphere) as the boundary facets whose nodes are all nodes of
the pair. The surface is drawn projected on the plane normal to the pair's
mean contact normal: in the model's coordinates when that normal is along
an axis, else along two orthonormal in-plane directions.

Pressure is force over area in the units of the input: Pa for SI inputs;
--pressure-unit and --length-unit name others (MPa and mm for a mm-N-MPa
model such as input/hertz_sphere.xml). --zoom draws only the neighbourhood of the nodes in
contact (for a small patch on a large surface, as in the Hertz problem).
"""
import argparse
import glob
import os
import re
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.tri as mtri  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tribos_summary  # noqa: E402

# Faces of a cell by local node index, in Tribos' (VTK) ordering.
HEX_FACES = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
TET_FACES = [(0, 2, 1), (0, 1, 3), (1, 2, 3), (0, 3, 2)]
# The nodes of each cell type in XDMF's Mixed topology (bodies of different
# cell types): Tet4, Hex8, Tet10, Hex20.
XDMF_MIXED_NODES = {6: 4, 9: 8, 38: 10, 48: 20}


def cell_corners(topology):
    """The corners of each cell (the first 4 or 8 of its nodes), as a list of
    arrays: from the rows of /mesh/topology, or from its Mixed list (each
    cell's type number, then its nodes)."""
    T = np.asarray(topology, dtype=int)
    if T.shape[1] > 1:
        cells = list(T)
    else:
        flat, cells, i = T.ravel(), [], 0
        while i < len(flat):
            n = XDMF_MIXED_NODES[flat[i]]
            cells.append(flat[i + 1:i + 1 + n])
            i += 1 + n
    return [c[:8] if len(c) in (8, 20) else c[:4] for c in cells]


def fail(message):
    sys.exit("plot_contact.py: " + message)


def find(node, tag, name):
    return next((c for c in node if c.tag == tag and c.get("name") == name), None)


def parameter(root, path):
    """The value of Sublist/.../Name in a Tribos parameter file, or None."""
    node = root
    for part in path.split("/")[:-1]:
        node = find(node, "ParameterList", part)
        if node is None:
            return None
    p = find(node, "Parameter", path.split("/")[-1])
    return None if p is None else p.get("value")


def read_pairs(root):
    """The contact pairs of a parameter file, in the order the solver numbers
    them (the `pair` field): name, law, F, slave surface, master (empty: a
    rigid plane). Without Contact/Pairs: the one face against the rigid plane."""
    law = parameter(root, "Contact/Friction Law") or "Frictionless"
    F = float(parameter(root, "Contact/Friction Coefficient") or 0.0)
    contact = find(root, "ParameterList", "Contact")
    pairs = None if contact is None else find(contact, "ParameterList", "Pairs")
    if pairs is None or not [c for c in pairs if c.tag == "ParameterList"]:
        return [{"name": "contact", "law": law, "F": F, "slave": parameter(root, "Contact/Face") or "", "master": ""}]
    out = []
    for p in pairs:
        if p.tag != "ParameterList":
            continue
        value = lambda key, default: next((c.get("value") for c in p if c.tag == "Parameter" and c.get("name") == key),  # noqa: E731
                                          default)
        out.append({"name": p.get("name"), "law": value("Friction Law", law),
                    "F": float(value("Friction Coefficient", F)), "slave": value("Slave Surface", ""),
                    "master": value("Master Surface", ""), "glued": value("Type", "Contact") == "Glued"})
    return out


STEP_FILE = re.compile(r"^(.*)\.step(\d{4,})$")


def summaries(directory):
    """The results of DIR that have a summary with an index beside it (BASE names)."""
    return [os.path.basename(f)[:-len(".json")] for f in sorted(glob.glob(os.path.join(directory, "*.json")))
            if os.path.exists(f[:-len(".json")] + ".xmf")]


def series_step(directory, series, step=None, time=None):
    """The data file name (without .h5) of a step of the series `series` of
    DIR: step N, the step at time T, or the last step its summary counts."""
    path = os.path.join(directory, series + ".json")
    try:
        rows = tribos_summary.load(path)["steps"]
    except (OSError, ValueError, KeyError) as e:
        fail("cannot read the summary %s with its steps: %s" % (path, e))
    if not rows:
        fail("the summary %s counts no complete step" % path)
    if step is not None:
        if not 1 <= step <= len(rows):
            fail("--step %d: the result %s has steps 1 to %d" % (step, series, len(rows)))
        row = rows[step - 1]
    elif time is not None:
        times = [float(r["time"]) for r in rows]
        found = [k for k, t in enumerate(times) if abs(t - time) <= 1e-9 * max(abs(t), abs(time), 1e-300)]
        if not found:
            fail("--time %g: the result %s has no step at that time (its steps run from t = %g to t = %g)"
                 % (time, series, times[0], times[-1]))
        row = rows[found[0]]
    else:
        row = rows[-1]
    name = row.get("file")
    if not isinstance(name, str) or not name.endswith(".h5"):
        # A summary without step files (Output/Write Results = false) or an older one.
        fail("the summary %s names no data file of step %s" % (path, row.get("step")))
    return name[:-len(".h5")]


def result_names(directory, base, step=None, time=None):
    """(data file name without .h5, the name of its series or result: the
    Base Name of its parameters file)."""
    if base is not None:
        m = STEP_FILE.match(base)
        if m and os.path.exists(os.path.join(directory, base + ".h5")):
            if step is not None or time is not None:
                fail("--base %s names one step; --step and --time choose a step of %s" % (base, m.group(1)))
            return base, m.group(1)
        if not os.path.exists(os.path.join(directory, base + ".h5")) and os.path.exists(
                os.path.join(directory, base + ".json")):
            return series_step(directory, base, step, time), base
        if step is not None or time is not None:
            fail("--step and --time choose a step of a run in load steps; %s is a result of one step" % base)
        return base, base
    found = summaries(directory)
    if len(found) == 1:
        return result_names(directory, found[0], step, time)
    if len(found) > 1:
        fail("%s holds %d results (%s); name one with --base" % (directory, len(found), ", ".join(found)))
    # No summary: the only data file.
    files = sorted(glob.glob(os.path.join(directory, "*.h5")))
    if len(files) != 1:
        fail("%s holds %d result files (*.h5) and no summary; name one with --base" % (directory, len(files)))
    name = os.path.splitext(os.path.basename(files[0]))[0]
    m = STEP_FILE.match(name)
    return name, m.group(1) if m else name


def read_result(directory, base, step=None, time=None):
    base, series = result_names(directory, base, step, time)
    h5 = os.path.join(directory, base + ".h5")
    if not os.path.exists(h5):
        fail("no result %s" % h5)
    try:
        f = h5py.File(h5, "r")
    except OSError as e:
        fail("cannot read %s: %s" % (h5, e))
    with f:
        if "points/contact/geometry" not in f:
            fail("%s has no contact points (a problem without contact)" % h5)
        c = f["points/contact"]
        n = c["geometry"].shape[0]
        r = {
            "coords": f["mesh/geometry"][...],
            "cells": cell_corners(f["mesh/topology"][...]),
            "body": f["cells/body"][...].ravel().astype(int) if "cells/body" in f else None,
            "x": c["geometry"][...],
            "normal_force": c["normal_force"][...].ravel(),
            "tangential_force": c["tangential_force"][...].reshape(n, 3),
            "slip": c["slip"][...].reshape(n, 3),
            "status": c["status"][...].ravel().astype(int),
            # Written since contact pairs exist; older results have one
            # surface and their points are matched to nodes by coordinates.
            "pair": c["pair"][...].ravel().astype(int) if "pair" in c else np.zeros(n, dtype=int),
            "node": c["node"][...].ravel().astype(int) if "node" in c else None,
            "normal": c["normal"][...].reshape(n, 3) if "normal" in c else None,
            # Written since the driver reports tractions and the slip of each step.
            "normal_traction": c["normal_traction"][...].ravel() if "normal_traction" in c else None,
            "slip_increment": c["slip_increment"][...].reshape(n, 3) if "slip_increment" in c else None,
        }
    r["pairs"] = [{"name": "contact", "law": "Frictionless", "F": 0.0, "slave": "", "master": ""}]
    params = os.path.join(directory, series + ".parameters.xml")
    if os.path.exists(params):
        try:
            r["pairs"] = read_pairs(ET.parse(params).getroot())
        except ET.ParseError as e:
            fail("cannot read the parameters %s: %s" % (params, e))
    else:
        r["pairs"][0]["law"] = "unknown"
        print("plot_contact.py: warning: no parameters file %s beside the result: its friction law is unknown, "
              "the friction map is not drawn" % params, file=sys.stderr)
    # The friction of the single-surface case, as scripts read it.
    r["law"], r["F"] = r["pairs"][0]["law"], r["pairs"][0]["F"]
    return base, r


def pair_views(r):
    """One dict per contact pair that has contact points, with the keys of r
    restricted to that pair's points, its name, law and F."""
    views = []
    for p in np.unique(r["pair"]):
        sel = r["pair"] == p
        v = dict(r)
        for key in ("x", "normal_force", "tangential_force", "slip", "status", "pair", "node", "normal",
                    "normal_traction", "slip_increment"):
            if r[key] is not None:
                v[key] = r[key][sel]
        info = r["pairs"][p] if 0 <= p < len(r["pairs"]) else {"name": "pair%d" % p, "law": r["law"], "F": r["F"],
                                                              "slave": "", "master": ""}
        v.update({"pair_index": int(p), "pair_name": info["name"], "law": info["law"], "F": info["F"],
                  "slave": info.get("slave", ""), "master": info.get("master", "")})
        views.append(v)
    return views


def contact_index(r):
    """For each mesh node, its index among the contact points (-1: none):
    the written row of each point's node, else (older results) matched by
    coordinates."""
    coords = r["coords"]
    index = -np.ones(len(coords), dtype=int)
    if r.get("node") is not None:
        index[r["node"]] = np.arange(len(r["node"]))
        return index
    scale = max(np.ptp(coords, axis=0).max(), 1e-300)
    key = lambda p: tuple(np.round(p / scale, 9))  # noqa: E731
    position = {key(p): i for i, p in enumerate(r["x"])}
    return np.array([position.get(key(p), -1) for p in coords])


def boundary_facets(cells):
    """The facets of the mesh that belong to one cell only (mesh node ids, in
    the cell's order), with that cell: tetrahedra and hexahedra apart (their
    faces differ in node count)."""
    facets, owners = [], []
    for corners, faces in ((4, TET_FACES), (8, HEX_FACES)):
        ids = np.array([i for i, c in enumerate(cells) if len(c) == corners], dtype=int)
        if not len(ids):
            continue
        local = np.array(faces)
        all_facets = np.array([cells[i] for i in ids])[:, local].reshape(-1, local.shape[1])
        owner = np.repeat(ids, len(faces))
        _, first, counts = np.unique(np.sort(all_facets, axis=1), axis=0, return_index=True, return_counts=True)
        once = first[counts == 1]
        facets += list(all_facets[once])
        owners += list(owner[once])
    return facets, np.array(owners, dtype=int)


def contact_normal(r):
    """The mean contact normal of the points (the written `normal`), else the
    normal of their best-fit plane."""
    x = r["x"]
    if r.get("normal") is not None and len(r["normal"]):
        n = r["normal"].mean(axis=0)
        if np.linalg.norm(n) > 1e-12:
            return n / np.linalg.norm(n)
    if len(x) < 3:
        return np.array([0.0, 0.0, 1.0])
    return np.linalg.svd(x - x.mean(axis=0))[2][2]


def face_facets(r):
    """The slave surface of the points (mesh node ids): boundary facets of the
    slave body, in the plane of the points when they are planar, else made of
    contact points only."""
    coords, cells, x = r["coords"], r["cells"], r["x"]
    facets, owner = boundary_facets(cells)
    extent = max(np.ptp(coords, axis=0).max(), 1e-300)
    index = contact_index(r)
    if r.get("body") is not None:
        # The bodies of the cells at the points: the other side of a contact
        # between two bodies lies on the same surface but is not drawn.
        points = np.nonzero(index >= 0)[0]
        at_point = np.array([np.isin(c, points).any() for c in cells], dtype=bool)
        keep = np.isin(r["body"][owner], np.unique(r["body"][at_point]))
        facets, owner = [f for f, k in zip(facets, keep) if k], None
    centre = x.mean(axis=0)
    plane = np.linalg.svd(x - centre)[2][2] if len(x) >= 3 else contact_normal(r)
    tol = 1e-9 * extent
    if np.abs((x - centre) @ plane).max(initial=0) <= tol:
        on_plane = np.abs((coords - centre) @ plane) <= tol
        return [list(f) for f in facets if on_plane[f].all()]
    return [list(f) for f in facets if (index[f] >= 0).all()]


def plane_frame(x, normal=None, length="m"):
    """Two orthonormal directions normal to the contact normal and their axis
    labels: the two other coordinate axes when the normal is along one (so
    the map shows the model's own coordinates), else the principal
    directions of the points in that plane."""
    if normal is None:
        normal = np.linalg.svd(x - x.mean(axis=0))[2][2]
    normal = normal / np.linalg.norm(normal)
    axis = int(np.argmax(np.abs(normal)))
    if abs(normal[axis]) > 1 - 1e-9:
        a, b = [k for k in range(3) if k != axis]
        e = np.eye(3)
        return e[a], e[b], "%s [%s]" % ("xyz"[a], length), "%s [%s]" % ("xyz"[b], length)
    inplane = (x - x.mean(axis=0)) - np.outer((x - x.mean(axis=0)) @ normal, normal)
    e1 = np.linalg.svd(inplane)[2][0] if len(x) >= 2 else np.cross(normal, np.eye(3)[np.argmin(np.abs(normal))])
    e1 = e1 - (e1 @ normal) * normal
    e1 /= np.linalg.norm(e1)
    return e1, np.cross(normal, e1), "in-plane coordinate 1 [%s]" % length, "in-plane coordinate 2 [%s]" % length


def nodal_areas(coords, facets):
    """Each facet's area split equally among its nodes (per mesh node)."""
    area = np.zeros(len(coords))
    if not len(facets):
        return area
    f = np.array(facets)
    p = coords[f]
    # Area of a planar polygon: half the norm of the summed cross products.
    s = np.zeros((len(f), 3))
    for i in range(1, f.shape[1] - 1):
        s += np.cross(p[:, i] - p[:, 0], p[:, i + 1] - p[:, 0])
    share = 0.5 * np.linalg.norm(s, axis=1) / f.shape[1]
    np.add.at(area, f.ravel(), np.repeat(share, f.shape[1]))
    return area


def contact_areas(r):
    """The slave surface's facets (mesh ids), the nodal area of every contact
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


def figure(title, u, v, labels, limits):
    du, dv = limits[1] - limits[0], limits[3] - limits[2]
    fig, ax = plt.subplots(figsize=(7.5, 4.5 * max(0.5, min(2.0, dv / max(du, 1e-300))) + 1.0))
    ax.set_aspect("equal")
    ax.set_title(title, loc="left", fontsize=10)
    ax.set_xlabel(labels[0])
    ax.set_ylabel(labels[1])
    ax.set_xlim(limits[0], limits[1])
    ax.set_ylim(limits[2], limits[3])
    return fig, ax


def output_name(base, r, n_views, what):
    if n_views == 1:
        return "%s_contact_%s.png" % (base, what)
    return "%s_contact_%s_%s.png" % (base, re.sub(r"[^A-Za-z0-9_.-]+", "_", r["pair_name"]), what)


def surface_label(r):
    if r.get("pair_name") is None:
        return ""
    other = ("against " + r["master"]) if r.get("master") else "against the rigid plane"
    return "%s: %s %s\n" % (r["pair_name"], r.get("slave") or "contact face", other)


def plot_pair(base, r, out, n_views, unit="Pa", zoom=False, length="m"):
    x = r["x"]
    _, area, facets = contact_areas(r)
    if not facets:
        return None
    if r.get("normal_traction") is not None:
        pressure = r["normal_traction"]
    else:
        pressure = np.where(area > 0, r["normal_force"] / np.maximum(area, 1e-300), 0.0)
    e1, e2, l1, l2 = plane_frame(x, contact_normal(r), length)
    labels = (l1, l2)
    u, v = x @ e1, x @ e2
    tri = triangulation(u, v, facets)
    active = r["status"] > 0
    if zoom and active.any():
        # The patch in contact and a margin of half its size around it.
        lo = np.array([u[active].min(), v[active].min()])
        hi = np.array([u[active].max(), v[active].max()])
        margin = 0.5 * max(hi - lo) + 1e-12 * max(np.ptp(u), np.ptp(v))
        limits = (max(lo[0] - margin, u.min()), min(hi[0] + margin, u.max()), max(lo[1] - margin, v.min()),
                  min(hi[1] + margin, v.max()))
    else:
        pad = 0.02 * max(np.ptp(u), np.ptp(v), 1e-300)
        limits = (u.min() - pad, u.max() + pad, v.min() - pad, v.max() + pad)
    shown = (u >= limits[0]) & (u <= limits[1]) & (v >= limits[2]) & (v <= limits[3])
    head = surface_label(r)
    written = []

    fig, ax = figure(head + "Normal contact pressure", u, v, labels, limits)
    m = ax.tripcolor(tri, pressure, shading="gouraud", cmap="viridis")
    fig.colorbar(m, ax=ax, label="normal pressure [%s]" % unit)
    written.append(save(fig, out, output_name(base, r, n_views, "pressure")))

    fig, ax = figure(head + "Contact status (arrows: slip of the step at the slipping nodes)", u, v, labels, limits)
    colours = {0: ("lightgrey", "no contact"), 1: ("tab:blue", "stick"), 2: ("tab:orange", "slip")}
    # Dots as large as the node spacing allows: few nodes, large dots.
    size = float(np.clip(3000.0 / max(shown.sum(), 1), 2, 50))
    for s, (c, label) in colours.items():
        sel = r["status"] == s
        ax.scatter(u[sel], v[sel], c=c, s=size, label="%s (%d)" % (label, sel.sum()), zorder=2)
    step_slip = r["slip_increment"] if r.get("slip_increment") is not None else r["slip"]
    su, sv = step_slip @ e1, step_slip @ e2
    arrows = shown & (r["status"] == 2)
    longest = float(np.hypot(su, sv)[arrows].max(initial=0))
    if longest > 0:
        # The largest slip of a slipping node drawn as 8 % of the drawn extent.
        scale = longest / (0.08 * max(limits[1] - limits[0], limits[3] - limits[2]))
        q = ax.quiver(u[arrows], v[arrows], su[arrows], sv[arrows], color="black", zorder=3, width=0.003,
                      angles="xy", scale_units="xy", scale=scale)
        # The scale arrow below the map, clear of the title (two lines for a pair).
        ax.quiverkey(q, 0.0, -0.14, longest, "largest %.2e %s" % (longest, length), labelpos="E", coordinates="axes",
                     fontproperties={"size": 8})
    ax.triplot(tri, color="0.85", lw=0.5, zorder=1)
    ax.legend(loc="upper right", fontsize=8)
    written.append(save(fig, out, output_name(base, r, n_views, "status")))

    if r["law"] == "Coulomb" and r["F"] > 0:
        tN = r["normal_force"]
        tT = np.linalg.norm(r["tangential_force"], axis=1)
        ratio = np.where(tN > 1e-12 * max(tN.max(), 1e-300), tT / (r["F"] * np.maximum(tN, 1e-300)), np.nan)
        fig, ax = figure(head + "Coulomb: |t_T| / (F t_N)   (F = %g; 1 on the slip zone)" % r["F"], u, v, labels, limits)
        m = ax.tripcolor(tri, np.nan_to_num(ratio, nan=0.0), shading="gouraud", cmap="magma", vmin=0.0, vmax=1.0)
        fig.colorbar(m, ax=ax, label="|t_T| / (F t_N)  (0 where no contact)")
        written.append(save(fig, out, output_name(base, r, n_views, "ratio")))
    return written


def plot(directory, base, r, out, unit="Pa", zoom=False, length="m"):
    views = pair_views(r)
    if len(r["pairs"]) == 1 and r["pairs"][0]["name"] == "contact" and not r["pairs"][0]["master"]:
        for v in views:
            v["pair_name"] = None  # Contact/Face against the rigid plane: no pair to name
    written = []
    for v in views:
        files = plot_pair(base, v, out, len(views), unit, zoom, length)
        if files is None:
            print("plot_contact.py: pair %s: no facet of its slave surface lies in the contact set; not drawn"
                  % v.get("pair_name"), file=sys.stderr)
            continue
        written += files
    if not written:
        fail("no mesh facet lies in the contact set of any pair; cannot draw a contact surface")
    return written


def save(fig, out, name):
    path = os.path.join(out, name)
    fig.tight_layout()
    fig.savefig(path, dpi=110, bbox_inches="tight")  # keeps the scale arrow below the map
    plt.close(fig)
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("directory")
    ap.add_argument("--base", help="result name: BASE of a result or of a run in load steps, or BASE.stepNNNN "
                                   "(default: the only result of the directory)")
    which = ap.add_mutually_exclusive_group()
    which.add_argument("--step", type=int, help="the load step drawn, 1-based (default: the last)")
    which.add_argument("--time", type=float, help="the load step drawn, by its time")
    ap.add_argument("--out", help="where the PNGs go, created if needed (default: the result's directory)")
    ap.add_argument("--pressure-unit", default="Pa", help="unit of force / area of the input (default Pa)")
    ap.add_argument("--length-unit", default="m", help="unit of length of the input (default m)")
    ap.add_argument("--zoom", action="store_true", help="draw only the neighbourhood of the nodes in contact")
    a = ap.parse_args()
    if not os.path.isdir(a.directory):
        fail("%s is not a directory" % a.directory)
    base, r = read_result(a.directory, a.base, a.step, a.time)
    out = a.out or a.directory
    try:
        os.makedirs(out, exist_ok=True)
    except OSError as e:
        fail("cannot create --out %s: %s" % (out, e.strerror or e))
    if not os.access(out, os.W_OK):
        fail("--out %s is not writable" % out)
    for path in plot(a.directory, base, r, out, a.pressure_unit, a.zoom, a.length_unit):
        print(path)


if __name__ == "__main__":
    main()
