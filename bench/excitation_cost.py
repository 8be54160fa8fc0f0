#!/usr/bin/env python3
"""Excitation cost bench (not a test): what a case without a vertical component costs with
this build against another build of pcrf (e.g. one from before the Excitation layer), and
that both give the same result.

    python3 bench/excitation_cost.py --pcrf build/pcrf --reference /path/to/old/pcrf [--repeat 7]

For each of the paper's records (../shared/records/paper, scale 2.5: every one rocks the
basic frame) it runs `pcrf run` with each binary in turn, --repeat times, interleaved so that
a loaded machine slows both alike, and keeps the median of the solver's own cpu_time_s
(process start-up excluded). It prints a table and the geometric mean of the ratios.
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from scene_cost import case_time_s  # noqa: E402


def run(pcrf, record):
    out = subprocess.run([pcrf, "run", "--record", str(record), "--scale", "2.5"], capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"excitation_cost: {pcrf} failed on {record}:\n{out.stderr}")
    return json.loads(out.stdout)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pcrf", required=True)
    parser.add_argument("--reference", required=True, help="the other pcrf binary")
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--records", default=str(Path(__file__).resolve().parents[1].parent / "shared" / "records"))
    args = parser.parse_args()
    records = sorted((Path(args.records) / "paper").glob("*.AT2"))
    if not records:
        print(f"excitation_cost: no records in {args.records}/paper: skipped")
        return
    print(f"{'record':<16} {'this [ms]':>10} {'reference [ms]':>15} {'ratio':>7}  same result")
    ratios = []
    for record in records:
        mine, theirs = [], []
        same = True
        for _ in range(args.repeat):
            a, b = run(args.pcrf, record), run(args.reference, record)
            mine.append(case_time_s(a))
            theirs.append(case_time_s(b))
            same = same and all(a[k] == b[k] for k in ("theta_max_rad", "t_theta_max_s", "impacts", "status", "steps"))
        m, t = statistics.median(mine), statistics.median(theirs)
        ratios.append(m / t)
        print(f"{record.stem:<16} {1e3 * m:10.2f} {1e3 * t:15.2f} {m / t:7.3f}  {'yes' if same else 'NO'}")
    print(f"geometric mean ratio (this / reference): {math.exp(statistics.mean(map(math.log, ratios))):.3f}")


if __name__ == "__main__":
    main()
