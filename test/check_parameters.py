#!/usr/bin/python3
"""The effective parameters of a run, printed and written, read back.

usage: check_parameters.py --work DIR --input FILE.xml [--set "Sublist/Key=value" ...]
                           --np N -- MPIEXEC... TRIBOS
MPIEXEC may contain the token NP, replaced by the rank count.

1. `tribos --print-parameters` (no input): exit 0, XML, documented defaults;
   --set applies; a bad --set exits 1. No file or directory is created.
2. `tribos --print-parameters FILE --set ...` prints the effective list; the
   printed file printed again is the same text (a fixed point), and
   printing creates nothing (no output directory, no work).
3. The same run twice, from FILE with the --set options and from the printed
   file: both converge with the same counts and the same displacement.
4. The run's result set holds BASE.parameters.xml: it parses as XML (the
   Python parser), has the values of the printed list, and its
   Output/Directory is the directory the run wrote to.
"""
import json
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET


def fail(msg, p=None):
    print("FAIL: " + msg)
    if p is not None:
        print("--- stdout ---\n" + p.stdout[-3000:] + "\n--- stderr ---\n" + p.stderr[-3000:])
    sys.exit(1)


def values(xml_text):
    """{path: (type, value)} of every Parameter, and the paths that have a docString."""
    root = ET.fromstring(xml_text)
    if root.tag != "ParameterList":
        fail("the root element is <%s>, not <ParameterList>" % root.tag)
    out, documented = {}, set()

    def walk(elem, path):
        for child in elem:
            name = child.get("name")
            full = path + "/" + name if path else name
            if child.tag == "ParameterList":
                walk(child, full)
            elif child.tag == "Parameter":
                out[full] = (child.get("type"), child.get("value"))
                if child.get("docString"):
                    documented.add(full)
            else:
                fail("unexpected element <%s> at %s" % (child.tag, path))
    walk(root, "")
    return out, documented


def main():
    sep = sys.argv.index("--")
    opts, cmd = sys.argv[1:sep], sys.argv[sep + 1:]
    work = opts[opts.index("--work") + 1]
    input_file = os.path.abspath(opts[opts.index("--input") + 1])
    np_ = opts[opts.index("--np") + 1]
    sets = [opts[i + 1] for i, o in enumerate(opts) if o == "--set"]
    mpi, tribos = cmd[:-1], cmd[-1]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)

    def tribos_run(np, *args):
        full = [np if c == "NP" else c for c in mpi] + [tribos] + list(args)
        return subprocess.run(full, cwd=work, capture_output=True, text=True)

    set_args = [a for s in sets for a in ("--set", s)]

    # 1. the documented defaults
    p = tribos_run("1", "--print-parameters")
    if p.returncode != 0:
        fail("--print-parameters exited %d" % p.returncode, p)
    defaults, documented = values(p.stdout)
    if defaults.get("Mesh/Element") != ("string", "Tet4"):
        fail("default Mesh/Element is %s, expected Tet4" % (defaults.get("Mesh/Element"),))
    for key in ("Mesh/Element", "Material/Young's Modulus", "Solver/Outer Algorithm"):
        if key not in documented:
            fail("%s has no docString" % key)
    p = tribos_run("1", "--print-parameters", "--set", "Mesh/Element=Hex8")
    if p.returncode != 0 or values(p.stdout)[0].get("Mesh/Element") != ("string", "Hex8"):
        fail("--print-parameters --set Mesh/Element=Hex8 did not print Hex8", p)
    p = tribos_run("1", "--print-parameters", "--set", "Mesh/Element=Tet20")
    if p.returncode != 1 or "Tet20" not in p.stderr:
        fail("--print-parameters with a bad --set must exit 1 naming the value", p)
    print("ok: documented defaults (%d parameters), --set applied, bad --set refused" % len(defaults))

    # 2. the effective list of the input, a fixed point of printing
    p = tribos_run(np_, "--print-parameters", input_file, *set_args)
    if p.returncode != 0:
        fail("--print-parameters %s exited %d" % (input_file, p.returncode), p)
    printed_text = p.stdout
    printed_file = os.path.join(work, "printed.xml")
    with open(printed_file, "w") as f:
        f.write(printed_text)
    printed, _ = values(printed_text)
    for s in sets:
        key, value = s.split("=", 1)
        if key not in printed:
            fail("--set %s is not in the printed list" % s)
    p = tribos_run("1", "--print-parameters", printed_file)
    if p.returncode != 0 or p.stdout != printed_text:
        fail("the printed list printed again differs", p)
    leftovers = sorted(set(os.listdir(work)) - {"printed.xml"})
    if leftovers:
        fail("--print-parameters created %s" % leftovers)
    print("ok: %d effective parameters; printing the printed file gives the same text; nothing created"
          % len(printed))

    # 3. the same run from the input and from the printed file
    summaries = []
    for name, args in (("from_input", [input_file] + set_args), ("from_printed", [printed_file])):
        out = os.path.join(work, name)
        p = tribos_run(np_, *args, "--output", out, "--quiet")
        if p.returncode != 0:
            fail("the run %s exited %d" % (name, p.returncode), p)
        summary = os.path.join(out, printed["Output/Base Name"][1] + ".json")
        with open(summary) as f:
            summaries.append(json.load(f))
    a, b = summaries
    if not (a["converged"] and b["converged"]):
        fail("a run did not converge: %s, %s" % (a["converged"], b["converged"]))
    for key in ("primal_dofs", "dual_dofs", "subdomains", "outer_iterations", "n_A"):
        if a[key] != b[key]:
            fail("%s differs: %s from the input, %s from the printed file" % (key, a[key], b[key]))
    du = abs(a["max_abs_displacement"] - b["max_abs_displacement"])
    if du > 1e-12 * abs(a["max_abs_displacement"]):
        fail("max_abs_displacement differs by %g" % du)
    print("ok: the printed file runs as the input does (n_A %d, max |u| %.6e)" % (a["n_A"], a["max_abs_displacement"]))

    # 4. the parameter file of the result set
    out = os.path.join(work, "from_input")
    written_file = os.path.join(out, printed["Output/Base Name"][1] + ".parameters.xml")
    if not os.path.exists(written_file):
        fail("no %s in the result set" % written_file)
    if a.get("parameters") != written_file:
        fail("the summary names %s as the parameter file" % a.get("parameters"))
    with open(written_file) as f:
        written, _ = values(f.read())
    if written.get("Output/Directory") != ("string", out):
        fail("Output/Directory of the written list is %s, expected %s" % (written.get("Output/Directory"), out))
    differ = [k for k in set(printed) | set(written) if k != "Output/Directory" and printed.get(k) != written.get(k)]
    if differ:
        fail("the written parameters differ from the printed ones at %s" % sorted(differ))
    print("ok: %s parses as XML and holds the effective parameters" % os.path.basename(written_file))


if __name__ == "__main__":
    main()
