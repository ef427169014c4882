#!/bin/bash
# FCLIB problems by Siconos' fc3d solvers and Tribos' friction algorithms,
# side by side (drivers/bench/fclib_vs_siconos.cpp; docs/benchmarks.md):
# every file of the development set, then the seed brick (F = 0.3) exported
# by tribos --export-fclib at Mesh/Level = 4, 8, 12, then a problem of two
# bodies with 534 contacts and dense rows of W: Cattaneo-Mindlin Level 3
# sheared to Q* in one step (input/cattaneo_mindlin.xml, Load Steps/Times =
# {5}).
#   scripts/bench_fclib.sh [BUILD_DIR] [OUT_DIR]     (defaults: build, output/bench_fclib)
# Environment: TOL (1e-8), REPEAT (5), LEVELS ("4 8 12"), DEV (the dev set
# directory), TRIBOS_ALGORITHMS ("Semismooth Newton,NSGS,Algorithm2,MSA+Algorithm1")
# for the dev set; BRICK_REPEAT (1) and BRICK_ALGORITHMS ("Semismooth
# Newton,Algorithm2": MSA + Algorithm 1 does not reach 1e-8 there) for the bricks;
# MULTIBODY_REPEAT (3) and MULTIBODY_ALGORITHMS ("Semismooth Newton,NSGS,
# Algorithm2") for the two-body problem;
# REUSE=1: each library's method made once for the repeated solves (--reuse,
# the time-stepping use) instead of anew for every run.
# Needs the build configured with Siconos numerics (libsiconos-numerics-dev).
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$here/build}
out=${2:-$here/output/bench_fclib}
tol=${TOL:-1e-8}
repeat=${REPEAT:-5}
levels=${LEVELS:-"4 8 12"}
dev=${DEV:-$here/../shared/fclib/dev}
algorithms=${TRIBOS_ALGORITHMS:-"Semismooth Newton,NSGS,Algorithm2,MSA+Algorithm1"}
brick_repeat=${BRICK_REPEAT:-1}
brick_algorithms=${BRICK_ALGORITHMS:-"Semismooth Newton,Algorithm2"}
reuse=${REUSE:+--reuse}
bench=$build/drivers/bench/tribos_fclib_vs_siconos
if [ ! -x "$bench" ]; then
  echo "bench_fclib.sh: $bench is missing (configure with libsiconos-numerics-dev installed," \
       "then cmake --build $build --target tribos_fclib_vs_siconos)" >&2
  exit 1
fi
mkdir -p "$out"
for f in "$dev"/*.hdf5; do
  "$bench" "$f" --tolerance "$tol" --repeat "$repeat" --tribos "$algorithms" $reuse
  echo
done
for k in $levels; do
  file=$out/brick_F03_L$k.hdf5
  if [ ! -s "$file" ]; then
    "$build/drivers/tribos" "$here/input/brick_coulomb_F03.xml" --set "Mesh/Level=$k" --quiet \
      --output "$out/brick_F03_L$k" --export-fclib "$file" > /dev/null
  fi
  "$bench" "$file" --tolerance "$tol" --repeat "$brick_repeat" --tribos "$brick_algorithms" $reuse
  echo
done
file=$out/cattaneo_mindlin_L3_Qstar.hdf5
if [ ! -s "$file" ]; then
  "$build/drivers/tribos" "$here/input/cattaneo_mindlin.xml" --set "Mesh/File=cattaneo_mindlin_3.msh" \
    --set "Load Steps/Times={5}" --quiet --output "$out/cattaneo_mindlin_L3_Qstar" --export-fclib "$file" > /dev/null
fi
"$bench" "$file" --tolerance "$tol" --repeat "${MULTIBODY_REPEAT:-3}" \
  --tribos "${MULTIBODY_ALGORITHMS:-Semismooth Newton,NSGS,Algorithm2}" $reuse
