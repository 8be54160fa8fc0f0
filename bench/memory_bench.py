#!/usr/bin/env python3
"""Rank 0's peak memory against the number of cases (not a test): studies of frames that
never lift (a 0.3 g sine; each case is a scan of the record), so that the master, the
hand-out and the cube writer are what is measured. One rank: the master and its worker
thread in one process, whose peak RSS /usr/bin/time reports.

    python3 bench/memory_bench.py --pcrf build/pcrf                 # 10^6 and 10^7 cases
    python3 bench/memory_bench.py --pcrf build/pcrf --cases 1e8     # about 12 minutes here
    python3 bench/memory_bench.py --pcrf build/pcrf --plan lhs --cases 1e5 1e6   # every case a frame

Prints a table: cases, stored metrics, wall time, peak RSS, cube size, and from the second row
on, what each case beyond the first row's costs in RSS and in the cube [bytes a case]. `--plan
lhs`: a Latin hypercube over the eight frame parameters under a weak record
(bench/nonlift_cost.py's study, every case its own frame: the plan's per-case memory shows).
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

# Axes multiplying to the case counts (one record).
AXES = {
    6: ["scale = {from = 0.1, to = 1, count = 100}", "kappa = {from = 1, to = 2.5, count = 100}",
        "lambda = {from = 1.5, to = 2.5, count = 100}"],
}
AXES[7] = AXES[6] + ["tan_alpha = {from = 0.15, to = 0.25, count = 10}"]
AXES[8] = AXES[7] + ["lambda_h = {from = 0.15, to = 0.25, count = 10}"]


def study_text(power, metrics):
    lines = ["[study]", 'name = "memory"', "[[records]]",
             'synthetic = "sine:amplitude_g=0.3,period_s=0.5,cycles=2,duration_s=2"', "[axes]", *AXES[power]]
    if metrics:
        lines += ["[outputs]", "metrics = [" + ", ".join(f'"{m}"' for m in metrics) + "]"]
    return "\n".join(lines) + "\n"


def measure(pcrf, power, metrics, folder, plan="grid", cases=0):
    toml = os.path.join(folder, f"memory{power}.toml")
    cube = os.path.join(folder, f"memory{power}.h5")
    if plan == "lhs":
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        from nonlift_cost import record_table, write_study
        _, scale, records = record_table(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
        toml = write_study(folder, cases, records, scale)
        if metrics:
            with open(toml, "a", encoding="utf-8") as f:
                f.write("[outputs]\nmetrics = [" + ", ".join(f'"{m}"' for m in metrics) + "]\n")
    else:
        with open(toml, "w", encoding="utf-8") as f:
            f.write(study_text(power, metrics))
    done = subprocess.run(["/usr/bin/time", "-f", "%e %M", pcrf, "study", toml, "-o", cube, "--overwrite",
                           "--progress-interval-s", "0"], capture_output=True, text=True, check=True)
    seconds, kib = done.stderr.strip().splitlines()[-1].split()
    size = os.path.getsize(cube)
    info = json.loads(subprocess.run([pcrf, "cube", "info", "--json", cube], capture_output=True, text=True,
                                     check=True).stdout)
    os.remove(cube)
    return float(seconds), int(kib) * 1024, size, len(info["metrics"])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--pcrf", default="build/pcrf")
    parser.add_argument("--cases", nargs="*", default=["1e6", "1e7"], help="10^6, 10^7 or 10^8")
    parser.add_argument("--metrics", nargs="*", default=[], help="stored metrics (default: every one)")
    parser.add_argument("--plan", choices=["grid", "lhs"], default="grid", help="grid (one frame per 100 cases) or lhs")
    args = parser.parse_args()
    print(f"plan {args.plan}\n| cases | stored metrics | wall time [s] | rank 0 peak RSS [MB] | cube [MB] | "
          "RSS beyond the first row [B a case] | cube beyond the first row [B a case] |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    first = None
    with tempfile.TemporaryDirectory(dir=".") as folder:
        for text in args.cases:
            cases = int(float(text))
            power = round(math.log10(cases))
            if args.plan == "grid" and (power not in AXES or 10 ** power != cases):
                sys.exit(f"memory_bench: {text}: choose 1e6, 1e7 or 1e8")
            seconds, rss, size, metrics = measure(os.path.abspath(args.pcrf), power, args.metrics, folder,
                                                  args.plan, cases)
            beyond = "| - | -" if first is None else \
                f"| {(rss - first[1]) / (cases - first[0]):.0f} | {(size - first[2]) / (cases - first[0]):.1f}"
            first = first or (cases, rss, size)
            print(f"| {cases:.0e} | {metrics} | {seconds:.0f} | {rss / 2**20:.0f} | {size / 1e6:.0f} {beyond} |",
                  flush=True)


if __name__ == "__main__":
    main()
