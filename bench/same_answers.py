#!/usr/bin/env python3
"""Same-answers check (not a test): two builds of pcrf give the same results, bit for bit, for
a move or a refactoring that must change nothing a user sees.

    python3 bench/same_answers.py --old OLD/pcrf --new build/pcrf [--records DIR] [--study FILE]

Compares:
- `pcrf run` JSON of every scene of the scene-cost bench (the prestressed frame, the block,
  the rocking frame) under every preset (fast, balanced, reference) and every record of
  DIR/paper (the paper's 11 far-field records; PCRF_RECORDS_DIR overrides DIR) at 1.2x and
  3x the scene's uplift threshold: every key but the case's time (wall_time_s, cpu_time_s), compared as text (JSON prints
  doubles with 17 significant digits, so equal text is equal bits);
- with --study, `pcrf study FILE` run by both builds (one rank) and every variable of the two
  cubes (h5py): equal arrays, NaN where NaN, except the wall-time variables.

Prints one line per group and the differing cases, and exits 1 when anything differs.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from scene_cost import SCENES, uplift_threshold_g  # noqa: E402

PRESETS = ("fast", "balanced", "reference")
LEVELS = (1.2, 3.0)  # PGA over the scene's uplift threshold
TIMING = {"wall_time_s", "cpu_time_s"}  # a case's own time, not its answer


def run_json(pcrf, args):
    out = subprocess.run([pcrf, "run", *args], capture_output=True, text=True)
    if out.returncode != 0:
        return {"exit": out.returncode, "stderr": out.stderr.strip()}
    return json.loads(out.stdout)


def same_runs(old, new, records):
    rows, bad = [], []
    for scene, scene_args in SCENES.items():
        thr = uplift_threshold_g(new, scene)
        for preset in PRESETS:
            n = same = 0
            for record in records:
                for level in LEVELS:
                    args = [*scene_args, "--preset", preset, "--record", str(record), "--measure", "pga_g",
                            "--intensity", repr(level * thr)]
                    a, b = run_json(old, args), run_json(new, args)
                    differ = sorted(k for k in set(a) | set(b)
                                    if k not in TIMING and json.dumps(a.get(k)) != json.dumps(b.get(k)))
                    n += 1
                    same += not differ
                    if differ:
                        bad.append(f"{scene} {preset} {record.stem} x{level}: {', '.join(differ)}")
            rows.append((scene, preset, n, same))
    return rows, bad


def same_study(old, new, study):
    import h5py
    import numpy as np
    with tempfile.TemporaryDirectory() as tmp:
        cubes = []
        for name, pcrf in (("old", old), ("new", new)):
            cube = os.path.join(tmp, f"{name}.nc")
            out = subprocess.run([pcrf, "study", str(study), "--output", cube], capture_output=True, text=True)
            if out.returncode != 0:
                sys.exit(f"same_answers: {name} study failed:\n{out.stderr}")
            cubes.append(cube)
        bad, compared = [], 0
        with h5py.File(cubes[0], "r") as a, h5py.File(cubes[1], "r") as b:
            names = []
            a.visititems(lambda k, v: names.append(k) if isinstance(v, h5py.Dataset) else None)
            for k in names:
                if "wall_time" in k or "cpu_time" in k:
                    continue
                if k not in b:
                    bad.append(f"{k}: missing in new")
                    continue
                x, y = a[k][()], b[k][()]
                compared += 1
                if x.dtype.kind == "f":
                    equal = x.shape == y.shape and np.array_equal(x.view(np.uint8), y.view(np.uint8))
                else:
                    equal = x.shape == y.shape and np.array_equal(x, y)
                if not equal:
                    bad.append(f"{k}: differs")
        return compared, bad


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--old", required=True)
    parser.add_argument("--new", required=True)
    parser.add_argument("--records", default=os.environ.get("PCRF_RECORDS_DIR", "../shared/records"))
    parser.add_argument("--study", help="a study file to run with both builds and compare cube by cube")
    o = parser.parse_args()
    records = sorted(Path(o.records, "paper").glob("*.AT2"))
    if not records:
        sys.exit(f"same_answers: no records in {o.records}/paper")
    rows, bad = same_runs(o.old, o.new, records)
    print(f"{'scene':<14} {'preset':<10} {'cases':>5} {'identical':>9}")
    for scene, preset, n, same in rows:
        print(f"{scene:<14} {preset:<10} {n:>5} {same:>9}")
    if o.study:
        compared, study_bad = same_study(o.old, o.new, o.study)
        print(f"study {o.study}: {compared} variables compared, {compared - len(study_bad)} identical bit for bit")
        bad += study_bad
    for line in bad:
        print("DIFFERS", line)
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
