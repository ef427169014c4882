#!/usr/bin/python3
"""Mesh files the bad-input table cannot say, run through the driver on 1
and 2 ranks:

  hostile_mesh_files.py --work DIR -- MPIEXEC ... NP ... TRIBOS

- A .geo whose System command creates a file (by absolute path): refused
  without Mesh/Run Geo Script (exit 1, the parameter named) and the file is
  not created; with the opt-in the command runs (the file appears) and the
  run converges, which shows that the first check can fail.
- A FIFO named as a .msh Mesh/File (nobody writes to it, so opening it would
  block): refused as not a regular file within seconds, exit 1.

Every run must end within its timeout, and a refused run leaves no result.
"""
import os
import subprocess
import sys

SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))
INPUT = os.path.join(SOURCE, "input", "gmsh_block_pressure.xml")
failures = []


def run(command, np_, args, timeout=120):
    mpi = [np_ if c == "NP" else c for c in command[:-1]]
    full = mpi + [command[-1], INPUT] + args
    try:
        p = subprocess.run(full, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        failures.append("no exit within %d s (hang): %s" % (timeout, " ".join(full)))
        return None
    return p


def expect(ok, what, p=None):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)
        if p is not None:
            print("--- stderr ---\n" + p.stderr[-2000:])


def results_in(out):
    return [n for n in os.listdir(out) if n.endswith((".h5", ".xmf", ".json"))] if os.path.isdir(out) else []


def main():
    sep = sys.argv.index("--")
    opts, command = sys.argv[1:sep], sys.argv[sep + 1:]
    work = os.path.abspath(opts[opts.index("--work") + 1])
    os.makedirs(work, exist_ok=True)
    for np_ in ("1", "2"):
        # A script that runs a shell command, then meshes the shipped block.
        mark = os.path.join(work, "system_ran_np" + np_)
        if os.path.exists(mark):
            os.remove(mark)
        script = os.path.join(work, "system_np%s.geo" % np_)
        with open(script, "w") as f:
            f.write('System "touch %s";\nInclude "%s";\n' % (mark, os.path.join(SOURCE, "input", "gmsh_block.geo")))
        out = os.path.join(work, "refused_np" + np_)
        p = run(command, np_, ["--set", "Mesh/File=" + script, "--output", out])
        if p is not None:
            expect(p.returncode == 1 and "set Mesh/Run Geo Script = true" in p.stderr,
                   "np %s: the .geo is refused without the opt-in (exit %d)" % (np_, p.returncode), p)
            expect(not os.path.exists(mark), "np %s: its System command did not run" % np_)
            expect(not results_in(out), "np %s: the refused run wrote no result" % np_)
        out = os.path.join(work, "allowed_np" + np_)
        p = run(command, np_, ["--set", "Mesh/File=" + script, "--set", "Mesh/Run Geo Script=true", "--output", out])
        if p is not None:
            expect(p.returncode == 0, "np %s: with the opt-in the .geo is meshed and the run converges (exit %d)"
                   % (np_, p.returncode), p)
            expect(os.path.exists(mark), "np %s: with the opt-in its System command ran" % np_)

        # A FIFO with a mesh file's name.
        fifo = os.path.join(work, "pipe_np%s.msh" % np_)
        if os.path.exists(fifo):
            os.remove(fifo)
        os.mkfifo(fifo)
        out = os.path.join(work, "fifo_np" + np_)
        p = run(command, np_, ["--set", "Mesh/File=" + fifo, "--output", out], timeout=60)
        if p is not None:
            expect(p.returncode == 1 and 'mesh file "%s" is a FIFO (named pipe), not a regular file' % fifo in p.stderr,
                   "np %s: a FIFO as Mesh/File is refused (exit %d)" % (np_, p.returncode), p)
            expect(not results_in(out), "np %s: the refused run wrote no result" % np_)
        os.remove(fifo)
    if failures:
        sys.exit("%d check(s) failed" % len(failures))


if __name__ == "__main__":
    main()
