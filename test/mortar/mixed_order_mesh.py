#!/usr/bin/python3
"""A mesh whose bodies differ in order: a .geo meshed by Gmsh in second-order
cells, then the named physical volumes (and the surfaces that bound them)
taken back to their first-order cells, with the nodes no cell uses any more
dropped. Gmsh's .geo meshes every volume with one order; this makes the
mixed meshes of the contact tests (a Tet4 body against a Tet10 one).

    mixed_order_mesh.py GEO OUT.msh --first-order upper [--first-order ...]
"""
import argparse
import subprocess
import sys
import tempfile

# Second-order Gmsh element type -> (first-order type, its corner count).
FIRST_ORDER = {11: (4, 4), 17: (5, 8), 9: (2, 3), 16: (3, 4), 8: (1, 2)}


def sections(lines):
    """Section name -> (first, last) line index of its body."""
    out, name = {}, None
    for i, line in enumerate(lines):
        if line.startswith("$End"):
            out[name] = (start, i)
            name = None
        elif line.startswith("$"):
            name, start = line[1:].strip(), i + 1
    return out


def demoted_entities(lines, sec, names):
    """The (dim, tag) of the volumes of the physical volumes `names` and of
    the surfaces bounding them."""
    first, _ = sec["PhysicalNames"]
    groups = {}
    for line in lines[first + 1:sec["PhysicalNames"][1]]:
        dim, tag, name = line.split(maxsplit=2)
        if int(dim) == 3:
            groups[name.strip().strip('"')] = int(tag)
    missing = [n for n in names if n not in groups]
    if missing:
        sys.exit(f"no physical volume {missing}; the file has {sorted(groups)}")
    wanted = {groups[n] for n in names}
    first, last = sec["Entities"]
    counts = [int(v) for v in lines[first].split()]
    at = first + 1 + counts[0] + counts[1] + counts[2]  # past points, curves, surfaces
    entities = set()
    for line in lines[at:at + counts[3]]:
        v = line.split()
        tag, nphys = int(v[0]), int(v[7])
        phys = {int(p) for p in v[8:8 + nphys]}
        if phys & wanted:
            entities.add((3, tag))
            nb = int(v[8 + nphys])
            entities.update((2, abs(int(s))) for s in v[9 + nphys:9 + nphys + nb])
    return entities


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("geo")
    p.add_argument("out")
    p.add_argument("--first-order", action="append", required=True, help="a physical volume to mesh in first order")
    a = p.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        msh = f"{tmp}/second_order.msh"
        subprocess.run(["gmsh", "-3", "-order", "2", "-format", "msh41", a.geo, "-o", msh], check=True,
                       stdout=subprocess.DEVNULL)
        lines = open(msh).read().splitlines()
    sec = sections(lines)
    demote = demoted_entities(lines, sec, a.first_order)

    # Elements: the demoted entities' blocks in first order.
    first, last = sec["Elements"]
    out_elements, used, i = [], set(), first + 1
    while i < last:
        dim, tag, etype, n = (int(v) for v in lines[i].split())
        rows = [[int(v) for v in l.split()] for l in lines[i + 1:i + 1 + n]]
        if (dim, tag) in demote and etype in FIRST_ORDER:
            etype, corners = FIRST_ORDER[etype]
            rows = [r[:1 + corners] for r in rows]
        out_elements.append(f"{dim} {tag} {etype} {n}")
        out_elements += [" ".join(map(str, r)) for r in rows]
        for r in rows:
            used.update(r[1:])
        i += 1 + n
    header = lines[first].split()
    out_elements.insert(0, " ".join(header))

    # Nodes: those of some element only.
    first, last = sec["Nodes"]
    out_nodes, kept, i = [], 0, first + 1
    blocks = []
    while i < last:
        dim, tag, parametric, n = (int(v) for v in lines[i].split())
        tags = [int(l) for l in lines[i + 1:i + 1 + n]]
        xyz = lines[i + 1 + n:i + 1 + 2 * n]
        keep = [k for k, t in enumerate(tags) if t in used]
        blocks.append([f"{dim} {tag} {parametric} {len(keep)}"] + [str(tags[k]) for k in keep] + [xyz[k] for k in keep])
        kept += len(keep)
        i += 1 + 2 * n
    all_tags = sorted(used)
    out_nodes = [f"{len(blocks)} {kept} {all_tags[0]} {all_tags[-1]}"] + [l for b in blocks for l in b]

    new = lines[:sec["Nodes"][0]] + out_nodes + lines[sec["Nodes"][1]:sec["Elements"][0]] + out_elements + \
        lines[sec["Elements"][1]:]
    with open(a.out, "w") as f:
        f.write("\n".join(new) + "\n")


if __name__ == "__main__":
    main()
