#!/usr/bin/python3
"""The memory estimate made before a run (drivers/src/Tribos_MemoryEstimate.hpp)
against the peak resident size the run then reaches, per rank, side by side
in one run of each case: a Markdown table for docs/benchmarks.md.

  scripts/bench_memory.py [--tribos build/drivers/tribos] [--cases WORD ...]
"""
import argparse
import json
import os
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# (label, ranks, input, --set overrides)
CASES = [
    ("brick linear, FETI, k = 16", 1, "brick_linear.xml", ["Mesh/Level=16"]),
    ("brick linear, FETI, Tet10, k = 8", 1, "brick_linear.xml", ["Mesh/Level=8", "Mesh/Element=Tet10"]),
    ("brick linear, FETI, Hex20, k = 8", 1, "brick_linear.xml", ["Mesh/Level=8", "Mesh/Element=Hex20"]),
    ("brick linear, FETI, Tet10, k = 8, METIS", 1, "brick_linear.xml",
     ["Mesh/Level=8", "Mesh/Element=Tet10", "Mesh/Partitioner=METIS", "Mesh/Subdomains=6"]),
    ("brick linear, monolithic CG+MueLu, k = 16", 1, "brick_linear.xml", ["Mesh/Level=16", "Solver/Type=Monolithic"]),
    ("brick linear, monolithic Direct, k = 8", 1, "brick_linear.xml",
     ["Mesh/Level=8", "Solver/Type=Monolithic", "Solver/Monolithic/Linear Solver=Direct"]),
    ("brick Coulomb F = 0.3, Tet4, k = 8", 1, "brick_coulomb_F03.xml", ["Mesh/Level=8"]),
    ("brick Coulomb F = 0.3, Tet4, k = 14", 1, "brick_coulomb_F03.xml", ["Mesh/Level=14"]),
    ("brick Coulomb F = 0.3, Hex8, k = 16", 1, "brick_coulomb_F03.xml", ["Mesh/Level=16", "Mesh/Element=Hex8"]),
    ("brick Coulomb F = 0.3, Tet4, k = 16, 3 ranks", 3, "brick_coulomb_F03.xml", ["Mesh/Level=16"]),
    ("prism Tresca, semismooth*, L = 3", 1, "prism_tresca.xml", ["Mesh/Level=3"]),
    ("prism Tresca, semismooth*, L = 6", 1, "prism_tresca.xml", ["Mesh/Level=6"]),
    ("cube scalability", 1, "cube_scalability.xml", []),
]


def run(tribos, ranks, inp, sets):
    with tempfile.TemporaryDirectory() as tmp:
        summary = os.path.join(tmp, "s.json")
        cmd = ["mpirun", "-np", str(ranks), "--oversubscribe"] + (["--allow-run-as-root"] if os.getuid() == 0 else [])
        cmd += [tribos, os.path.join(ROOT, "input", inp), "--summary", summary, "--quiet",
                "--set", "Output/Write Results=false"]
        for s in sets:
            cmd += ["--set", s]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
        with open(summary) as f:
            return json.load(f)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--tribos", default=os.path.join(ROOT, "build/drivers/tribos"))
    ap.add_argument("--cases", nargs="+", help="the cases whose label contains one of these words (default: all)")
    a = ap.parse_args()
    print("| case | nodes | estimate [MB] | peak RSS [MB] | estimate / peak |")
    print("|---|---|---|---|---|")
    for label, ranks, inp, sets in CASES:
        if a.cases and not any(w in label for w in a.cases):
            continue
        s = run(a.tribos, ranks, inp, sets)
        est, peak = s["memory_estimate_mb"], s["peak_rss_mb"]
        print("| %s | %d | %.0f | %.0f | %.2f |" % (label, s["nodes"], est, peak, est / peak))


if __name__ == "__main__":
    main()
