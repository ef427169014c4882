#!/usr/bin/env bash
# Numerical scalability of the FETI solver (docs/benchmarks.md): the unit cube
# of input/cube_scalability.xml with n x n x n subdomains of 4 x 4 x 4 cells
# (fixed H/h = 4), n = 2..5, on 1 and 2 MPI ranks, for every preconditioner of
# the projected CG. Writes one --summary JSON per run and prints a Markdown table.
#
#   scripts/bench_feti.sh [BUILD_DIR] [OUT_DIR]
#
# Environment: ELEMENT=Hex8|Tet4 (default Hex8), SIZES="2 3 4 5",
# RANKS="1 2", PRECONDITIONERS="None Lumped" (a dash stands for a space:
# "Lumped-Unscaled"), EXTRA_SET="Key=value" (one more
# --set, e.g. "Solver/FETI/Local Solver=Tacho").
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
OUT=${2:-output/bench_feti}
ELEMENT=${ELEMENT:-Hex8}
SIZES=${SIZES:-"2 3 4 5"}
RANKS=${RANKS:-"1 2"}
PRECONDITIONERS=${PRECONDITIONERS:-"None Lumped"}
EXE="$BUILD/drivers/tribos"
[ -x "$EXE" ] || { echo "no driver at $EXE; build the target tribos first" >&2; exit 1; }
mkdir -p "$OUT"
MPIRUN=(mpirun)
[ "$(id -u)" = 0 ] && MPIRUN+=(--allow-run-as-root)
MPIRUN+=(--oversubscribe)

for n in $SIZES; do
  cells=$((4 * n))
  for pc in $PRECONDITIONERS; do
    for np in $RANKS; do
      json="$OUT/${ELEMENT}_S$((n * n * n))_${pc}_np${np}.json"
      args=(input/cube_scalability.xml --summary "$json"
            --set "Mesh/Element=$ELEMENT"
            --set "Mesh/Subdomain Grid={$n,$n,$n}"
            --set "Mesh/Cells={$cells,$cells,$cells}"
            --set "Solver/FETI/Projected CG/Preconditioner=${pc//-/ }")
      [ -n "${EXTRA_SET:-}" ] && args+=(--set "$EXTRA_SET")
      "${MPIRUN[@]}" -np "$np" "$EXE" "${args[@]}" > "$OUT/$(basename "$json" .json).log" 2>&1 ||
        echo "run failed: $json (see the .log)" >&2
    done
  done
done

/usr/bin/python3 - "$OUT" "$ELEMENT" <<'PY'
import glob, json, os, sys
out, element = sys.argv[1], sys.argv[2]
order = {"None": 0, "Lumped": 1, "Lumped Unscaled": 2}
print("| element | S | ranks | precond. | primal dofs | dual dofs | PCG it. | n_A | setup [s] | solve [s] | peak RSS [MB] | converged |")
print("|---|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---|")
entries = []
for f in glob.glob(os.path.join(out, element + "_S*.json")):
    d = json.load(open(f))
    p = os.path.basename(f).split("_")[2].replace("-", " ")
    entries.append((d["subdomains"], order.get(p, 9), d["ranks"], p, d))
for s, _, r, p, d in sorted(entries):
    print("| %s | %d | %d | %s | %d | %d | %d | %d | %.2f | %.2f | %.0f | %s |" % (
        d["element"], s, r, p, d["primal_dofs"], d["dual_dofs"], d["outer_iterations"], d["n_A"],
        d["time_setup_s"], d["time_solve_s"], d["peak_rss_mb"], d["converged"]))
PY
