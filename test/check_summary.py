#!/usr/bin/python3
"""Runs the tribos driver and checks conditions on its JSON summary.

usage: check_summary.py SUMMARY.json "python expression on s" ... -- COMMAND ...
Each expression sees the summary as the dict s; the test fails when the
command fails or an expression is false.
"""
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts"))
import tribos_summary  # noqa: E402

sep = sys.argv.index("--")
summary, checks, cmd = sys.argv[1], sys.argv[2:sep], sys.argv[sep + 1:]
subprocess.run(cmd, check=True)
s = tribos_summary.load(summary)
failed = [c for c in checks if not eval(c, {}, {"s": s})]
for c in checks:
    print(("FAILED: " if c in failed else "ok: ") + c)
sys.exit(1 if failed else 0)
