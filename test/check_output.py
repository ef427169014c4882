#!/usr/bin/python3
"""Checks a result file written by several ranks: the XDMF index names
datasets that exist with the stated shapes, the cells tile the box (positive
volumes summing to its volume), the clamped face does not move, and the
contact point set has the documented fields.

usage: check_output.py DIR/BASE.xmf BOX_VOLUME
"""
import os
import re
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np

xmf, volume = sys.argv[1], float(sys.argv[2])
root = ET.parse(xmf).getroot()
h5dir = os.path.dirname(xmf)
ok = True
for item in root.iter("DataItem"):
    dims = tuple(int(d) for d in item.attrib["Dimensions"].split())
    fname, path = item.text.strip().split(":")
    with h5py.File(os.path.join(h5dir, fname), "r") as f:
        if f[path].shape != dims:
            print("FAILED: %s has shape %s, index says %s" % (path, f[path].shape, dims))
            ok = False
with h5py.File(xmf.replace(".xmf", ".h5"), "r") as f:
    X = f["mesh/geometry"][:]
    T = f["mesh/topology"][:]
    u = f["nodes/displacement"][:]
    if T.shape[1] == 4:
        a, b, c, d = (X[T[:, k]] for k in range(4))
        vols = np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a)) / 6
        if vols.min() <= 0 or abs(vols.sum() - volume) > 1e-10 * volume:
            print("FAILED: cell volumes min %g sum %g (box %g)" % (vols.min(), vols.sum(), volume))
            ok = False
    clamped = np.abs(X[:, 0]) < 1e-12
    # TFETI imposes Dirichlet rows through multipliers: to the solver tolerance.
    if np.abs(u[clamped]).max() > 1e-5 * np.abs(u).max():
        print("FAILED: clamped nodes move")
        ok = False
    if "points/contact" in f:
        for name in ["normal_force", "tangential_force", "slip", "status", "gap"]:
            if name not in f["points/contact"]:
                print("FAILED: contact field %s missing" % name)
                ok = False
print("output checks", "passed" if ok else "FAILED")
sys.exit(0 if ok else 1)
