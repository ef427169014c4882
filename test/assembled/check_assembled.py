#!/usr/bin/python3
"""examples/assembled against the tribos driver on the files it writes.

    check_assembled.py --work DIR --app ASSEMBLED --tribos TRIBOS [--ranks 2 3] [--size m] [--rel 1e-8]
                       -- MPIEXEC NPFLAG [FLAGS...]

(MPIEXEC NPFLAG: the launcher and its rank-count flag; the rank count is
put after them.) The application (an FECrsMatrix assembled over the ranks,
solved by Tribos::Assembled in a load history of 4 steps) runs on each
rank count of --ranks and writes its mesh (assembled.msh), the same problem
as a driver input (assembled.xml) and every node's displacement of every
step (assembled.stepNNNN.csv). Checked:

  - each run exits 0, every step converged with its KKT residuals within
    the summary's limit (assembled.steps.csv), the first step built the
    subdomains and the later ones did not (the reuse path);
  - the mesh and the input written on every rank count are the same files;
  - the driver, on 2 ranks on that input, converges in every step;
  - in every step, for every rank count, max |u_app - u_driver| <= rel
    max |u_driver| over the nodes, matched by body and coordinates (the
    bodies touch: a node of the upper block's bottom may lie where a node
    of the lower block's top does);
  - the contact counts (active, stick, slip) of the application and of the
    driver, printed side by side.
"""
import argparse
import csv
import filecmp
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
import tribos_summary  # noqa: E402

FAILURES = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what, flush=True)
    if not ok:
        FAILURES.append(what)


def run(cmd, echo=True):
    print("$ " + " ".join(cmd), flush=True)
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
    if echo or p.returncode != 0:
        sys.stdout.write(p.stdout)
    return p.returncode, p.stdout


def mesh_bodies(path):
    """Node tag -> physical volume (body) tag, from the $Entities and $Nodes
    of a Gmsh 4.1 ASCII file."""
    with open(path) as f:
        lines = f.read().split("\n")
    at = lines.index("$Entities") + 1
    points, curves, surfaces, volumes = map(int, lines[at].split())
    body_of_volume = {}
    for line in lines[at + 1 + points + curves + surfaces: at + 1 + points + curves + surfaces + volumes]:
        v = line.split()
        body_of_volume[int(v[0])] = int(v[8])  # tag, 6 box values, count, first physical tag
    at = lines.index("$Nodes") + 1
    blocks = int(lines[at].split()[0])
    at += 1
    body = {}
    for _ in range(blocks):
        dim, entity, _, count = map(int, lines[at].split())
        for line in lines[at + 1: at + 1 + count]:
            if dim == 3:
                body[int(line)] = body_of_volume[entity]
        at += 1 + 2 * count
    return body


def application_step(directory, step, body_of_node):
    rows = np.loadtxt(os.path.join(directory, "assembled.step%04d.csv" % step), delimiter=",", skiprows=1, ndmin=2)
    bodies = np.array([body_of_node[int(n)] for n in rows[:, 0]])
    return bodies, rows[:, 1:4], rows[:, 4:7]


def driver_step(path):
    with h5py.File(path, "r") as f:
        x = np.array(f["mesh/geometry"])
        u = np.array(f["nodes/displacement"])
        topology = np.array(f["mesh/topology"])
        cell_body = np.array(f["cells/body"]).ravel()
    body = np.full(len(x), -1)
    for c in range(topology.shape[0]):
        body[topology[c]] = cell_body[c]
    return body, x, u


def keys(body, x, scale):
    return [(int(b),) + tuple(np.round(p / scale, 9)) for b, p in zip(body, x)]


def compare(app, drv):
    """max |u_app - u_driver| and max |u_driver| over the nodes matched by
    (body, coordinates); bodies numbered as each side numbers them, matched
    by the order of their tags."""
    (ab, ax, au), (db, dx, du) = app, drv
    amap = {b: k for k, b in enumerate(sorted(set(ab)))}
    dmap = {b: k for k, b in enumerate(sorted(set(db)))}
    scale = float(np.max(np.abs(dx)))
    index = {k: i for i, k in enumerate(keys([dmap[b] for b in db], dx, scale))}
    if len(index) != len(dx):
        raise ValueError("the driver's mesh has two nodes of one body at one place")
    matched = [index.get(k) for k in keys([amap[b] for b in ab], ax, scale)]
    missing = sum(m is None for m in matched)
    if missing or len(ax) != len(dx):
        raise ValueError("%d of the application's %d nodes have no node of the driver's %d" % (missing, len(ax), len(dx)))
    diff = np.abs(au - du[np.array(matched)])
    return float(diff.max()), float(np.max(np.abs(du))), int(np.argmax(diff.max(axis=1)))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--work", required=True)
    ap.add_argument("--app", required=True)
    ap.add_argument("--tribos", required=True)
    ap.add_argument("--ranks", type=int, nargs="+", default=[2, 3])
    ap.add_argument("--size", type=int, default=1)
    ap.add_argument("--rel", type=float, default=1e-8)
    ap.add_argument("launcher", nargs="+")
    args = ap.parse_args()
    launch = lambda np_: args.launcher[:2] + [str(np_)] + args.launcher[2:]  # noqa: E731
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)

    # The application on each rank count.
    app_dirs, app_rows = {}, {}
    for np_ in args.ranks:
        d = os.path.join(args.work, "app_np%d" % np_)
        rc, _ = run(launch(np_) + [args.app, "--size", str(args.size), "--out", d, "--timings"])
        check(rc == 0, "the application on %d ranks exits 0 (%d)" % (np_, rc))
        if rc != 0:
            continue
        with open(os.path.join(d, "assembled.steps.csv")) as f:
            rows = list(csv.DictReader(f))
        check(len(rows) == 4 and all(r["converged"] == "true" and float(r["kkt_worst"]) <= float(r["limit"]) for r in rows),
              "np %d: 4 steps, each converged with its KKT residuals within the limit" % np_)
        check([r["rebuilt"] for r in rows] == ["true", "false", "false", "false"],
              "np %d: the first step built the subdomains, the later ones reused them" % np_)
        app_dirs[np_], app_rows[np_] = d, rows
    if not app_dirs:
        return 1
    first = app_dirs[args.ranks[0]]
    for np_, d in app_dirs.items():
        for name in ("assembled.msh", "assembled.xml"):
            check(filecmp.cmp(os.path.join(first, name), os.path.join(d, name), shallow=False),
                  "np %d wrote the %s of np %d" % (np_, name, args.ranks[0]))

    # The driver on the files the application wrote.
    out = os.path.join(args.work, "driver")
    rc, _ = run(launch(2) + [args.tribos, os.path.join(first, "assembled.xml"), "--output", out, "--quiet"],
                echo=False)  # its summary is DIR/solution.json
    check(rc == 0, "the driver on assembled.xml exits 0 (%d)" % rc)
    if rc != 0:
        return 1
    summary = tribos_summary.load(os.path.join(out, "solution.json"))
    steps = summary["steps"]
    check(len(steps) == 4 and all(r["converged"] for r in steps), "the driver: 4 steps, each converged")

    body_of_node = mesh_bodies(os.path.join(first, "assembled.msh"))
    print("step  time  ranks  max|u_app - u_driver|  max|u_driver|  relative   app active/stick/slip  driver")
    for k, row in enumerate(steps, start=1):
        drv = driver_step(os.path.join(out, row["file"]))
        for np_, d in app_dirs.items():
            diff, scale, _ = compare(application_step(d, k, body_of_node), drv)
            a = app_rows[np_][k - 1]
            c = row["contact"]
            print("%4d  %4g  %5d  %21.3e  %13.3e  %9.2e   %6s/%s/%s  %12s" %
                  (k, row["time"], np_, diff, scale, diff / scale, a["active"], a["stick"], a["slip"],
                   "%d/%d/%d" % (c["active"], c["stick"], c["slip"])))
            check(diff <= args.rel * scale, "step %d, np %d: max |u_app - u_driver| = %.2e <= %g max |u_driver| = %.2e"
                  % (k, np_, diff, args.rel, args.rel * scale))
    if FAILURES:
        print("%d check(s) failed" % len(FAILURES))
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
