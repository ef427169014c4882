#!/usr/bin/python3
"""Hertz contact of an elastic sphere on an elastic block: Tribos against the
analytic solution, over a sequence of meshes (docs/hertz.md).

usage: scripts/hertz.py [-l LEVEL ...] [--np N] [--tribos EXE] [--out DIR]
                        [--subdomains LEVEL:S ...] [--table FILE.md]
                        [--plot FILE.png | --no-plot] [--no-run]
                        [--set "Sublist/Key=value" ...]

For each level (default 0 1 2), input/hertz_sphere.geo is meshed by Gmsh
with -setnumber Level L (element size 0.1 / 2^(L-1) mm at the contact point;
Level 1 is the shipped input/hertz_sphere.msh) and solved by

    mpirun -np N TRIBOS input/hertz_sphere.xml --set Mesh/File=MESH --output OUT/level_L
           [--set Mesh/Subdomains=S]

(TRIBOS: build/drivers/tribos, else build-gmsh/drivers/tribos.)

Then the result (OUT/level_N/solution.h5, .json, .parameters.xml) is compared
with Hertz's solution for the force the run computed:

  F     = 4 * sum of the nodal normal forces (quarter model)
  1/E*  = (1 - nu1^2)/E1 + (1 - nu2^2)/E2   (the two bodies' materials of the run)
  a     = (3 F R / (4 E*))^(1/3),   p0 = 3 F / (2 pi a^2)

Estimators from the finite element result:

  a_h   the second moment of the nodal forces: for the Hertz pressure
        p = p0 sqrt(1 - r^2/a^2), int p r^2 dA / int p dA = 2 a^2 / 5, so
        a_h = sqrt(5/2 * sum f_i r_i^2 / sum f_i). The nodal forces f_i are
        the integrals of p against the hat functions, so the sum integrates p
        times the P1 interpolant of r^2: no nodal areas, no fit, and no
        dependence on where the last active node happens to lie (the edge of
        the active set moves by whole elements).
  p0_h  the peak of the Hertz profile p0 sqrt(1 - r^2/a^2) fitted to the
        nodal pressures p_i = f_i / A_i (A_i the node's share of the slave
        facets projected on the contact plane) by least squares weighted by
        A_i (an L2 fit on the contact face), p0 and a both free (the fitted
        a is a_fit, a second estimate of a). The centre node's own pressure
        f_0 / A_0 (p_centre, reported too) is no estimator: node-to-segment
        contact leaves an oscillation of the nodal forces over the master
        mesh (slave nodes lying on master nodes carry ~40 % less), which does
        not fall under refinement; the fit averages it out.
  a_act the radius of the outermost active slave node (for information: it
        is a lower bound of the contact radius, within one element).

Writes the table (stdout, and --table as Markdown), OUT/hertz.json with every
figure, the plot of nodal pressure against r with Hertz's curve and the
errors against h (--plot, default OUT/hertz_pressure.png) and, when Level 1
is among the levels, its contact meshes seen from above (hertz_mesh.png
beside it). docs/hertz.md has the command that made docs/images/hertz_*.png. --no-run analyses results
already in OUT. The script exits 1 if a run fails or does not converge.
"""
import argparse
import json
import math
import os
import shutil
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
INPUT = os.path.join(ROOT, "input", "hertz_sphere.xml")
GEO = os.path.join(ROOT, "input", "hertz_sphere.geo")
COARSE = os.path.join(ROOT, "input", "hertz_sphere.msh")
RADIUS = 10.0  # R of input/hertz_sphere.geo
SLAVE_BODY, MASTER_BODY = "sphere", "block"


def fail(message):
    sys.exit("hertz.py: " + message)


def parameter(root, path):
    """The value of Sublist/.../Name in a Tribos parameter file, or None."""
    node = root
    for part in path.split("/")[:-1]:
        node = next((c for c in node if c.tag == "ParameterList" and c.get("name") == part), None)
        if node is None:
            return None
    p = next((c for c in node if c.tag == "Parameter" and c.get("name") == path.split("/")[-1]), None)
    return None if p is None else p.get("value")


def effective_modulus(params_xml, overrides=()):
    """E* of the two bodies of a run: their materials from the input file
    (with the run's --set overrides), the per-body material (Bodies/NAME/
    Material) or else the common one (Material). The run's own
    BASE.parameters.xml is not used: it lacks Bodies (docs/hertz.md)."""
    root = ET.parse(params_xml).getroot()
    given = dict(s.split("=", 1) for s in overrides)

    def value(path):
        return given.get(path) or parameter(root, path)

    inv = 0.0
    for body in (SLAVE_BODY, MASTER_BODY):
        E = value("Bodies/%s/Material/Young's Modulus" % body) or value("Material/Young's Modulus")
        nu = value("Bodies/%s/Material/Poisson's Ratio" % body) or value("Material/Poisson's Ratio")
        inv += (1.0 - float(nu) ** 2) / float(E)
    return 1.0 / inv


def hertz(F, R, Estar):
    a = (3.0 * F * R / (4.0 * Estar)) ** (1.0 / 3.0)
    return a, 3.0 * F / (2.0 * math.pi * a * a)


def tet_boundary_facets(cells):
    """Facets (sorted node triples) that belong to one tetrahedron only."""
    faces = np.concatenate([cells[:, [0, 1, 2]], cells[:, [0, 1, 3]], cells[:, [1, 2, 3]], cells[:, [0, 2, 3]]])
    faces = np.sort(faces, axis=1)
    uniq, count = np.unique(faces, axis=0, return_counts=True)
    return uniq[count == 1]


# The mid-edge nodes of a written Tet10 cell (VTK's order): the corners of
# each edge.
TET10_EDGES = [(0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3)]


def slave_facets(cells, node, num_nodes):
    """The slave facets: boundary facets of the mesh whose three corners are
    all contact nodes (node triples)."""
    is_contact = np.zeros(num_nodes, bool)
    is_contact[node] = True
    facets = tet_boundary_facets(cells[:, :4])
    return facets[is_contact[facets].all(axis=1)]


def nodal_areas(coords, cells, node):
    """A_i of the contact nodes `node`: their share of the slave facets
    projected on the plane z = 0 (facets of a symmetry plane project to
    nothing). A 3-node facet gives each corner a third; a 6-node one (Tet10)
    gives the shares of mortar's transformed basis, int N~_i dA on a flat
    facet: 2/15 to each corner, 1/5 to each mid-edge node (docs/contact.md)."""
    facets = slave_facets(cells, node, len(coords))
    p = coords[facets]
    e1, e2 = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    area = 0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
    nodal = np.zeros(len(coords))
    second_order = cells.shape[1] == 10
    for k in range(3):
        np.add.at(nodal, facets[:, k], area * (2.0 / 15 if second_order else 1.0 / 3))
    if second_order:
        mid = {}
        for c in cells:
            for k, (i, j) in enumerate(TET10_EDGES):
                mid[(min(c[i], c[j]), max(c[i], c[j]))] = c[4 + k]
        for f, A in zip(facets, area):
            for i, j in ((0, 1), (1, 2), (0, 2)):
                nodal[mid[(min(f[i], f[j]), max(f[i], f[j]))]] += A / 5
    return nodal[node]


def fit_hertz(r, p, w, a_guess):
    """The Hertz profile p0 sqrt(1 - r^2/a^2) fitted to the nodal pressures
    p_i by weighted least squares (weights w_i: the nodal areas, so that the
    fit is an L2 fit on the contact face), over the nodes r < 1.5 a_guess
    (the inactive ring included: it pins the edge). For each a, p0 has a
    closed form; a is found by a scan refined twice. Returns (a, p0)."""
    keep = r < 1.5 * a_guess
    r, p, w = r[keep], p[keep], w[keep]

    def best(a):
        s = np.sqrt(np.clip(1.0 - (r / a) ** 2, 0.0, None))
        p0 = np.sum(w * p * s) / max(np.sum(w * s * s), 1e-300)
        return np.sum(w * (p - p0 * s) ** 2), p0

    lo, hi = 0.5 * a_guess, 1.5 * a_guess
    for _ in range(3):
        grid = np.linspace(lo, hi, 201)
        k = int(np.argmin([best(a)[0] for a in grid]))
        step = grid[1] - grid[0]
        a = grid[k]
        lo, hi = a - step, a + step
    return float(a), float(best(a)[1])


def analyse(directory, R=RADIUS, base="solution", input_file=INPUT, overrides=()):
    """The Hertz figures of one result directory (a dict)."""
    import h5py

    with open(os.path.join(directory, base + ".json")) as f:
        summary = json.load(f)
    with h5py.File(os.path.join(directory, base + ".h5"), "r") as f:
        coords = f["mesh/geometry"][...]
        cells = f["mesh/topology"][...].astype(int)
        node = f["points/contact/node"][...].ravel().astype(int)
        x = f["points/contact/geometry"][...]
        fn = f["points/contact/normal_force"][...].ravel()
        status = f["points/contact/status"][...].ravel().astype(int)
        weight = f["points/contact/master_weight"][...].max(axis=1) if "points/contact/master_weight" in f else None
    Estar = effective_modulus(input_file, overrides)
    r = np.hypot(x[:, 0], x[:, 1])
    F = 4.0 * fn.sum()
    a, p0 = hertz(F, R, Estar)
    a_h = math.sqrt(2.5 * np.sum(fn * r * r) / fn.sum())
    active = status > 0
    a_act = float(r[active].max()) if active.any() else 0.0

    # The force over the area projected on the contact plane (the written
    # normal_traction divides by the area on the sphere itself, larger by
    # 1/cos of the surface's tilt: 0.5 % at r = a).
    A = nodal_areas(coords, cells, node)
    pressure = np.divide(fn, A, out=np.zeros_like(fn), where=A > 0)
    centre = int(np.argmin(r))
    a_fit, p0_h = fit_hertz(r, pressure, A, a_h)

    # h near the contact: mean edge length of the slave facets inside the
    # Hertz contact radius.
    p = coords[slave_facets(cells, node, len(coords))]
    centroid_r = np.hypot(p[:, :, 0].mean(axis=1), p[:, :, 1].mean(axis=1))
    inside = centroid_r < a
    edges = np.concatenate([np.linalg.norm(p[inside][:, i] - p[inside][:, j], axis=1) for i, j in ((0, 1), (1, 2), (0, 2))])
    h = float(edges.mean()) if len(edges) else float("nan")
    kkt = summary.get("kkt", {})
    return {
        "directory": directory,
        "h": h,
        "dofs": summary.get("primal_dofs"),
        "nodes": summary.get("nodes"),
        "ranks": summary.get("ranks"),
        "subdomains": summary.get("subdomains"),
        "converged": bool(summary.get("converged")),
        "kkt": {k: kkt.get(k) for k in ("equilibrium", "dirichlet", "nonpenetration", "complementarity", "limit")},
        "F": F,
        "Estar": Estar,
        "a_h": a_h,
        "a": a,
        "err_a": a_h / a - 1.0,
        "a_active": a_act,
        "a_fit": a_fit,
        "err_a_fit": a_fit / a - 1.0,
        "p0_h": p0_h,
        "p_centre": float(pressure[centre]),
        "p0": p0,
        "err_p0": p0_h / p0 - 1.0,
        "active": int(active.sum()),
        "time_s": summary.get("time_setup_s", 0.0) + summary.get("time_solve_s", 0.0),
        "r": r.tolist(),
        "pressure": pressure.tolist(),
        "status": status.tolist(),
        "master_weight": None if weight is None else weight.tolist(),
    }


def default_tribos():
    for b in ("build", "build-gmsh"):
        exe = os.path.join(ROOT, b, "drivers", "tribos")
        if os.path.exists(exe):
            return exe
    return os.path.join(ROOT, "build", "drivers", "tribos")


def mesh_for(level, out, order=1):
    if level == 1 and order == 1:
        return COARSE  # the same as meshing the .geo with Level 1
    msh = os.path.join(out, "hertz_sphere_%d%s.msh" % (level, "" if order == 1 else "_order%d" % order))
    if not os.path.exists(msh) or os.path.getmtime(msh) < os.path.getmtime(GEO):
        gmsh = shutil.which("gmsh") or fail("gmsh not found (apt-get install gmsh)")
        subprocess.run([gmsh, "-3", "-order", str(order), "-format", "msh4", "-setnumber", "Level", str(level), GEO,
                        "-o", msh], check=True, stdout=subprocess.DEVNULL)
    return msh


def run(level, args):
    directory = os.path.join(args.out, "level_%d" % level)
    cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(args.np), args.tribos, INPUT,
           "--set", "Mesh/File=" + mesh_for(level, args.out, args.order), "--output", directory, "--quiet"]
    if level in args.subdomains:
        cmd += ["--set", "Mesh/Subdomains=%d" % args.subdomains[level]]
    for s in args.set:
        cmd += ["--set", s]
    return directory, timed_run(cmd, directory, level, fail)


def timed_run(cmd, directory, level, fail):
    """Runs tribos (exit 0 or 2: a result), printing the command; the wall
    time, also written to DIRECTORY/wall_s.txt."""
    print("$ " + " ".join("'%s'" % c if " " in c else c for c in cmd), file=sys.stderr)
    t0 = time.time()
    done = subprocess.run(cmd, stdout=subprocess.DEVNULL)
    wall = time.time() - t0
    with open(os.path.join(directory, "wall_s.txt"), "w") as f:
        f.write("%.2f\n" % wall)
    if done.returncode not in (0, 2):
        fail("level %d: tribos exited with %d" % (level, done.returncode))
    return wall


COLUMNS = [("level", "%d"), ("h", "%.4f"), ("dofs", "%d"), ("F", "%.1f"), ("a_h", "%.4f"), ("a", "%.4f"),
           ("err_a", "%+.2f%%"), ("a_fit", "%.4f"), ("err_a_fit", "%+.2f%%"), ("p0_h", "%.0f"), ("p0", "%.0f"),
           ("err_p0", "%+.2f%%"), ("p_centre", "%.0f"), ("active", "%d"), ("subdomains", "%d"), ("time_s", "%.2f"),
           ("wall_s", "%.1f")]


def cell(row, key, fmt):
    v = row.get(key)
    if v is None:
        return "-"
    return fmt % (100 * v if fmt.endswith("%%") else v)


def table(rows, markdown):
    head = [k for k, _ in COLUMNS]
    lines = []
    if markdown:
        lines.append("| " + " | ".join(head) + " |")
        lines.append("|" + "---:|" * len(head))
        for row in rows:
            lines.append("| " + " | ".join(cell(row, k, f) for k, f in COLUMNS) + " |")
    else:
        lines.append("  ".join("%9s" % k for k in head))
        for row in rows:
            lines.append("  ".join("%9s" % cell(row, k, f) for k, f in COLUMNS))
    return "\n".join(lines)


def plot(rows, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12.5, 4.6))
    fine = rows[-1]
    rr = np.linspace(0, fine["a"], 200)
    r, pr = np.array(fine["r"]), np.array(fine["pressure"])
    ax1.plot(rr, fine["p0"] * np.sqrt(1 - (rr / fine["a"]) ** 2), "k-", label="Hertz (F of the run)")
    ax1.plot([fine["a"], fine["a"] * 1.6], [0, 0], "k-")
    ax1.plot(rr, fine["p0_h"] * np.sqrt(np.clip(1 - (rr / fine["a_fit"]) ** 2, 0, None)), "k--", lw=1,
             label="fit: p0_h = %.0f, a_fit = %.3f" % (fine["p0_h"], fine["a_fit"]))
    keep = r < 1.6 * fine["a"]
    if fine.get("master_weight"):
        w = np.array(fine["master_weight"])[keep]
        sc = ax1.scatter(r[keep], pr[keep], c=w, s=9, cmap="viridis", vmin=1 / 3, vmax=1,
                         label="nodal pressure f_i / A_i")
        fig.colorbar(sc, ax=ax1, label="largest master weight (1: on a master node)")
    else:
        ax1.plot(r[keep], pr[keep], "o", ms=3, color="C3", label="nodal pressure f_i / A_i")
    ax1.set_xlabel("r [mm]")
    ax1.set_ylabel("contact pressure [MPa]")
    ax1.set_title("Level %d (h = %.3f mm, %d dofs)" % (fine["level"], fine["h"], fine["dofs"]))
    ax1.legend()
    h = np.array([row["h"] for row in rows])
    for key, label, marker in (("err_a", "|a_h / a - 1|  (moment)", "o"), ("err_a_fit", "|a_fit / a - 1|  (fit)", "s"),
                               ("err_p0", "|p0_h / p0 - 1|  (fit)", "^")):
        e = np.abs([row[key] for row in rows])
        ax2.loglog(h, 100 * e, marker + "-", label=label)
    if len(rows) > 1:
        ax2.loglog(h, 100 * abs(rows[0]["err_p0"]) * (h / h[0]), "k:", lw=1, label="slope 1")
    ax2.set_xlabel("h near the contact [mm]")
    ax2.set_ylabel("error against Hertz [%]")
    ax2.set_title("errors under refinement (levels %s)" % ", ".join(str(row["level"]) for row in rows))
    ax2.grid(True, which="both", alpha=0.3)
    ax2.legend(fontsize=8)
    fig.tight_layout()
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    fig.savefig(path, dpi=110)


def mesh_plot(row, path):
    """The slave facets (sphere) over the master facets (block top) near the
    contact, seen from above, with the active slave nodes and Hertz's a."""
    import h5py
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    with h5py.File(os.path.join(row["directory"], "solution.h5"), "r") as f:
        coords = f["mesh/geometry"][...]
        cells = f["mesh/topology"][...].astype(int)
        node = f["points/contact/node"][...].ravel().astype(int)
        status = f["points/contact/status"][...].ravel().astype(int)
    facets = tet_boundary_facets(cells[:, :4])
    is_slave = np.zeros(len(coords), bool)
    is_slave[node] = True
    slave = facets[is_slave[facets].all(axis=1)]
    top = np.abs(coords[:, 2]) < 1e-9
    master = facets[top[facets].all(axis=1) & ~is_slave[facets].any(axis=1)]
    fig, ax = plt.subplots(figsize=(6.4, 6))
    lim = 1.5 * row["a"]
    for tri, style in ((master, dict(color="C3", lw=1.4)), (slave, dict(color="C0", lw=0.7))):
        for t in tri:
            xy = coords[np.append(t, t[0]), :2]
            if np.hypot(xy[:, 0], xy[:, 1]).min() < 1.2 * lim:
                ax.plot(xy[:, 0], xy[:, 1], **style)
    xs = coords[node]
    act = status > 0
    ax.plot(xs[act, 0], xs[act, 1], "o", ms=3.5, color="C0", label="active slave node")
    t = np.linspace(0, np.pi / 2, 100)
    ax.plot(row["a"] * np.cos(t), row["a"] * np.sin(t), "k--", label="Hertz contact radius a = %.3f mm" % row["a"])
    ax.plot([], [], color="C3", lw=1.4, label="master facets (block top)")
    ax.plot([], [], color="C0", lw=0.7, label="slave facets (sphere), projected")
    ax.set_xlim(0, lim)
    ax.set_ylim(0, lim)
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_title("Level %d: non-matching contact meshes seen from above" % row["level"])
    ax.legend(loc="upper right", fontsize=8, framealpha=0.95)
    fig.tight_layout()
    fig.savefig(path, dpi=80)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("-l", "--levels", type=int, nargs="+", default=[0, 1, 2])
    ap.add_argument("--subdomains", nargs="*", default=["3:8"],
                    help="LEVEL:S, METIS subdomains of a level (default 3:8; the input file has 2)")
    ap.add_argument("--np", type=int, default=2)
    ap.add_argument("--order", type=int, choices=(1, 2), default=1,
                    help="element order of the meshes: 2 makes Gmsh write Tet10 (gmsh -order 2)")
    ap.add_argument("--tribos", default=default_tribos())
    ap.add_argument("--out", default=os.path.join(ROOT, "output", "hertz"))
    ap.add_argument("--table", help="write the table as Markdown to this file")
    ap.add_argument("--plot", help="the pressure plot (default OUT/hertz_pressure.png; docs: "
                    "docs/images/hertz_pressure.png)")
    ap.add_argument("--no-plot", action="store_true")
    ap.add_argument("--no-run", action="store_true", help="analyse the results already in --out")
    ap.add_argument("--set", action="append", default=[], help="passed to tribos")
    args = ap.parse_args()
    args.out = os.path.abspath(args.out)
    args.plot = args.plot or os.path.join(args.out, "hertz_pressure.png")
    args.subdomains = {int(k): int(v) for k, v in (x.split(":") for x in args.subdomains)}
    os.makedirs(args.out, exist_ok=True)
    rows = []
    for level in args.levels:
        wall = None
        directory = os.path.join(args.out, "level_%d" % level)
        if not args.no_run:
            directory, wall = run(level, args)
        row = analyse(directory, overrides=args.set)
        wall_file = os.path.join(directory, "wall_s.txt")
        if wall is None and os.path.exists(wall_file):
            with open(wall_file) as f:
                wall = float(f.read())
        row["level"], row["wall_s"] = level, wall
        rows.append(row)
        print(table([row], False).split("\n")[1], file=sys.stderr, flush=True)
    print(table(rows, False))
    if args.table:
        with open(args.table, "w") as f:
            f.write(table(rows, True) + "\n")
    with open(os.path.join(args.out, "hertz.json"), "w") as f:
        json.dump([{k: v for k, v in row.items() if k not in ("r", "pressure", "status", "master_weight")}
                   for row in rows], f, indent=1)
    if not args.no_plot:
        plot(rows, args.plot)
        coarse = [row for row in rows if row["level"] == 1]
        if coarse:
            mesh_plot(coarse[0], os.path.join(os.path.dirname(os.path.abspath(args.plot)), "hertz_mesh.png"))
    bad = [row["level"] for row in rows if not row["converged"]]
    if bad:
        fail("not converged: level(s) %s" % bad)


if __name__ == "__main__":
    main()
