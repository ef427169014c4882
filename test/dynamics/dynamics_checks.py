"""What the checks of test/dynamics share: one line per check, and the
run's parameters read back from its BASE.parameters.xml.

  from dynamics_checks import check, failed, parameter, numbers
"""

_failed = False


def check(ok, what):
    """Prints "ok: what" or "FAILED: what"; a failure is remembered."""
    global _failed
    print(("ok: " if ok else "FAILED: ") + what)
    _failed = _failed or not ok


def failed():
    """Whether some check failed."""
    return _failed


def parameter(root, path, default=None):
    """The value (text) of the parameter at path ("List/List/Name") of a
    parameters file's root, or default when it is not there."""
    node = root
    for name in path.split("/")[:-1]:
        node = next((c for c in node if c.tag == "ParameterList" and c.get("name") == name), None)
        if node is None:
            return default
    leaf = next((c for c in node if c.tag == "Parameter" and c.get("name") == path.split("/")[-1]), None)
    return default if leaf is None else leaf.get("value")


def numbers(text):
    """The numbers of an Array(double) value, "{a, b, c}"."""
    return [float(v) for v in text.strip("{} ").split(",")]
