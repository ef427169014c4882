"""Reads the summary of a Tribos run with its load steps.

A run that writes its results (Output/Write Results, the default) keeps the
row of each load step in the steps table BASE.steps.jsonl beside its summary
BASE.json: one JSON object per line, appended as each step is written, so
that writing a step costs the same at step 10 and at step 10^5. The summary
says how many rows are complete (`steps_completed`; a run killed while it
wrote a step may have left one more row, or part of one, which is not yet
part of the result) and names the table (`steps_file`). A run that writes no
results has the rows in its summary (`steps`).

    import tribos_summary
    s = tribos_summary.load("output/run/solution.json")
    for row in s["steps"]: ...

load() returns the summary as a dict with `steps` the list of the complete
rows in step order, whichever way the run kept them; find() names the
summary of a run's output directory.
"""
import glob
import json
import os


def find(directory, base=None):
    """DIR/BASE.json: given by `base`, else the only summary of `directory`
    with an index (BASE.xmf) beside it. Raises ValueError saying why not."""
    if not os.path.isdir(directory):
        raise ValueError("%s is not a directory" % directory)
    if base is not None:
        path = os.path.join(directory, base + ".json")
        if not os.path.exists(path):
            raise ValueError("%s holds no summary %s.json (files there: %s)"
                             % (directory, base, ", ".join(sorted(os.listdir(directory))) or "none"))
        return path
    found = [f for f in sorted(glob.glob(os.path.join(directory, "*.json")))
             if os.path.exists(f[:-len(".json")] + ".xmf")]
    if not found:
        raise ValueError("%s holds no result (a BASE.json beside a BASE.xmf): not the output directory of a tribos "
                         "run" % directory)
    if len(found) > 1:
        raise ValueError("%s holds %d results (%s); name one with --base"
                         % (directory, len(found), ", ".join(os.path.basename(f) for f in found)))
    return found[0]


def steps_of(summary, directory):
    """The complete step rows of a summary read from `directory`."""
    if "steps" in summary:
        return summary["steps"]
    name, count = summary.get("steps_file"), summary.get("steps_completed")
    if not isinstance(name, str) or not isinstance(count, int):
        raise ValueError("the summary has neither steps nor steps_file with steps_completed")
    # Beside the summary, or (a copy written by --summary elsewhere) in the
    # output directory, where the index the summary names (`output`) is.
    path = os.path.join(directory, name)
    if not os.path.exists(path) and isinstance(summary.get("output"), str):
        path = os.path.join(os.path.dirname(summary["output"]), name)
    rows = []
    with open(path) as f:
        for line in f:
            if len(rows) == count:
                break
            if not line.endswith("\n"):
                break  # a row a killed run left half written
            rows.append(json.loads(line))
    if len(rows) != count:
        raise ValueError("%s has %d complete rows, the summary says %d" % (name, len(rows), count))
    return rows


def load(path):
    """The summary at `path`, its `steps` the complete step rows."""
    with open(path) as f:
        summary = json.load(f)
    if not isinstance(summary, dict):
        raise ValueError("%s is not a JSON object" % path)
    summary["steps"] = steps_of(summary, os.path.dirname(os.path.abspath(path)))
    return summary
