#!/usr/bin/env python3
"""Checkpoint cost (issue 30): the time of one cube checkpoint against the cube's size.

Runs build/bench/checkpoint/pcrf_checkpoint_bench at each --cases size: a cube of 17 metrics
filled completely, then --repeats checkpoints that each follow one chunk (16 384 cases) of new
results; the median checkpoint time, beside the median time of a plain copy of the cube file.
Two value patterns: --varying 2 (two metrics vary from case to case, the others are 0: the
cube of a study whose frames never lift, about 20 MB per 10^6 cases as studies measure) and
--varying 17 (every metric varies: the cube hardly compresses, the worst case).

    python3 bench/checkpoint_cost.py --bench build/bench/checkpoint/pcrf_checkpoint_bench
    python3 bench/checkpoint_cost.py --bench ... --cases 1e5 1e6 --varying 2 --repeats 7
    cmake --build build --target checkpoint_cost           # the same through CMake

Prints a table, then a least-squares line (checkpoint time = a + b * cube size) and what it
gives for the cube of 10^8 cases (ten times the 10^7 one). See docs/checkpoint.md.
"""
import argparse
import re
import subprocess
import tempfile

FIELDS = re.compile(r"cases (\d+) metrics (\d+) cube_MB ([\d.]+) checkpoint_s ([\d.]+) copy_s ([\d.]+) fill_s ([\d.]+)")


def measure(bench, cases, varying, repeats, folder):
    out = subprocess.run([bench, "--cases", str(cases), "--varying", str(varying), "--repeats", str(repeats),
                          "--dir", folder], check=True, capture_output=True, text=True).stdout
    m = FIELDS.search(out)
    if not m:
        raise SystemExit("unexpected output: " + out)
    return {"cases": int(m[1]), "size_mb": float(m[3]), "checkpoint_s": float(m[4]), "copy_s": float(m[5])}


def fit(rows):
    """Least squares checkpoint_s = a + b * size_mb."""
    n = len(rows)
    mx = sum(r["size_mb"] for r in rows) / n
    my = sum(r["checkpoint_s"] for r in rows) / n
    sxx = sum((r["size_mb"] - mx) ** 2 for r in rows)
    b = sum((r["size_mb"] - mx) * (r["checkpoint_s"] - my) for r in rows) / sxx if sxx else 0.0
    return my - b * mx, b


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--bench", required=True, help="pcrf_checkpoint_bench")
    p.add_argument("--pcrf", help="ignored (the CMake bench target passes it)")
    p.add_argument("--cases", nargs="+", type=float, default=[1e5, 1e6, 1e7])
    p.add_argument("--varying", nargs="+", type=int, default=[2, 17])
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--dir", default=None, help="folder for the cubes (default: a temporary one)")
    a = p.parse_args()
    with tempfile.TemporaryDirectory(dir=a.dir) as folder:
        print("| cases | varying metrics | cube [MB] | checkpoint [s] | copy of the cube [s] | rest [s] |")
        print("| ---: | ---: | ---: | ---: | ---: | ---: |")
        for varying in a.varying:
            rows = []
            for cases in a.cases:
                r = measure(a.bench, int(cases), varying, a.repeats, folder)
                rows.append(r)
                print(f"| {r['cases']:.0e} | {varying} | {r['size_mb']:.1f} | {r['checkpoint_s']:.3f} | "
                      f"{r['copy_s']:.3f} | {r['checkpoint_s'] - r['copy_s']:.3f} |", flush=True)
            if len(rows) > 1:
                a0, b = fit(rows)
                big = rows[-1]["size_mb"] * 1e8 / rows[-1]["cases"]
                print(f"varying {varying}: checkpoint = {a0:.3f} s + {1e3 * b:.2f} s/GB x cube; "
                      f"10^8 cases ({big:.0f} MB): {a0 + b * big:.1f} s per checkpoint")


if __name__ == "__main__":
    main()
