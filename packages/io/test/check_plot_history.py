#!/usr/bin/python3
"""scripts/plot_history.py on a load history that the library writes:

  check_plot_history.py --work DIR -- COMMAND ...
  (COMMAND: write_series_fixture under mpiexec; it gets DIR/run and the steps)

The fixture writes a load cycle through IO::StepSeries with the values
chosen here (an elastic-perfectly-plastic tangential spring: the force
follows the displacement, capped at the friction limit, so that going back
leaves a loop). Checks that
  - the script finds the result, reads every step's data file through the
    index and recovers, per pair, the chosen force and the mean tangential
    displacement of its slave nodes (the displacement less its normal part)
    along the pair's direction, and the stick/slip counts over the times;
  - it draws two non-blank PNGs next to the data or into --output, and the
    pictures follow the data (other forces, other pixels);
  - only the steps the summary lists are drawn (a step being committed is
    in the index first);
  - a directory without a result, a summary without steps and an index with
    fewer steps than the summary are refused with one line naming the file;
  - where pvpython is installed, ParaView's reader finds the steps' times.
Exits 77 (skipped) when matplotlib or h5py is not installed.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys

try:
    import h5py  # noqa: F401
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.image as mpimg
    import numpy as np
except ImportError as e:
    print("skipped: %s (install python3-matplotlib and python3-h5py)" % e)
    sys.exit(77)

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPTS = os.path.join(HERE, "..", "..", "..", "scripts")
SCRIPT = os.path.join(SCRIPTS, "plot_history.py")
sys.path.insert(0, SCRIPTS)
import plot_history  # noqa: E402

failures = []


def check(ok, what):
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        failures.append(what)


def cycle():
    """Times, tangential displacement, force and stick/slip counts of a load
    cycle: up past the limit, back past the opposite limit, up again."""
    stiffness, limit, nodes = 1000.0, 1.5, 7
    deltas = [x * 1e-3 for x in (0, 1, 2, 3, 2, 1, 0, -1, -2, -3, -2, -1, 0, 1)]
    steps, slipped = [], 0.0
    for k, d in enumerate(deltas, 1):
        trial = stiffness * (d - slipped)
        force = max(-limit, min(limit, trial))
        slipped = d - force / stiffness
        slip = nodes if abs(trial) > limit else 0
        steps.append((0.5 * k, d, force, nodes - slip, slip))
    return steps


def run(args, **kw):
    return subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True, **kw)


def write_fixture(command, directory, steps):
    shutil.rmtree(directory, ignore_errors=True)
    p = run(command + [directory] + ["%r,%r,%r,%d,%d" % s for s in steps])
    if p.returncode != 0:
        sys.exit("the fixture failed (%d): %s%s" % (p.returncode, p.stdout, p.stderr))


def plot(directory, *extra):
    return run([sys.executable, SCRIPT, directory] + list(extra))


def pixels(path):
    try:
        return mpimg.imread(path)
    except (OSError, ValueError, SyntaxError):
        return None


def check_pictures(out, what):
    images = {}
    for name in ("cycle_load_displacement.png", "cycle_stick_slip.png"):
        image = pixels(os.path.join(out, name))
        check(image is not None and image.shape[:2] == (480, 640), "%s: %s is a 640 x 480 image" % (what, name))
        check(image is not None and float(np.std(image)) > 0.01, "%s: %s is not blank" % (what, name))
        images[name] = image
    return images


def check_values(directory, steps):
    h = plot_history.load_history(directory)
    times, deltas, forces, stick, slip = (np.array([s[i] for s in steps], dtype=float) for i in range(5))
    check(h["base"] == "cycle", "the result found is cycle")
    check(np.array_equal(h["time"], times), "the times of every step, in order")
    check([p["name"] for p in h["pairs"]] == ["top", "side"], "the pairs top and side, in the solver's order")
    # The force a pair transmits is minus the friction force on its slave side.
    expected = {"top": ([1, 0, 0], deltas, -forces),  # normal +z: u = (delta, 0, delta/4) less its z part
                "side": ([0, 0, 1], deltas / 4, -forces / 2)}  # normal +x: its z part
    for pair in h["pairs"]:
        direction, x, y = plot_history.curve(pair)
        d, ex, ey = expected[pair["name"]]
        check(np.allclose(direction, d, rtol=0, atol=1e-15), "%s: the direction %s" % (pair["name"], direction))
        check(np.allclose(x, ex, rtol=1e-12, atol=1e-18),
              "%s: the mean tangential displacement of the slave nodes per step" % pair["name"])
        check(np.array_equal(y, ey), "%s: the force the pair transmits per step" % pair["name"])
    check(np.array_equal(h["counts"]["stick"], stick) and np.array_equal(h["counts"]["slip"], slip),
          "the stick and slip counts per step")
    return h


def check_paraview(directory, times):
    """Where ParaView is installed: its reader finds every step's time in the index."""
    pvpython = shutil.which("pvpython")
    if pvpython is None:
        print("skipped: the index in ParaView (pvpython is not installed)")
        return
    code = ("from paraview.simple import OpenDataFile\n"
            "r = OpenDataFile(%r)\nprint(repr(list(r.TimestepValues)))" % os.path.join(directory, "cycle.xmf"))
    p = run([pvpython, "--force-offscreen-rendering", "-c", code])
    found = p.stdout.strip().splitlines()[-1] if p.returncode == 0 and p.stdout.strip() else p.stderr.strip()
    check(found == repr([float(t) for t in times]), "ParaView plays the %d steps at their times (%s)" % (len(times), found))


def expect_refusal(directory, says, what):
    p = plot(directory)
    message = p.stderr.strip()
    check(p.returncode != 0 and says in message and "Traceback" not in message and "\n" not in message,
          "%s refused in one line (%s)" % (what, message))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--work", required=True)
    parser.add_argument("command", nargs=argparse.REMAINDER)
    args = parser.parse_args()
    command = args.command[1:] if args.command[:1] == ["--"] else args.command
    os.makedirs(args.work, exist_ok=True)
    directory, out = os.path.join(args.work, "run"), os.path.join(args.work, "pictures")
    steps = cycle()
    check(any(s[4] for s in steps) and any(s[2] < 0 for s in steps), "the cycle slips both ways")

    write_fixture(command, directory, steps)
    check(os.path.exists(os.path.join(directory, "cycle.step0014.h5")), "the fixture wrote 14 step files")
    check_values(directory, steps)
    p = plot(directory)
    check(p.returncode == 0, "plot_history.py DIR succeeds (%s)" % p.stderr.strip())
    first = check_pictures(directory, "next to the data")
    os.makedirs(out, exist_ok=True)
    p = plot(directory, "--output", out)
    check(p.returncode == 0, "plot_history.py DIR --output OUT succeeds (%s)" % p.stderr.strip())
    check_pictures(out, "in --output")

    check_paraview(directory, [s[0] for s in steps])

    # Other forces: another loop picture, the same stick/slip picture.
    other = os.path.join(args.work, "other")
    write_fixture(command, other, [(t, d, -0.5 * f, st, sl) for t, d, f, st, sl in steps])
    plot(other)
    second = check_pictures(other, "other forces")
    name = "cycle_load_displacement.png"
    check(first[name] is not None and second[name] is not None and first[name].shape == second[name].shape
          and not np.array_equal(first[name], second[name]), "the loop picture follows the forces")

    # A step being committed: in the index, not yet in the summary.
    summary = os.path.join(other, "cycle.json")
    with open(summary) as f:
        data = json.load(f)
    data["steps"] = data["steps"][:-1]
    with open(summary, "w") as f:
        json.dump(data, f)
    h = plot_history.load_history(other)
    check(len(h["time"]) == len(steps) - 1, "only the steps of the summary are drawn")

    # Refusals.
    empty = os.path.join(args.work, "empty")
    os.makedirs(empty, exist_ok=True)
    expect_refusal(empty, "holds no result", "a directory without a result")
    data["steps"] = []
    with open(summary, "w") as f:
        json.dump(data, f)
    expect_refusal(other, "has no list \"steps\"", "a summary without steps")
    write_fixture(command, other, steps[:3])
    with open(os.path.join(directory, "cycle.json")) as f:
        data = json.load(f)
    with open(summary, "w") as f:
        json.dump(data, f)  # 14 steps against an index of 3
    expect_refusal(other, "only 3", "a summary of more steps than the index")

    if failures:
        sys.exit("%d check(s) failed:\n  %s" % (len(failures), "\n  ".join(failures)))
    print("all checks passed")


if __name__ == "__main__":
    main()
