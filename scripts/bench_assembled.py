#!/usr/bin/python3
"""An application's own assembly through Tribos::Assembled against the
tribos driver on the same problem (docs/benchmarks.md).

usage: scripts/bench_assembled.py [--size M] [--ranks R] [--repeat N] [--app PATH] [--tribos PATH] [--work DIR]

Runs examples/assembled (built in the tree as build/test/assembled/assembled:
two blocks in Coulomb contact, 4 load steps, Algorithm 2 to 1e-10) at
--size M (M = 5: 20 017 nodes, M = 6: 33 836) on R ranks with --timings, then
the driver on the mesh and input the application wrote: with its own
decomposition (Mesh/Subdomain Size Auto), with as many METIS subdomains
as the application's ranks gave it (Mesh/Subdomains), and with those and
every dense block of F formed (Solver/FETI/Dual Operator = Explicit; Auto
forms the blocks of at most 4000 rows). Prints one table
row per run: subdomains, primal and dual dofs, the applications of F over
the 4 steps, setup, solve and setup + solve seconds (the largest over the
ranks: the application's SolveSummary setupSeconds and solveSeconds summed
over the steps, the driver's summary time_setup_s and time_solve_s), and
their ratio to the application's. The application's own assembly is its
last column (the driver's setup includes reading, partitioning and
assembling the mesh). With --repeat N the four runs are made N times in
turn and the fastest of each kept.
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import tribos_summary  # noqa: E402


def mpirun(ranks):
    return ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)]


def run(cmd):
    t0 = time.monotonic()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
    wall = time.monotonic() - t0
    if p.returncode != 0:
        sys.exit("bench_assembled: %s failed (exit %d):\n%s%s" % (" ".join(cmd), p.returncode, p.stdout[-3000:],
                                                                p.stderr[-3000:]))
    return p.stdout, wall


def application(args, out):
    _, wall = run(mpirun(args.ranks) + [args.app, "--size", str(args.size), "--out", out, "--timings", "--no-fields"])
    with open(os.path.join(out, "assembled.steps.csv")) as f:
        rows = list(csv.DictReader(f))
    if len(rows) != 4 or not all(r["converged"] == "true" for r in rows):
        sys.exit("bench_assembled: the application did not converge in every step")
    return {"run": "application (Tribos::Assembled)", "subdomains": int(rows[0]["subdomains"]),
            "primal": int(rows[0]["primal_dofs"]), "dual": int(rows[0]["dual_dofs"]),
            "n_A": sum(int(r["n_A"]) for r in rows), "setup": sum(float(r["setup_s"]) for r in rows),
            "solve": sum(float(r["solve_s"]) for r in rows), "assembly": float(rows[0]["assembly_s"]), "wall": wall}


def driver(args, xml, out, label, sets):
    cmd = mpirun(args.ranks) + [args.tribos, xml, "--output", out, "--quiet"]
    for s in sets:
        cmd += ["--set", s]
    _, wall = run(cmd)
    s = tribos_summary.load(os.path.join(out, "solution.json"))
    if len(s["steps"]) != 4 or not all(r["converged"] for r in s["steps"]):
        sys.exit("bench_assembled: the driver did not converge in every step")
    return {"run": label, "subdomains": s["subdomains"], "primal": s["primal_dofs"], "dual": s["dual_dofs"],
            "n_A": sum(r["n_A"] for r in s["steps"]), "setup": s["time_setup_s"], "solve": s["time_solve_s"],
            "assembly": None, "wall": wall}


def keep_fastest(best, r):
    return r if best is None or r["setup"] + r["solve"] < best["setup"] + best["solve"] else best


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--size", type=int, default=5)
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--app", default=os.path.join(ROOT, "build/test/assembled/assembled"))
    ap.add_argument("--tribos", default=os.path.join(ROOT, "build/drivers/tribos"))
    ap.add_argument("--work", help="keep the files here (default: a scratch directory)")
    args = ap.parse_args()
    for exe in (args.app, args.tribos):
        if not os.access(exe, os.X_OK):
            sys.exit("bench_assembled: %s is not built (cmake --build build --target assembled_example tribos)" % exe)
    load_before = os.getloadavg()[0]
    with tempfile.TemporaryDirectory() as tmp:
        work = args.work or tmp
        os.makedirs(work, exist_ok=True)
        app_dir = os.path.join(work, "app")
        xml = os.path.join(app_dir, "assembled.xml")
        rows = [None] * 4
        # Round by round, so that a load on the machine falls on every run alike.
        for _ in range(args.repeat):
            rows[0] = keep_fastest(rows[0], application(args, app_dir))
            same = ["Mesh/Subdomains=%d" % rows[0]["subdomains"]]
            rows[1] = keep_fastest(rows[1], driver(args, xml, os.path.join(work, "driver_auto"),
                                                   "driver, Subdomain Size Auto", []))
            rows[2] = keep_fastest(rows[2], driver(args, xml, os.path.join(work, "driver_same"),
                                                   "driver, %d METIS subdomains" % rows[0]["subdomains"], same))
            rows[3] = keep_fastest(rows[3], driver(args, xml, os.path.join(work, "driver_explicit"),
                                                   "driver, %d METIS subdomains, Dual Operator Explicit"
                                                   % rows[0]["subdomains"], same + ["Solver/FETI/Dual Operator=Explicit"]))
        with open(os.path.join(app_dir, "assembled.msh")) as f:
            lines = f.read().split("\n")
        nodes = int(lines[lines.index("$Nodes") + 1].split()[1])
    base = rows[0]["setup"] + rows[0]["solve"]
    print("size %d, %d nodes, %d ranks, 4 load steps, Algorithm 2 to 1e-10, %d round(s); load average %.1f before, "
          "%.1f after" % (args.size, nodes, args.ranks, args.repeat, load_before, os.getloadavg()[0]))
    print("| run | subdomains | primal dofs | dual dofs | n_A (4 steps) | setup s | solve s | setup + solve s "
          "| / application | application's assembly s |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        total = r["setup"] + r["solve"]
        print("| %s | %d | %d | %d | %d | %.2f | %.2f | %.2f | %.2f | %s |"
              % (r["run"], r["subdomains"], r["primal"], r["dual"], r["n_A"], r["setup"], r["solve"], total,
                 total / base, "%.2f" % r["assembly"] if r["assembly"] is not None else ""))


if __name__ == "__main__":
    main()
