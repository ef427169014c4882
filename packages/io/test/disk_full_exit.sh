#!/bin/bash
# usage: disk_full_exit.sh NP MPIEXEC NUMPROC_FLAG PROGRAM [MPIEXEC FLAGS...]
# Runs the disk-full test program as a driver would run (--exit-status): its
# result does not fit under a file size limit, so every rank must end (no
# hang) with status 3, the error must be printed once, and nothing may crash.
set -u
np=$1 mpiexec=$2 numproc=$3 program=$4
shift 4
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
ulimit -c unlimited 2>/dev/null  # a crash would leave a core here
timeout 300 "$mpiexec" "$numproc" "$np" "$@" "$program" --exit-status >out.txt 2>err.txt
status=$?
cat out.txt err.txt
fail=0
if [ $status -eq 124 ]; then echo "FAILED: no end within 300 s (hang)"; fail=1; fi
if [ $status -ne 3 ]; then echo "FAILED: exit status $status, expected 3"; fail=1; fi
messages=$(grep -c "^io_test_disk_full: error: " err.txt)
if [ "$messages" -ne 1 ]; then echo "FAILED: $messages error messages, expected 1"; fail=1; fi
if grep -qiE "segmentation|core dumped|exited on signal|MPI_ABORT" out.txt err.txt; then echo "FAILED: a crash or an abort"; fail=1; fi
if ls core* >/dev/null 2>&1; then echo "FAILED: core dump"; fail=1; fi
[ $fail -eq 0 ] && echo "disk_full_exit np $np: passed"
exit $fail
