#!/usr/bin/env python3
"""The fuzz target `python` of tests/fuzz/fuzz.py: Python containers given to the module.

A mutant is a JSON description: a call of the module (`study` of a dict through
`pcrf._pcrf.study_text`, `run` and `Frame` with keywords, `record_measures`, a cube report's
`where=`/`by=`), its seed value, and edits that a JSON file cannot hold but a Python caller
can: a list or dict that holds itself, values nested 30 to 200 000 deep, ints beyond 64 bits,
tuples, numpy object arrays that hold themselves, non-string keys, objects of no known type.
Each mutant runs in a child Python (this file with --run), so a crash is a signal the judge
sees; the child exits 0 when the call returned, 2 after one `pcrf: error:` line when it raised
`pcrf.InputError` (which must name a key when the edits were nesting or integers: issue 41,
items 2 and 4), and 1 with the traceback for any other exception (pybind11's "Unable to cast",
RecursionError, TypeError, ...): the judge counts that as a finding.
"""

import copy
import json
import os
import subprocess
import sys
from pathlib import Path

DEEP = [31, 32, 33, 100, 5000, 200_000]
INTS = [2**63 - 1, 2**63, -(2**63) - 1, 2**70, -(2**70), 10**400]
FLOATS = ["nan", "inf", "-inf", 1e308, -0.0]
SEEDS = {
    "study": {"study": {"name": "fuzz"}, "plan": {"kind": "grid"},
              "records": [{"synthetic": ["sine:amplitude_g=1.5,period_s=0.5,cycles=2,duration_s=2"]}],
              "axes": {"scale": [1.0, 4.0], "kappa": {"from": 1.2, "to": 2.4, "count": 3}},
              "physics": {"tail_s": 0.5, "max_steps": 100000}, "solver": {"preset": "fast"},
              "outputs": {"histories": [{"label": "one", "scale": 1.0, "kappa": 1.2,
                                         "record": "sine:amplitude_g=1.5,period_s=0.5,cycles=2,duration_s=2"}]}},
    "run": {"synthetic": "sine:amplitude_g=1.5,period_s=0.5,cycles=1,duration_s=1", "tail_s": 0.0,
            "frame": {"kappa": 2.0, "lambda": 0.5}, "max_steps": 10000, "preset": "fast"},
    "frame": {"kappa": 2.5, "points": 11, "fracture_strain": 0.01},
    "record_measures": {"synthetic": "sine:amplitude_g=0.5,period_s=0.5,cycles=1,duration_s=1",
                        "periods_s": [0.2, 0.5, 1.0], "damping": 0.05},
    "report": {"by": ["kappa", "scale"], "where": {"kappa": 1.2, "scale": [1.0]}, "metric": "theta_max_rad"},
}
NAMED_EDITS = {"self", "deep", "int"}  # an InputError for these must name its key


# ---- the parent's side: seeds and mutants ------------------------------------------------------

def paths(value, prefix=()):
    """Every path (keys and indices) into the JSON value, itself first."""
    yield list(prefix)
    if isinstance(value, dict):
        for key, item in value.items():
            yield from paths(item, prefix + (key,))
    elif isinstance(value, list):
        for i, item in enumerate(value):
            yield from paths(item, prefix + (i,))


def mutate(rng, data):
    """Up to three edits at random places of the seed (JSON bytes in, JSON bytes out)."""
    mutant = json.loads(data)
    places = list(paths(mutant["value"]))
    edits = []
    for _ in range(rng.randint(1, 3)):
        op = rng.choice(["self", "self", "deep", "deep", "int", "int", "float", "tuple", "numpy", "key", "object",
                         "none"])
        edit = {"op": op, "path": rng.choice(places)}
        if op == "deep":
            edit["n"] = rng.choice(DEEP)
        elif op == "int":
            edit["n"] = str(rng.choice(INTS))
        elif op == "float":
            edit["x"] = rng.choice(FLOATS)
        edits.append(edit)
    mutant["edits"] = edits
    return json.dumps(mutant).encode()


class PythonContainers:
    """The target: seeds per call, mutated by `mutate`, each run by a child Python."""
    name = "python"
    suffix = ".json"

    def __init__(self, module_dir):
        self.module_dir = str(module_dir)

    def seeds(self, work):
        return [(call, json.dumps({"call": call, "value": value, "edits": []}).encode(), [])
                for call, value in SEEDS.items()]

    def mutate(self, rng, data):
        return mutate(rng, data)

    def command(self, pcrf, file, extra):
        return ["env", f"PYTHONPATH={self.module_dir}", f"PCRF_EXECUTABLE={pcrf}", sys.executable,
                os.path.abspath(__file__), "--run", str(file)]


def module_available(module_dir):
    """Whether `import pcrf` works from `module_dir` (a build without the module has none)."""
    done = subprocess.run([sys.executable, "-c", "import pcrf"], env=dict(os.environ, PYTHONPATH=str(module_dir)),
                          capture_output=True)
    return done.returncode == 0


# ---- the child's side: build the value, call, say how it ended -----------------------------

def nested(value, depth):
    for _ in range(depth):
        value = [value]
    return value


def at(root, path):
    """(the container holding path's end, its key), or (None, None) for the root or a path the
    edits before changed."""
    if not path:
        return None, None
    node = root
    for key in path[:-1]:
        node = node[key]
    return node, path[-1]


def apply(root, edit):
    """root with the edit made (the root itself may be replaced)."""
    import numpy as np

    def change(old):
        op = edit["op"]
        if op == "self":
            if isinstance(old, dict):
                old["again"] = old
                return old
            if isinstance(old, list):
                old.append(old)
                return old
            box = [old]
            box.append(box)
            return box
        if op == "deep":
            return nested(old, edit["n"])
        if op == "int":
            return int(edit["n"])
        if op == "float":
            return float(edit["x"])
        if op == "tuple":
            return tuple(old) if isinstance(old, list) else (old,)
        if op == "numpy":
            array = np.empty(2, dtype=object)
            array[0], array[1] = old, array
            return array
        if op == "key":
            if isinstance(old, dict):
                old[(1, (2, (3,)))] = 1.0
                old[7] = "seven"
            return old
        if op == "object":
            return object()
        return None  # "none"

    try:
        holder, key = at(root, edit["path"])
    except (KeyError, IndexError, TypeError):
        return root, False
    if holder is None:
        return change(root), True
    try:
        holder[key] = change(holder[key])
    except (KeyError, IndexError, TypeError):
        return root, False
    return root, True


def call(pcrf, name, value, work):
    keywords = value if isinstance(value, dict) else {"value": value}
    keywords = {str(k): v for k, v in keywords.items()}
    if name == "study":  # a dict is checked as pcrf.study checks it, without running; anything else by pcrf.study
        if isinstance(value, dict):
            return pcrf._pcrf.study_text(value)
        return pcrf.study(value, output=os.path.join(work, "never.h5"), check=True)
    if name == "run":
        return pcrf.run(**keywords)
    if name == "frame":
        return pcrf.Frame(**keywords)
    if name == "record_measures":
        return pcrf.record_measures(**keywords)
    return pcrf._pcrf.cube_report("stats", os.path.join(work, "no_such_cube.h5"), **keywords)


def run_child(mutant_file):
    import warnings

    warnings.simplefilter("ignore")
    import pcrf

    mutant = json.loads(Path(mutant_file).read_text())
    value = copy.deepcopy(mutant["value"])
    applied = []
    for edit in mutant["edits"]:
        value, done = apply(value, edit)
        if done:  # an edit of the whole value (the root) leaves no keyword to name
            applied.append(edit["op"] if edit["path"] else "root")
    try:
        call(pcrf, mutant["call"], value, os.path.dirname(os.path.abspath(mutant_file)))
    except pcrf.InputError as e:
        message = " ".join(str(e).split())
        if applied and set(applied) <= NAMED_EDITS and e.key is None and e.file is None:
            print(f"an InputError that names no key after {applied}: {message}", file=sys.stderr)
            return 1
        print(f"pcrf: error: {message}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--run":
        sys.exit(run_child(sys.argv[2]))
    sys.exit(__doc__)
