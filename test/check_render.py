#!/usr/bin/python3
"""scripts/render.py on a real result (skipped, exit 77, without ParaView):

  check_render.py --out DIR -- COMMAND ...   (COMMAND: a tribos run writing to DIR)

The deformed body is rendered coloured by |u| and by the von Mises stress:
both PNGs are written at the requested size, are not blank, and differ
(the colour follows the field).
"""
import argparse
import os
import shutil
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import numpy as np  # noqa: E402

SCRIPT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts", "render.py")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", required=True)
    ap.add_argument("command", nargs=argparse.REMAINDER)
    a = ap.parse_args()
    for tool, package in (("pvbatch", "paraview"), ("xvfb-run", "xvfb")):
        if shutil.which(tool) is None:
            print("skipped: %s is missing (apt-get install %s)" % (tool, package))
            return 77
    command = a.command[1:] if a.command[:1] == ["--"] else a.command
    shutil.rmtree(a.out, ignore_errors=True)
    run = subprocess.run(command, capture_output=True, text=True)
    if run.returncode != 0:
        print("FAILED: the run exited %d\n%s" % (run.returncode, run.stderr))
        return 1
    images, failures = [], 0
    for field in ("displacement", "von_mises"):
        png = os.path.join(a.out, field + ".png")
        r = subprocess.run(["xvfb-run", "-a", "pvbatch", SCRIPT, a.out, "--field", field, "--out", png],
                           capture_output=True, text=True, timeout=240)
        ok = r.returncode == 0 and os.path.exists(png)
        print(("ok: " if ok else "FAILED: ") + "render --field %s" % field)
        if not ok:
            print(r.stdout[-2000:], r.stderr[-2000:])
            failures += 1
            continue
        img = mpimg.imread(png)[..., :3]
        good = img.shape[:2] == (700, 1200) and float(img.std()) > 0.05
        print(("ok: " if good else "FAILED: ") + "%s: %s, pixel std %.3f" % (field, img.shape, img.std()))
        failures += not good
        images.append(img)
    if len(images) == 2:
        diff = float(np.abs(images[0] - images[1]).mean())
        print(("ok: " if diff > 1e-3 else "FAILED: ") + "the colours follow the field (mean pixel change %.4f)" % diff)
        failures += diff <= 1e-3
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
