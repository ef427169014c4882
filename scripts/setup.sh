#!/usr/bin/env bash
# Command 1: install what is missing, build, run the main example on 2 ranks.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
scripts/build.sh
flags=(--oversubscribe)
[ "$(id -u)" -eq 0 ] && flags+=(--allow-run-as-root)
mpirun "${flags[@]}" -np 2 build/drivers/tribos input/brick_linear.xml \
  --output output/brick_linear --summary output/brick_linear/summary.json
echo "Results: output/brick_linear/solution.xmf (open in ParaView)"
