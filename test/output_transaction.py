#!/usr/bin/python3
"""The output of a run is a transaction; three ways to try to break it:

  output_transaction.py concurrent --work DIR -- MPIEXEC... TRIBOS
      a second run into the directory a first run is writing is refused at
      once ("in use by another run"); the first run completes its set.
  output_transaction.py kill --work DIR -- MPIEXEC... TRIBOS
      runs killed (SIGKILL) at many moments never leave a mixed set: a
      summary (the set's last file) always comes with the h5 and xmf of the
      same run; the next run removes the killed runs' temporaries.
  output_transaction.py history-kill --work DIR -- MPIEXEC... TRIBOS
      a load history of 400 steps killed (SIGKILL) at many moments, each
      time continued by --restart, until it completes: after every kill the
      directory holds a consistent set (the summary counts k steps; the
      steps table has k complete rows, each naming a step file whose SHA-256
      it records; the history has rows of steps 1..k); --restart always
      accepts what a kill left; the completed series equals the
      uninterrupted run's (every step's displacement to 1e-12, its index,
      steps table rows and history rows one per step).
  output_transaction.py disk-full --np N --work DIR -- MPIEXEC... TRIBOS
      output on filesystems too small for the result (tmpfs of 256 kB, and of
      sizes around the result's, where the HDF5 file fits but its index or
      summary may not): every run ends on every rank with exit 1 (refused
      before any work by the estimate of its output) or 3 (the disk filled),
      one clear message and nothing left, or with exit 0 and a complete set;
      no hang, no crash. Skipped (exit 0 with a message) where mount is refused.

MPIEXEC may contain the token NP, replaced by the rank count.
"""
import glob
import json
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree

HERE = os.path.dirname(os.path.abspath(__file__))
INPUT = os.path.join(os.path.dirname(HERE), "input", "brick_coulomb_F03.xml")


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def command(mpi, tribos, np_, out, *sets, name="run"):
    cmd = [np_ if c == "NP" else c for c in mpi] + [tribos, INPUT, "--output", out, "--quiet"]
    # Algorithm 2: check_sets counts its loops in the history.
    for s in sets + ("Problem Name=" + name, "Solver/Outer Algorithm=Algorithm2"):
        cmd += ["--set", s]
    return cmd


def check_sets(out):
    """Every summary in out comes with the h5, xmf, parameters and history of the same run."""
    import h5py
    for summary in glob.glob(os.path.join(out, "*.json")):
        base = summary[:-5]
        with open(summary) as f:
            s = json.load(f)
        for ext in (".h5", ".xmf", ".parameters.xml", ".history.csv"):
            if not os.path.exists(base + ext):
                fail("%s without its %s" % (summary, ext))
        with h5py.File(base + ".h5", "r") as h5:
            problem = h5.attrs["problem"]
            problem = problem.decode() if isinstance(problem, bytes) else problem
            if problem != s["problem"] or int(h5.attrs["converged"]) != int(s["converged"]):
                fail("%s and its h5 come from different runs (%s, %s)" % (summary, s["problem"], problem))
            with open(base + ".xmf") as f:
                for ref in re.findall(r">[^<>:]+\.h5:(/[^<]+)<", f.read()):
                    if ref not in h5:
                        fail("the xmf names %s, which the h5 of %s lacks" % (ref, s["problem"]))
        root = xml.etree.ElementTree.parse(base + ".parameters.xml").getroot()
        names = [p.get("value") for p in root.findall("Parameter") if p.get("name") == "Problem Name"]
        if names != [s["problem"]]:
            fail("%s and its parameters come from different runs (%s, %s)" % (summary, s["problem"], names))
        # The history has the summary's outer iterations (one row per
        # Algorithm 2 loop: the run's input) and ends at its n_A.
        with open(base + ".history.csv") as f:
            rows = [line.split(",") for line in f.read().splitlines()[1:]]
        if len(rows) != s["outer_iterations"] or float(rows[-1][4]) != s["n_A"]:
            fail("%s and its history come from different runs (%d rows, n_A %s; summary %d, %d)"
                 % (summary, len(rows), rows[-1][4] if rows else "-", s["outer_iterations"], s["n_A"]))


def temporaries(out):
    return [n for n in os.listdir(out) if n.endswith(".tmp")]


def concurrent(mpi, tribos, work):
    out = os.path.join(work, "out")
    # Level 18 runs about 9 s alone: long enough to outlast the start of the
    # second run (mpirun on 2 ranks) while other tests load the machine.
    first = subprocess.Popen(command(mpi, tribos, "1", out, "Mesh/Level=18", name="first"),
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    # The first run holds the directory once its lock file exists.
    for _ in range(200):
        if os.path.exists(os.path.join(out, ".tribos.lock")):
            break
        time.sleep(0.05)
    time.sleep(0.3)
    t = time.time()
    second = subprocess.run(command(mpi, tribos, "2", out, "Mesh/Level=4", name="second"),
                            capture_output=True, text=True, timeout=120)
    waited = time.time() - t
    if first.poll() is not None:
        fail("the first run ended before the second started; make it longer")
    if second.returncode != 1 or "in use by another run" not in second.stderr:
        fail("second run: exit %d, stderr %s" % (second.returncode, second.stderr))
    if waited > 20:
        fail("the second run took %.1f s to be refused" % waited)
    out1, err1 = first.communicate(timeout=600)
    if first.returncode != 0:
        fail("first run: exit %d\n%s" % (first.returncode, err1))
    check_sets(out)
    with open(os.path.join(out, "solution.json")) as f:
        if json.load(f)["problem"] != "first":
            fail("the set is not the first run's")
    print("ok: the second run was refused in %.1f s: %s" % (waited, second.stderr.strip()))


def wait_until_gone(group, out, timeout=60):
    """Waits until the killed run has no process left: mpirun (its process
    group) and the rank that holds the output lock, which Open MPI starts in
    a group of its own and which may still be exiting after mpirun is
    reaped (until it has, the next run is refused, rightly)."""
    end = time.time() + timeout

    def alive(pid):
        try:
            with open("/proc/%d/stat" % pid) as f:
                return f.read().rsplit(")", 1)[1].split()[0] != "Z"
        except (FileNotFoundError, ProcessLookupError, IndexError):
            return False

    def group_alive():
        try:
            os.killpg(group, 0)
            return True
        except ProcessLookupError:
            return False

    def holder():
        try:
            with open(os.path.join(out, ".tribos.lock")) as f:
                words = f.read().split()
            return int(words[0]) if words else 0
        except (FileNotFoundError, ValueError):
            return 0

    while time.time() < end:
        pid = holder()
        if not group_alive() and not (pid and pid != os.getpid() and alive(pid)):
            return
        time.sleep(0.02)
    fail("processes of a killed run still exist %d s after the kill" % timeout)


def kill(mpi, tribos, work):
    out = os.path.join(work, "out")
    done = subprocess.run(command(mpi, tribos, "1", out, "Mesh/Level=4", name="complete"),
                          capture_output=True, text=True, timeout=600)
    if done.returncode != 0:
        fail("the first run failed: " + done.stderr)
    # How long a run takes, to spread the kills over it.
    t = time.time()
    subprocess.run(command(mpi, tribos, "1", out, "Mesh/Level=8", name="timed"), capture_output=True, timeout=600)
    duration = time.time() - t
    random.seed(1)
    kills = 0
    for k in range(12):
        delay = duration * (0.3 + 0.7 * random.random())
        p = subprocess.Popen(command(mpi, tribos, "1", out, "Mesh/Level=8", name="killed%d" % k),
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
        time.sleep(delay)
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGKILL)
            kills += 1
        p.wait()
        wait_until_gone(p.pid, out)
        check_sets(out)
    last = subprocess.run(command(mpi, tribos, "1", out, "Mesh/Level=4", name="after"),
                          capture_output=True, text=True, timeout=600)
    if last.returncode != 0:
        fail("the run after the kills failed: " + last.stderr)
    check_sets(out)
    if temporaries(out):
        fail("temporaries of killed runs remain: %s" % temporaries(out))
    print("ok: %d runs killed between %.1f and %.1f s, every state consistent" % (kills, 0.3 * duration, duration))


HISTORY_STEPS = 400


def history_command(mpi, tribos, out, extra=()):
    times = "{" + ", ".join(repr((k + 1) / 100.0) for k in range(HISTORY_STEPS)) + "}"
    linear = os.path.join(os.path.dirname(HERE), "input", "brick_linear.xml")
    return [("2" if c == "NP" else c) for c in mpi] + [tribos, linear, "--output", out, "--quiet",
                                                      "--set", "Mesh/Level=3", "--set", "Load Steps/Times=" + times] + list(extra)


def check_history(out):
    """The set a killed history leaves: returns the steps its summary counts."""
    import hashlib
    summary = os.path.join(out, "solution.json")
    if not os.path.exists(summary):
        return 0
    with open(summary) as f:
        s = json.load(f)
    k = s["steps_completed"]
    with open(os.path.join(out, s["steps_file"])) as f:
        lines = f.read().split("\n")
    if len(lines) - 1 < k:
        fail("the summary counts %d steps, the steps table has %d complete rows" % (k, len(lines) - 1))
    for i, line in enumerate(lines[:k], 1):
        row = json.loads(line)
        path = os.path.join(out, row["file"])
        if row["step"] != i or not os.path.exists(path):
            fail("row %d of the steps table: step %s, file %s" % (i, row["step"], row["file"]))
        with open(path, "rb") as f:
            if hashlib.sha256(f.read()).hexdigest() != row["sha256"]:
                fail("step %d's file %s is not the one its row records" % (i, row["file"]))
    with open(os.path.join(out, "solution.history.csv")) as f:
        steps = {int(line.split(",")[6]) for line in f.read().splitlines()[1:] if line.count(",") == 6}
    if not set(range(1, k + 1)) <= steps:
        fail("the history lacks rows of steps %s" % sorted(set(range(1, k + 1)) - steps))
    return k


def steps_counted(out):
    """The steps the summary in out counts (0 while there is none)."""
    try:
        with open(os.path.join(out, "solution.json")) as f:
            return json.load(f)["steps_completed"]
    except (OSError, ValueError, KeyError):
        return 0


def history_kill(mpi, tribos, work):
    import h5py
    import numpy as np
    reference, out = os.path.join(work, "reference"), os.path.join(work, "out")
    done = subprocess.run(history_command(mpi, tribos, reference), capture_output=True, text=True, timeout=600)
    if done.returncode != 0:
        fail("the uninterrupted history failed: " + done.stderr)
    random.seed(2)
    kills, restarts = 0, 0
    for attempt in range(40):
        k = check_history(out) if os.path.isdir(out) else 0
        if k == HISTORY_STEPS:
            break
        extra = ["--restart", out] if k > 0 else []
        restarts += 1 if k > 0 else 0
        p = subprocess.Popen(history_command(mpi, tribos, out, extra), stdout=subprocess.DEVNULL,
                             stderr=subprocess.PIPE, text=True, start_new_session=True)
        # Killed once the run has written a few more steps, at a random
        # moment after: while a step is solved, written or committed.
        if attempt < 8:
            target = k + random.randint(5, 40)
            while p.poll() is None and steps_counted(out) < target:
                time.sleep(0.005)
            time.sleep(0.03 * random.random())
            if p.poll() is None:
                # Rank 0 (the lock's holder, in a process group of its own
                # under mpirun) at once, then the launcher's group.
                try:
                    with open(os.path.join(out, ".tribos.lock")) as f:
                        os.kill(int(f.read().split()[0]), signal.SIGKILL)
                except (OSError, ValueError, IndexError):
                    pass
                os.killpg(p.pid, signal.SIGKILL)
                kills += 1
        _, err = p.communicate()
        print("attempt %d: from step %d, exit %d, %d steps counted" % (attempt, k, p.returncode, steps_counted(out)))
        wait_until_gone(p.pid, out)
        if p.returncode not in (0, -signal.SIGKILL, 128 + signal.SIGKILL, 137):
            fail("a run of the history (after %d steps) ended with exit %d:\n%s" % (k, p.returncode, err))
    if check_history(out) != HISTORY_STEPS:
        fail("the history did not complete after %d kills" % kills)
    if kills < 4:
        fail("only %d runs were killed before they ended" % kills)
    with open(os.path.join(out, "solution.steps.jsonl")) as f:
        rows = [json.loads(line) for line in f]
    with open(os.path.join(reference, "solution.steps.jsonl")) as f:
        ref_rows = [json.loads(line) for line in f]
    if [(r["step"], r["time"], r["file"]) for r in rows] != [(r["step"], r["time"], r["file"]) for r in ref_rows]:
        fail("the steps table of the continued history is not the uninterrupted one's")
    with open(os.path.join(out, "solution.history.csv")) as f:
        steps = [int(line.split(",")[6]) for line in f.read().splitlines()[1:]]
    if steps != list(range(1, HISTORY_STEPS + 1)):
        fail("the history of the continued run is not one row a step in order")
    index = xml.etree.ElementTree.parse(os.path.join(out, "solution.xmf")).getroot()
    if len(index.find("Domain").find("Grid").findall("Grid")) != HISTORY_STEPS:
        fail("the index of the continued history does not list its %d steps" % HISTORY_STEPS)
    worst = 0.0
    for r in rows:
        with h5py.File(os.path.join(out, r["file"]), "r") as a, h5py.File(os.path.join(reference, r["file"]), "r") as b:
            u, v = np.array(a["nodes/displacement"]), np.array(b["nodes/displacement"])
            worst = max(worst, float(np.max(np.abs(u - v)) / max(float(np.max(np.abs(v))), 1e-300)))
    if worst > 1e-12:
        fail("the continued history differs from the uninterrupted one by %.1e" % worst)
    print("ok: %d kills, %d restarts, every state consistent; the history equals the uninterrupted one (%.1e)"
          % (kills, restarts, worst))


def run_on_small_disk(mpi, tribos, np_, out, size_kb):
    """One run with its output on a tmpfs of size_kb; returns (exit, message)."""
    subprocess.run(["umount", out], capture_output=True)
    m = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=%dk" % size_kb, "tmpfs", out], capture_output=True, text=True)
    if m.returncode != 0:
        return None, m.stderr.strip()
    try:
        try:
            p = subprocess.run(command(mpi, tribos, np_, out, "Mesh/Level=8", name="full"),
                               capture_output=True, text=True, timeout=300)
        except subprocess.TimeoutExpired:
            fail("hang with %d kB of disk (%s ranks)" % (size_kb, np_))
        err = p.stderr
        for crash in ("Segmentation", "core dumped", "MPI_ABORT", "HDF5-DIAG", "terminate called"):
            if crash in err:
                fail("crash or raw library error with %d kB of disk:\n%s" % (size_kb, err))
        lines = [l for l in err.splitlines() if l.startswith("tribos:")]
        if p.returncode == 0:
            check_sets(out)
            return 0, "complete"
        if p.returncode not in (1, 3):
            fail("exit %d with %d kB of disk, expected 0, 1 (refused by the output estimate) or 3\n%s"
                 % (p.returncode, size_kb, err))
        if p.returncode == 1 and (len(lines) != 1 or "Load Steps/Times" not in lines[0] or "free" not in lines[0]):
            fail("expected one message naming the steps' output and the free space:\n" + err)
        if p.returncode == 3 and (len(lines) != 1 or "space" not in lines[0].lower()):
            fail("expected one clear message naming the full device:\n" + err)
        left = [n for n in os.listdir(out) if not n.startswith(".tribos.lock")]
        if left:
            fail("a failed write with %d kB of disk left %s" % (size_kb, left))
        return p.returncode, lines[0]
    finally:
        subprocess.run(["umount", out], capture_output=True)


def disk_full(mpi, tribos, work, np_):
    out = os.path.join(work, "small")
    os.makedirs(out, exist_ok=True)
    # Far too small, then sizes around the result's (about 790 kB: the h5
    # fits but the xmf or the summary may not), then enough: every 2 kB on
    # 2 ranks, every 6 kB on the others (the same outcomes, a third of the
    # runs: the suite's time budget).
    around = [764, 768, 770, 772, 774, 776, 780] if np_ == "2" else [768, 774, 780]
    outcomes = {}
    for size_kb in [256] + around + [4096]:
        code, message = run_on_small_disk(mpi, tribos, np_, out, size_kb)
        if code is None:
            print("skipped: cannot mount a small tmpfs here (%s)" % message)
            return
        outcomes[size_kb] = code
        print("%5d kB: exit %d: %s" % (size_kb, code, message))
    if outcomes[256] not in (1, 3) or outcomes[4096] != 0:
        fail("256 kB must fail (refused by the output estimate, or the full disk) and 4 MB succeed: %s" % outcomes)
    print("ok: %s ranks, every size ended cleanly" % np_)


def main():
    # A run stopped from outside (a CI job cancelled, a kill of the process
    # group) sends SIGTERM: leave through the finally blocks, which unmount
    # the small tmpfs, instead of leaving it mounted under the build tree.
    signal.signal(signal.SIGTERM, lambda signum, frame: sys.exit(128 + signum))
    sep = sys.argv.index("--")
    what, opts = sys.argv[1], sys.argv[2:sep]
    work = opts[opts.index("--work") + 1]
    np_ = opts[opts.index("--np") + 1] if "--np" in opts else "1"
    mpi, tribos = sys.argv[sep + 1:-1], sys.argv[-1]
    work = os.path.join(work, what + "_np" + np_)
    if os.path.ismount(os.path.join(work, "small")):
        subprocess.run(["umount", os.path.join(work, "small")])
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    {"concurrent": lambda: concurrent(mpi, tribos, work), "kill": lambda: kill(mpi, tribos, work),
     "disk-full": lambda: disk_full(mpi, tribos, work, np_),
     "history-kill": lambda: history_kill(mpi, tribos, work)}[what]()


if __name__ == "__main__":
    main()
