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
- A run stopped while Gmsh meshes its script (a loop without end): SIGTERM
  and SIGINT to mpiexec on 1 rank, SIGTERM to mpiexec on 2 ranks with both
  cores kept busy (mpiexec ends the job by SIGKILL once a rank has died: the
  other rank must not die before rank 0 has cleaned up), and SIGTERM and
  SIGINT to a one-rank tribos without mpiexec. The run ends by the signal
  within seconds, Gmsh ends with it, and neither Gmsh's private temporary
  directory (in TMPDIR) nor a result is left.
- A run killed by SIGKILL while Gmsh meshes (no handler runs) leaves its
  directory; the next run that meshes a .geo removes it, and keeps the
  directory of a live process and one a process holds locked.

Every run must end within its timeout, and a refused run leaves no result.
"""
import contextlib
import fcntl
import glob
import os
import signal
import subprocess
import sys
import time

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


def processes_running(fragment):
    """The pids of the processes whose command line holds `fragment`."""
    pids = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open("/proc/%s/cmdline" % entry, "rb") as f:
                if fragment.encode() in f.read():
                    pids.append(int(entry))
        except OSError:
            pass
    return pids


@contextlib.contextmanager
def busy(count):
    """`count` processes spinning, so that the runs compete for the cores."""
    spinners = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(count)]
    try:
        yield
    finally:
        for s in spinners:
            s.kill()
            s.wait()


def write_loop(work, label):
    script = os.path.join(work, "loop_%s.geo" % label)  # its name finds its Gmsh
    with open(script, "w") as f:
        f.write("x = 0;\nFor i In {1:1e15}\n  x = x + 1;\nEndFor\n")
    return script


def fresh_tmp(work, label):
    tmp = os.path.join(work, "tmp_" + label)
    os.makedirs(tmp, exist_ok=True)
    for left in glob.glob(os.path.join(tmp, "tribos-geo-*")):
        subprocess.run(["rm", "-rf", left])
    return tmp


def launch_meshing(launch, script, tmp, out):
    """Starts a run of `script` and waits until its Gmsh runs."""
    p = subprocess.Popen(launch + [INPUT, "--set", "Mesh/File=" + script, "--set", "Mesh/Run Geo Script=true",
                                   "--set", "Mesh/Geo Time Limit=120", "--output", out],
                         env=dict(os.environ, TMPDIR=tmp), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         start_new_session=True)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and not (processes_running(script) and glob.glob(os.path.join(tmp, "tribos-geo-*"))):
        time.sleep(0.1)
    return p, bool(processes_running(script))


def stopped_while_meshing(launch, label, sig, work):
    """Runs LOOP (a .geo without end) through `launch` (a command line before
    the input), sends `sig` to the launched process once Gmsh runs, and
    checks what is left."""
    tmp = fresh_tmp(work, label)
    script = write_loop(work, label)
    out = os.path.join(work, "stopped_" + label)
    p, meshing = launch_meshing(launch, script, tmp, out)
    expect(meshing, "%s: Gmsh runs the script" % label)
    p.send_signal(sig)
    try:
        _, err = p.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        p.communicate()
        expect(False, "%s: the run ends within 30 s of %s" % (label, sig.name))
        return
    # The ranks are gone when the launcher returns; give the kernel a moment to reap Gmsh.
    for _ in range(20):
        if not processes_running(script):
            break
        time.sleep(0.1)
    expect(p.returncode != 0, "%s: the run ends by %s (exit %d)" % (label, sig.name, p.returncode))
    expect(not processes_running(script), "%s: Gmsh ended with the run" % label)
    left = glob.glob(os.path.join(tmp, "tribos-geo-*"))
    expect(not left, "%s: Gmsh's temporary directory removed (left: %s)" % (label, left))
    expect(not results_in(out), "%s: no result written" % label)
    if not meshing or left:
        print("--- stderr ---\n" + err[-2000:])


def killed_then_swept(tribos, work):
    """A run killed by SIGKILL leaves Gmsh's directory (no handler runs);
    the next run that meshes a .geo in the same TMPDIR removes it, but not
    the directory of a live process (named for this one) nor one that a
    process holds locked (as a run does its own)."""
    label = "sigkill"
    tmp = fresh_tmp(work, label)
    script = write_loop(work, label)
    p, meshing = launch_meshing([tribos], script, tmp, os.path.join(work, "killed"))
    expect(meshing, "%s: Gmsh runs the script" % label)
    p.kill()
    p.communicate()
    for _ in range(50):
        if not processes_running(script):
            break
        time.sleep(0.1)
    expect(not processes_running(script), "%s: Gmsh ended with the run (parent-death signal)" % label)
    left = glob.glob(os.path.join(tmp, "tribos-geo-*"))
    expect(len(left) == 1, "%s: the killed run left its directory (%s)" % (label, left))
    if len(left) != 1:
        return
    # Its name holds the run's pid before the random suffix: the same name
    # for a live pid (this process), and for a dead one held locked.
    head, pid, suffix = left[0].rsplit("-", 2)
    expect(pid == str(p.pid), "%s: the directory is named for the run's pid %d (%s)" % (label, p.pid, left[0]))
    live = "%s-%d-%s" % (head, os.getpid(), suffix)
    gone = subprocess.Popen(["true"])
    gone.wait()
    locked = "%s-%d-%s" % (head, gone.pid, suffix)
    for d in (live, locked):
        os.mkdir(d, 0o700)
        open(os.path.join(d, "gmsh.log"), "w").close()
    lock = os.open(locked, os.O_RDONLY)
    fcntl.flock(lock, fcntl.LOCK_EX)
    bad = os.path.join(work, "bad_syntax.geo")  # a run that meshes a .geo, refused at once by Gmsh
    with open(bad, "w") as f:
        f.write("x = ;\n")
    q = subprocess.run([tribos, INPUT, "--set", "Mesh/File=" + bad, "--set", "Mesh/Run Geo Script=true",
                        "--output", os.path.join(work, "after_kill")],
                       env=dict(os.environ, TMPDIR=tmp), capture_output=True, text=True, timeout=120)
    os.close(lock)
    expect(q.returncode == 1 and "Gmsh could not mesh the script" in q.stderr,
           "%s: the next run meshes its .geo (exit %d)" % (label, q.returncode), q)
    expect(not os.path.exists(left[0]), "%s: the next run removed the killed run's directory" % label)
    expect(os.path.isdir(live), "%s: the directory of a live process is kept" % label)
    expect(os.path.isdir(locked), "%s: a directory held locked is kept" % label)
    expect(sorted(glob.glob(os.path.join(tmp, "tribos-geo-*"))) == sorted([live, locked]),
           "%s: the next run removed its own directory" % label)


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

        # Stopped while Gmsh meshes: the launcher's SIGTERM and SIGINT. On
        # two ranks mpirun forwards the signal to both and kills rank 0 by
        # SIGKILL as soon as rank 1 has died: with both cores busy, rank 0's
        # handler then came too late unless rank 1 waits for it.
        mpiexec = [np_ if c == "NP" else c for c in command[:-1]] + [command[-1]]
        if np_ == "1":
            for sig in (signal.SIGTERM, signal.SIGINT):
                stopped_while_meshing(mpiexec, "mpiexec_%s_np1" % sig.name, sig, work)
        else:
            with busy(2):
                stopped_while_meshing(mpiexec, "mpiexec_SIGTERM_np2", signal.SIGTERM, work)
    # The same signals to tribos itself, one rank without mpiexec.
    for sig in (signal.SIGTERM, signal.SIGINT):
        stopped_while_meshing([command[-1]], "tribos_%s" % sig.name, sig, work)
    killed_then_swept(command[-1], work)
    if failures:
        sys.exit("%d check(s) failed" % len(failures))


if __name__ == "__main__":
    main()
