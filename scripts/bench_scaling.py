#!/usr/bin/python3
"""Scaling benchmark: the brick with Coulomb friction F = 0.3 (the outer
algorithm of the input: Auto, the matrix-free Newton method, unless --set names one)
from a hundred thousand to a few million degrees of freedom, side by side with
the linear elastic solve of the same mesh by the monolithic Belos CG + MueLu
path on the same ranks, and with the memory bandwidth of the machine.

usage: scripts/bench_scaling.py [--levels 24 36 48] [--sizes 6 | Auto ...] [--ranks 2]
           [--tolerance 1e-4] [--precision Single] [--no-linear]
           [--set NAME=VALUE ...] [--tribos build/drivers/tribos]

For every level k (k cells per unit length of the 3 x 1 x 1 brick: 3k x k x k
cubes of 6 tetrahedra) and subdomain size H (Mesh/Subdomain Size, cells per
subdomain edge) it prints one row: mesh dofs, primal and dual dofs,
subdomains, coarse dimension, setup (assembly, factorization, dense blocks),
factorization, applications of F and the time of one, the bandwidth bound of
one (the dense blocks' bytes on a rank over the bandwidth one rank gets while
all ranks run, from tribos_stream_triad), solve time, total wall time of the
run (mesh to result check, no output files), outer iterations, n_A, the
largest KKT residual of the result, peak RSS per rank, and the wall time of
the linear solve with the ratio of the two. docs/scaling.md and
docs/benchmarks.md hold its tables.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def mpirun(ranks):
    cmd = ["mpirun", "-np", str(ranks), "--oversubscribe"]
    if os.getuid() == 0:
        cmd.append("--allow-run-as-root")
    return cmd


def run(cmd):
    """Runs the driver with a summary file; returns (summary, wall seconds)."""
    with tempfile.TemporaryDirectory() as tmp:
        summary = os.path.join(tmp, "summary.json")
        t0 = time.monotonic()
        proc = subprocess.run(cmd + ["--summary", summary, "--set", "Output/Write Results=false",
                                     "--set", "Output/Directory=" + os.path.join(tmp, "out")],
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        wall = time.monotonic() - t0
        if not os.path.exists(summary):
            sys.exit("bench_scaling: the run failed (exit %d): %s\n%s" % (proc.returncode, " ".join(cmd), proc.stderr))
        with open(summary) as f:
            return json.load(f), wall


def bandwidth(bench, ranks, precision):
    """GB/s one rank gets for the packed symmetric product while all ranks run."""
    out = subprocess.run(mpirun(ranks) + [bench, "--mb", "600", "--repeat", "5"], check=True,
                         stdout=subprocess.PIPE, text=True).stdout
    rows = {}
    for line in out.splitlines():
        m = re.match(r"(\w+)\s.*?([\d.]+) GB/s", line)
        if m:
            rows[m.group(1)] = float(m.group(2))
    kernel = "mixed" if precision == "Single" else "dspmv"
    return rows["triad"] / ranks, rows[kernel] / ranks, out


def subdomain_size(text):
    """A Mesh/Subdomain Size value: a whole number >= 1 or Auto."""
    if text == "Auto" or (text.isdigit() and int(text) >= 1):
        return text
    raise argparse.ArgumentTypeError("%r: expected a whole number >= 1 or Auto" % text)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--levels", type=int, nargs="+", default=[24, 36, 48])
    ap.add_argument("--sizes", type=subdomain_size, nargs="+", default=["6"],
                    help="Mesh/Subdomain Size values: whole numbers or Auto (the H it chose is printed)")
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--tolerance", type=float, default=1e-4,
                    help="relative tolerance of the contact solve (Algorithm 2's, which Auto's Newton method takes)")
    ap.add_argument("--precision", choices=["Double", "Single"], default="Single", help="dense block precision")
    ap.add_argument("--no-linear", action="store_true", help="skip the monolithic linear solve")
    ap.add_argument("--element", choices=["Tet4", "Hex8", "Tet10", "Hex20"],
                    help="Mesh/Element of both runs (default: the inputs', Tet4)")
    ap.add_argument("--set", action="append", default=[], help="extra NAME=VALUE for the contact runs")
    ap.add_argument("--tribos", default=os.path.join(ROOT, "build/drivers/tribos"))
    ap.add_argument("--stream", default=os.path.join(ROOT, "build/drivers/bench/tribos_stream_triad"))
    args = ap.parse_args()
    for exe in (args.tribos, args.stream):
        if not os.access(exe, os.X_OK):
            sys.exit("bench_scaling: %s is not built (scripts/build.sh builds it)" % exe)

    triad, spmv, raw = bandwidth(args.stream, args.ranks, args.precision)
    print("Memory bandwidth per rank with %d ranks running: triad %.1f GB/s, packed product (%s) %.1f GB/s"
          % (args.ranks, triad, args.precision.lower(), spmv))
    print()
    print("| k | H | mesh dofs | primal | dual | S | coarse | setup s | factor s | F apps | F ms | bound ms "
          "| solve s | wall s | Iter | n_A | KKT max | RSS/rank GB | linear s | ratio |")
    print("|---" * 20 + "|")
    element = ["--set", "Mesh/Element=" + args.element] if args.element else []
    for level in args.levels:
        linear = None
        if not args.no_linear:
            s, wall = run(mpirun(args.ranks) + [args.tribos, os.path.join(ROOT, "input/brick_linear.xml"),
                                                "--set", "Mesh/Level=%d" % level, "--set", "Solver/Type=Monolithic",
                                                "--set", "Mesh/Subdomain Grid={%d,1,1}" % args.ranks] + element)
            linear = (wall, s)
        for H in args.sizes:
            cmd = mpirun(args.ranks) + [args.tribos, os.path.join(ROOT, "input/brick_coulomb_F03.xml"),
                                        "--set", "Mesh/Level=%d" % level, "--set", "Mesh/Subdomain Size=" + H,
                                        "--set", "Solver/Algorithm 2/Relative Tolerance=%g" % args.tolerance,
                                        "--set", "Solver/FETI/Dense Block Precision=" + args.precision] + element
            for e in args.set:
                cmd += ["--set", e]
            s, wall = run(cmd)
            mesh_dofs = 3 * s["nodes"]
            f_ms = 1e3 * s["time_F_apply_s"] / max(s["F_applications"], 1)
            bound_ms = 1e3 * s["dense_block_memory_mb"] * 1048576.0 / (spmv * 1e9)
            kkt = max(v for k, v in s["kkt"].items() if k not in ("displacement_scale", "force_scale", "tolerance", "limit"))
            ok = "" if s["converged"] else " (not converged)"
            lin = ("%.1f | %.2f" % (linear[0], wall / linear[0])) if linear else "- | -"
            chosen = "%d" % s["subdomain_size"] if H != "Auto" else "Auto: %d" % s["subdomain_size"]
            print("| %d | %s | %d | %d | %d | %d | %d | %.1f | %.1f | %d | %.1f | %.1f | %.1f | %.1f | %d | %d | %.1e%s | %.2f | %s |"
                  % (level, chosen, mesh_dofs, s["primal_dofs"], s["dual_dofs"], s["subdomains"], s["coarse_size"],
                     s["time_setup_s"], s["time_factor_s"], s["F_applications"], f_ms, bound_ms, s["time_solve_s"],
                     wall, s["outer_iterations"], s["n_A"], kkt, ok, s["peak_rss_mb"] / 1024.0, lin))
            sys.stdout.flush()
    print()
    print("tribos_stream_triad (%d ranks):" % args.ranks)
    print(raw.rstrip())


if __name__ == "__main__":
    main()
