#!/usr/bin/python3
"""One case of the bad-input suite (cases.txt), run on N ranks as a process:

  run_case.py CASES NAME --np N --work DIR -- MPIEXEC ... TRIBOS
  run_case.py --generate DIR               every gen:NAME input as DIR/NAME.xml
  run_case.py --check-table CASES -- IN_PROCESS
                                           in_process.cpp reads CASES as this does

A case line is  name | exit | stderr regex | input | arguments | check
  exit      the expected exit code (0 converged, 1 bad input, 2 not
            converged, 3 run failure; docs/exit_codes.md), followed by
            "process" when the case runs as its own process, by this
            script (ctest bad_input_NAME_npN): every case with a result set
            (exit 0, 2) and the refusals that need a process. The others
            (exit 1, 3) run in one process per rank count, in_process.cpp
            calling the driver's main as a function, with the same checks.
  regex     must match stderr (exit 1-3) or stdout (exit 0 with --help);
            read by Python here, as an ECMAScript regex in-process
  input     input/NAME.xml, data/NAME.xml (test/data), gen:NAME (a file
            written into the case's directory, see GENERATED) or "-" for
            none
  arguments more command-line arguments, split as a POSIX shell does
            (shlex.split; {work}: the case's directory, {out}: its output
            directory; --output {out} unless given)
  check     optional Python expression over s (the summary), h5 (the
            result file) and a (its root attributes), e.g.
            s['contact']['nodes'] == 0 (process cases only)

Whatever the case, the run must end within the timeout without a crash,
and what it leaves must not lie:
  exit 0    the summary on stdout is valid JSON with converged true; a
            written result is a complete set (h5, xmf, json) marked converged
            whose parameters file, read again, gives the same file (every
            value as it was; checked on one rank)
  exit 2    a complete set whose json and h5 say converged = false
  exit 1, 3 no result file and no temporary in the output directory
"""
import json
import os
import re
import shlex
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(os.path.dirname(HERE))


def base_input(text_changes, base="brick_linear.xml"):
    with open(os.path.join(SOURCE, "input", base)) as f:
        text = f.read()
    for old, new in text_changes:
        assert old in text, old
        text = text.replace(old, new, 1)
    return text


# A Problem Name of 2- and 4-byte UTF-8 sequences: "Młyn ü 𝜇" (the last a mathematical italic mu).
NON_ASCII = "M\u0142yn \u00fc \U0001d707"


def named(problem):
    """The brick with this Problem Name (XML text, as written in the file)."""
    return base_input([('value="brick_linear"', 'value="%s"' % problem)])


# Inputs that cannot be said with --set: they are written into the case's
# directory. A generator returns text (written as UTF-8) or bytes (written as
# they are: other encodings, bytes that are not text).
GENERATED = {
    "value_text": lambda: base_input([('value="0.277"', 'value="abc"')]),
    "value_trailing": lambda: base_input([('value="21.2e10"', 'value="21.2e10abc"')]),
    "array_nan": lambda: base_input([('value="{0.0, 3.0}"', 'value="{0.0, nan}"')]),
    "int_float": lambda: base_input([('name="Level" type="int" value="6"', 'name="Level" type="int" value="2.9"')]),
    "duplicate": lambda: base_input([('<ParameterList name="Material">',
                                      '<ParameterList name="Material">\n    <Parameter name="Poisson\'s Ratio" '
                                      'type="double" value="0.3"/>')]),
    "duplicate_list": lambda: base_input([('<ParameterList name="Material">',
                                           '<ParameterList name="Material"></ParameterList>\n'
                                           '  <ParameterList name="Material">')]),
    "unknown_type": lambda: base_input([('type="double" value="0.277"', 'type="float" value="0.277"')]),
    "no_value": lambda: base_input([('type="double" value="0.277"', 'type="double"')]),
    "malformed": lambda: base_input([("</ParameterList>\n", "")]),
    "empty": lambda: "",
    "root_not_list": lambda: '<Parameter name="a" type="int" value="1"/>\n',
    "tab_name": lambda: base_input([('value="brick_linear"', 'value="tab&#9;quote&quot;backslash\\newline&#10;end"')]),
    "deep": lambda: "<ParameterList>" + "<ParameterList name=\"a\">" * 20000 + "</ParameterList>" * 20001 + "\n",
    "element": lambda: base_input([('<ParameterList name="Mesh">', '<ParameterList name="Mesh">\n    <Foo/>')]),
    "brick": lambda: base_input([]),
    "brick_free": lambda: base_input([('''<ParameterList name="Dirichlet">
      <ParameterList name="clamped end">
        <Parameter name="Face" type="string" value="xmin"/>
        <Parameter name="Components" type="string" value="xyz"/>
      </ParameterList>
      <ParameterList name="support">
        <Parameter name="Face" type="string" value="zmin"/>
        <Parameter name="Components" type="string" value="z"/>
      </ParameterList>
    </ParameterList>''', '<ParameterList name="Dirichlet"></ParameterList>')]),
    "base_name_newline": lambda: base_input([('<ParameterList name="Output">',
                                              '<ParameterList name="Output">\n    <Parameter name="Base Name" '
                                              'type="string" value="two&#10;lines"/>')]),
    "problem_name_long": lambda: base_input([('value="brick_linear"', 'value="%s"' % ("x" * 100000))]),
    # Encodings (bytes, written as they are): what XML 1.0 allows is read, the value comes out as UTF-8.
    "utf8_bom": lambda: b"\xef\xbb\xbf" + named(NON_ASCII).encode("utf-8"),
    "utf16le_bom": lambda: b"\xff\xfe" + named(NON_ASCII).encode("utf-16-le"),
    "utf16be_bom": lambda: b"\xfe\xff" + named(NON_ASCII).encode("utf-16-be"),
    "latin1": lambda: ('<?xml version="1.0" encoding="ISO-8859-1"?>\n' + named("caf\u00e9 \u00fc")).encode("latin-1"),
    "char_references": lambda: named("caf&#233; &#x1D707;"),
    # ... and what it does not is refused with its place.
    "invalid_utf8": lambda: named("caf\u00e9").encode("latin-1"),
    "nul_byte": lambda: named("a\0b").encode("utf-8"),
    "reference_nul": lambda: named("a&#0;b"),
    "shift_jis": lambda: '<?xml version="1.0" encoding="Shift_JIS"?>\n' + named("x"),
    "utf32": lambda: named("x").encode("utf-32"),
    # Every character XML escapes or normalizes, and non-ASCII ones: the parameters file gives them back.
    "name_specials": lambda: named("tab&#9;lf&#10;cr&#13;quote&quot;apos'amp&amp;lt&lt;gt>" + NON_ASCII),
}


def write_generated(name, path):
    content = GENERATED[name]()
    with (open(path, "wb") if isinstance(content, bytes) else open(path, "w", encoding="utf-8")) as f:
        f.write(content)


def parse_cases(path):
    cases = {}
    with open(path) as f:
        for line in f:
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            fields = [x.strip() for x in line.split("|")]
            fields += [""] * (6 - len(fields))
            name, code, regex, inp, args, check = fields[:6]
            code, _, marker = code.partition(" ")
            if marker.strip() not in ("", "process"):
                raise ValueError("case %s: the exit column %r is not CODE or CODE process" % (name, fields[1]))
            cases[name] = dict(exit=int(code), process=marker.strip() == "process", regex=regex, input=inp, args=args,
                               check=check)
    return cases


def check_table(cases_file, command):
    """The table as in_process.cpp reads it (its --list: fields and argument
    words in hex) is the table as read here, every line."""
    p = subprocess.run(command + [cases_file, "--list"], capture_output=True, timeout=120)
    if p.returncode != 0:
        fail("%s --list: exit %d" % (" ".join(command), p.returncode), p.stdout.decode(errors="replace"),
             p.stderr.decode(errors="replace"))
    theirs = {}
    for row in p.stdout.decode().splitlines():
        cols = row.split("\t")
        text = [bytes.fromhex(c).decode() for c in cols[:1] + cols[3:6] + cols[6:]]
        theirs[text[0]] = dict(exit=int(cols[1]), process=cols[2] == "process", regex=text[1], input=text[2],
                               check=text[3], words=text[4:])
    ours = parse_cases(cases_file)
    if list(theirs) != list(ours):
        fail("in_process.cpp and run_case.py read other case names or another order (names in one only: %s)"
             % sorted(set(theirs) ^ set(ours)))
    for name, case in ours.items():
        mine = dict(exit=case["exit"], process=case["process"], regex=case["regex"], input=case["input"],
                    check=case["check"], words=shlex.split(case["args"]))
        if theirs[name] != mine:
            fail("case %s: in_process.cpp reads %r, run_case.py %r" % (name, theirs[name], mine))
    print("ok: in_process.cpp and run_case.py read the %d cases of %s alike" % (len(ours), cases_file))


def fail(msg, out="", err=""):
    print("FAIL: " + msg)
    if out:
        print("--- stdout ---\n" + out[-3000:])
    if err:
        print("--- stderr ---\n" + err[-3000:])
    sys.exit(1)


def result_files(out_dir):
    if not os.path.isdir(out_dir):
        return [], []
    names = os.listdir(out_dir)
    results = [n for n in names if n.endswith((".h5", ".xmf", ".json")) and not n.startswith(".")]
    temporaries = [n for n in names if n.endswith(".tmp")]
    return results, temporaries


def check_set(out_dir, converged, err):
    import h5py
    results, temporaries = result_files(out_dir)
    if temporaries:
        fail("temporaries left: %s" % temporaries, err=err)
    bases = {os.path.splitext(n)[0] for n in results}
    if len(bases) != 1:
        fail("expected one result set in %s, found %s" % (out_dir, results), err=err)
    base = os.path.join(out_dir, bases.pop())
    for ext in (".h5", ".xmf", ".json"):
        if not os.path.exists(base + ext):
            fail("incomplete result set: no " + base + ext, err=err)
    with open(base + ".json") as f:
        s = json.load(f)
    h5 = h5py.File(base + ".h5", "r")
    if s["converged"] != converged or int(h5.attrs["converged"]) != int(converged):
        fail("result set not marked converged = %s (json %s, h5 %s)" % (converged, s["converged"], h5.attrs["converged"]))
    with open(base + ".xmf") as f:
        for ref in re.findall(r">[^<>:]+\.h5:(/[^<]+)<", f.read()):
            if ref not in h5:
                fail("the xmf names %s, which the h5 lacks" % ref)
    return s, h5


def check_parameters_reread(tribos, out_dir, summary, err):
    """BASE.parameters.xml runs again as it is: read back by tribos it gives
    the same file, so every value (strings with any character) is unchanged;
    and any XML parser reads the Problem Name of the summary from it (tab, LF
    and CR written literally would come back as spaces)."""
    import xml.etree.ElementTree as ET
    files = [n for n in os.listdir(out_dir) if n.endswith(".parameters.xml")]
    if len(files) != 1:
        fail("expected one parameters file in %s, found %s" % (out_dir, files), err=err)
    path = os.path.join(out_dir, files[0])
    p = subprocess.run([tribos, path, "--print-parameters"], capture_output=True, timeout=120)
    with open(path, "rb") as f:
        written = f.read()
    if p.returncode != 0 or p.stdout != written:
        fail("%s read again gives exit %d and %s text" % (path, p.returncode, "the same" if p.stdout == written
                                                          else "other"), p.stdout.decode(errors="replace"),
             p.stderr.decode(errors="replace"))
    names = [e.get("value") for e in ET.parse(path).getroot().iter("Parameter") if e.get("name") == "Problem Name"]
    if names != [summary["problem"]]:
        fail("%s holds the Problem Name %r for an XML parser, the summary %r" % (path, names, summary["problem"]))


def main():
    if sys.argv[1] == "--generate":
        os.makedirs(sys.argv[2], exist_ok=True)
        for name in GENERATED:
            write_generated(name, os.path.join(sys.argv[2], name + ".xml"))
        return
    sep = sys.argv.index("--")
    if sys.argv[1] == "--check-table":
        check_table(sys.argv[2], sys.argv[sep + 1:])
        return
    cases_file, name = sys.argv[1], sys.argv[2]
    opts = sys.argv[3:sep]
    np_ = opts[opts.index("--np") + 1]
    work = os.path.join(opts[opts.index("--work") + 1], "%s_np%s" % (name, np_))
    command = sys.argv[sep + 1:]
    case = parse_cases(cases_file)[name]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    out_dir = os.path.join(work, "out")
    inp = case["input"]
    if inp.startswith("gen:"):
        path = os.path.join(work, inp[4:] + ".xml")
        write_generated(inp[4:], path)
        inp_args = [path]
    elif inp.startswith("input/"):
        inp_args = [os.path.join(SOURCE, inp)]
    elif inp.startswith("data/"):
        inp_args = [os.path.join(SOURCE, "test", inp)]
    else:
        inp_args = []
    extra = [a.replace("{work}", work).replace("{out}", out_dir) for a in shlex.split(case["args"])]
    if "--output" not in extra:
        extra += ["--output", out_dir]
    mpi = [np_ if c == "NP" else c for c in command[:-1]]
    full = mpi + [command[-1]] + inp_args + extra
    try:
        p = subprocess.run(full, capture_output=True, text=True, timeout=300, cwd=work)
    except subprocess.TimeoutExpired:
        fail("no exit within 300 s (hang): " + " ".join(full))
    out, err = p.stdout, p.stderr
    if p.returncode != case["exit"]:
        fail("exit %d, expected %d: %s" % (p.returncode, case["exit"], " ".join(full)), out, err)
    for crash in ("Segmentation fault", "core dumped", "Aborted", "MPI_ABORT", "HDF5-DIAG", "terminate called"):
        if crash in err or crash in out:
            fail("the run crashed or printed a raw library error (%s)" % crash, out, err)
    text = out if case["exit"] == 0 else err
    if case["regex"] and not re.search(case["regex"], text):
        fail("output does not match /%s/" % case["regex"], out, err)
    s, h5 = None, None
    if case["exit"] in (1, 3):
        results, temporaries = result_files(out_dir)
        if results or temporaries:
            fail("a failed run left files: %s" % (results + temporaries), out, err)
    elif case["exit"] == 2:
        s, h5 = check_set(out_dir, False, err)
    elif "--help" not in extra:
        try:
            s = json.loads(out)
        except ValueError as e:
            fail("the summary on stdout is not valid JSON: %s" % e, out, err)
        if not s["converged"]:
            fail("exit 0 without converged = true", out, err)
        if os.path.isdir(out_dir) and result_files(out_dir)[0]:
            s, h5 = check_set(out_dir, True, err)
            if np_ == "1":
                check_parameters_reread(command[-1], out_dir, s, err)
    # The HDF5 root attributes, strings decoded.
    a = {k: (v.decode() if isinstance(v, bytes) else v) for k, v in h5.attrs.items()} if h5 is not None else {}
    if case["check"] and not eval(case["check"], {"s": s, "h5": h5, "a": a}):
        fail("check failed: " + case["check"], out, err)
    print("ok: %s (np %s): exit %d" % (name, np_, p.returncode))
    print(err.strip()[-600:])


if __name__ == "__main__":
    main()
