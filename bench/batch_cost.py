#!/usr/bin/env python3
"""Batch cost bench (not a test): cases per second per core of a Latin-hypercube design,
one case at a time against lockstep lanes at W = 1, 2, 4, 8 (docs/batches.md).

    python3 bench/batch_cost.py --bench build/bench/batch/pcrf_batch_bench
        [--cases 10000] [--callgrind-cases 100] [--repeat 3] [--records DIR]

Design: the block (alpha, R) and the prestressed frame (tan alpha, Pi_sigma_c, kappa), under
three of the paper's far-field records (ER1, ER3, ER7, from ../shared/records or
PCRF_RECORDS_DIR; without them the bench says so and stops), each scaled to twice the
design's median uplift threshold, the balanced preset.

Two measures, as a shared and loaded machine requires:
- instructions: valgrind's callgrind, whole process (the design's set-up and reading the
  records included, the same in every row; valgrind runs no AVX-512: its W = 8 row is two
  AVX2 registers);
- time: the one-case run and the batch run in turn (A B A B ...), --repeat pairs, the median
  of the pair ratios, and cases/s of the batch run (median).
Also the batch's own statistics: lane occupancy (share of lane attempts that belonged to a
case), accepted and rejected steps, root searches and events (the scalar work of a lane).
"""
import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

RECORDS = ["ER1_MUL279", "ER3_BOL090", "ER7_CAP000"]
VARIANTS = [("W=1", ["--lanes", "1"]), ("W=2", ["--lanes", "2"]), ("W=4", ["--lanes", "4"]),
            ("W=8", ["--lanes", "8"]), ("W=4 sleef", ["--lanes", "4", "--trig", "sleef"]),
            ("W=8 sleef", ["--lanes", "8", "--trig", "sleef"])]


def records_folder(given):
    for candidate in [given, os.environ.get("PCRF_RECORDS_DIR"),
                      Path(__file__).resolve().parents[2] / "shared" / "records"]:
        if candidate and (Path(candidate) / "paper").is_dir():
            return Path(candidate) / "paper"
    return None


def run(bench, args):
    out = subprocess.run([str(bench)] + args, capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def instructions(bench, args):
    if shutil.which("valgrind") is None:
        return None
    with tempfile.TemporaryDirectory() as tmp:
        out = subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={tmp}/cg"] + [str(bench)] + args,
                             capture_output=True, text=True, check=True)
    for line in out.stderr.splitlines():
        if "Collected :" in line:
            return int(line.split(":")[-1])
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bench", required=True, help="pcrf_batch_bench")
    parser.add_argument("--cases", type=int, default=10000, help="frames of the design (timed runs)")
    parser.add_argument("--callgrind-cases", type=int, default=100, help="frames of the design under callgrind")
    parser.add_argument("--repeat", type=int, default=3, help="A B pairs of timed runs")
    parser.add_argument("--records", help="records folder (default: ../shared/records or PCRF_RECORDS_DIR)")
    a = parser.parse_args()
    folder = records_folder(a.records)
    if folder is None:
        print("batch_cost: the PEER records (../shared/records/paper) are not here; nothing measured")
        return 0
    files = [str(folder / f"{r}.AT2") for r in RECORDS]
    for scene in ["block", "frame"]:
        base = ["--scene", scene] + files
        one = ["--one-case"]
        i_one = instructions(a.bench, base + one + ["--cases", str(a.callgrind_cases)])
        print(f"\n{scene}: {a.cases} frames x {len(files)} records (timed), {a.callgrind_cases} x {len(files)} (callgrind)")
        print("| variant | kernels | instr. vs one-case | time vs one-case | cases/s | occupancy | rejected/accepted |"
              " root searches/step | events/case |")
        print("|---|---|---|---|---|---|---|---|---|")
        for name, args in VARIANTS:
            i_batch = instructions(a.bench, base + args + ["--cases", str(a.callgrind_cases)])
            ratios, rates, stats = [], [], None
            for _ in range(a.repeat):
                t_one = run(a.bench, base + one + ["--cases", str(a.cases)])
                stats = run(a.bench, base + args + ["--cases", str(a.cases)])
                ratios.append(t_one["seconds"] / stats["seconds"])
                rates.append(stats["cases_per_s"])
            instr = f"{i_one / i_batch:.2f}x" if i_one and i_batch else "n/a"
            steps = max(stats["accepted"], 1)
            print(f"| {name} | {stats['kernels']}/{stats['trig']} | {instr} | {statistics.median(ratios):.2f}x |"
                  f" {statistics.median(rates):.0f} | {stats['occupancy']:.3f} | {stats['rejected'] / steps:.4f} |"
                  f" {stats['root_searches'] / steps:.3f} | {stats['events'] / stats['cases']:.0f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
