#!/usr/bin/env python3
"""Checkpoint cost (issue 30): a cube checkpoint's time against the cube's size, by journal
append (the checkpoint now) and by fold (a copy of the cube with the changes written into it:
the checkpoint before the journal, and now the fold's mechanism).

Runs build/bench/checkpoint/pcrf_checkpoint_bench --runs times at each --cases size and
prints the median of each field over the runs: a cube of 17 metrics filled completely and
folded, then --repeats checkpoints of one chunk (16 384 new results) each timed as an append
and as a fold (the bench prints their medians), then one fold of a journal holding a quarter
of the cube's cases (kFoldJournalShare), and a plain copy of the cube file. Two value
patterns: --varying 2 (two metrics vary from case to case, the others are 0: the cube of a
study whose frames never lift, about 20 MB per 10^6 cases) and --varying 17 (every metric
varies: the cube hardly compresses, the worst case).

    python3 bench/checkpoint_cost.py --bench build/bench/checkpoint/pcrf_checkpoint_bench
    python3 bench/checkpoint_cost.py --bench ... --cases 1e5 1e6 --varying 2 --runs 3
    cmake --build build --target checkpoint_cost           # the same through CMake

Prints a table, least-squares lines (time = a + b * cube size) for the fold of one chunk and
the fold at a quarter, the append's cost per result, and what they give for a run of 10^8
cases (docs/checkpoint.md): its appends (every result once) and its folds (a geometric
series: each fold comes when the journal holds a quarter of the cube's results, so the cube
grows by 1.25 from one fold to the next).
"""
import argparse
import math
import re
import statistics
import subprocess
import tempfile

FIELDS = re.compile(r"cases (\d+) metrics (\d+) cube_MB ([\d.]+) append_s ([\d.]+) fold_chunk_s ([\d.]+) "
                    r"fold_quarter_s ([\d.]+) journal_quarter_MB ([\d.]+) quarter_appends_s ([\d.]+) quarter_results (\d+) "
                    r"copy_s ([\d.]+) fill_s ([\d.]+) changed (\d+)")
NAMES = ["cases", "metrics", "size_mb", "append_s", "fold_chunk_s", "fold_quarter_s", "journal_mb", "quarter_appends_s",
         "quarter_results", "copy_s", "fill_s", "changed"]
FOLD_SHARE = 0.25  # kFoldJournalShare (cube_writer.hpp) [results in the journal / results in the cube]
FIRST_FOLD_RESULTS = 16384  # results at a run's first fold after creation (one chunk), for the count of folds


def measure(bench, cases, varying, repeats, folder):
    out = subprocess.run([bench, "--cases", str(cases), "--varying", str(varying), "--repeats", str(repeats),
                          "--dir", folder], check=True, capture_output=True, text=True).stdout
    m = FIELDS.search(out)
    if not m:
        raise SystemExit("unexpected output: " + out)
    return {name: float(value) for name, value in zip(NAMES, m.groups())}


def median_of_runs(bench, cases, varying, repeats, runs, folder):
    rows = [measure(bench, cases, varying, repeats, folder) for _ in range(runs)]
    return {name: statistics.median(r[name] for r in rows) for name in NAMES}


def fit(rows, field):
    """Least squares rows[field] = a + b * size_mb."""
    n = len(rows)
    mx = sum(r["size_mb"] for r in rows) / n
    my = sum(r[field] for r in rows) / n
    sxx = sum((r["size_mb"] - mx) ** 2 for r in rows)
    b = sum((r["size_mb"] - mx) * (r[field] - my) for r in rows) / sxx if sxx else 0.0
    return my - b * mx, b


def per_result_text(r):
    """The appends' cost per result [µs] of one row, as text."""
    return f"{1e6 * r['quarter_appends_s'] / r['quarter_results']:.2f}" if r["quarter_results"] > 0 else "–"


def append_per_result(rows):
    """An append's cost per result [s], from the largest cube (the most results appended,
    in the fewest syncs, as a long run's checkpoints)."""
    return rows[-1]["quarter_appends_s"] / rows[-1]["quarter_results"]


def write_per_result(rows):
    """What a fold spends per result on top of a fold of one chunk [s]: reading, laying over,
    compressing and writing the chunks. Either scheme pays it once per result (a chunk is
    written at the checkpoint, or the fold, after its results came): from the largest cube."""
    r = rows[-1]
    return (r["fold_quarter_s"] - r["fold_chunk_s"]) / r["quarter_results"]


def estimate(rows, cases=1e8, checkpoints=None):
    """Checkpoint time of a whole run of `cases` results, old scheme and new, in parts."""
    big = rows[-1]["size_mb"] * cases / rows[-1]["cases"]
    a, b = fit(rows, "fold_chunk_s")  # a checkpoint of one chunk: constant + copy of the cube
    writes = write_per_result(rows) * cases
    # Old: at least one checkpoint per 256 MiB of results held (1.96 million at 17 metrics),
    # each copying the cube as it then is: half the final one on average.
    k = checkpoints or math.ceil(cases / 1.96e6)
    old = k * a + b * big / 2 * k
    # New: every result appended once, and folds, each when the journal holds a quarter of the
    # cube's results, so the cube grows by 1.25 from one to the next: their copies add up to
    # big * (1 + 1/0.25). The appends' constant (a sync) is in the per-result cost measured.
    folds = math.ceil(math.log(cases / FIRST_FOLD_RESULTS) / math.log(1 + FOLD_SHARE))
    appends = append_per_result(rows) * cases
    new = folds * a + b * big * (1 + 1 / FOLD_SHARE)
    return {"big_mb": big, "old_copies_s": old, "checkpoints": k, "writes_s": writes, "appends_s": appends,
            "folds": folds, "new_copies_s": new}


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--bench", required=True, help="pcrf_checkpoint_bench")
    p.add_argument("--pcrf", help="ignored (the CMake bench target passes it)")
    p.add_argument("--cases", nargs="+", type=float, default=[1e5, 1e6, 1e7])
    p.add_argument("--varying", nargs="+", type=int, default=[2, 17])
    p.add_argument("--repeats", type=int, default=5, help="timed appends and folds of one chunk per run")
    p.add_argument("--runs", type=int, default=3, help="runs of the bench per size (the median is printed)")
    p.add_argument("--dir", default=None, help="folder for the cubes (default: a temporary one)")
    a = p.parse_args()
    with tempfile.TemporaryDirectory(dir=a.dir) as folder:
        print("| cases | varying metrics | cube [MB] | old checkpoint: copy + chunk [s] | new checkpoint: append [s] "
              "| append per result [µs] | fold at a quarter [s] | journal then [MB] | copy of the cube [s] |")
        print("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
        for varying in a.varying:
            rows = []
            for cases in a.cases:
                r = median_of_runs(a.bench, int(cases), varying, a.repeats, a.runs, folder)
                rows.append(r)
                print(f"| {r['cases']:.0e} | {varying} | {r['size_mb']:.1f} | {r['fold_chunk_s']:.3f} | "
                      f"{r['append_s']:.4f} | {per_result_text(r)} | {r['fold_quarter_s']:.3f} | {r['journal_mb']:.0f} | "
                      f"{r['copy_s']:.3f} |",
                      flush=True)
            if len(rows) > 1:
                a0, b = fit(rows, "fold_chunk_s")
                e = estimate(rows)
                print(f"varying {varying}: a checkpoint of one chunk = {a0:.3f} s + {1e3 * b:.2f} s/GB x cube; "
                      f"appends {1e6 * append_per_result(rows):.2f} us per result; chunks written "
                      f"{1e6 * write_per_result(rows):.2f} us per result")
                print(f"  10^8 cases ({e['big_mb']:.0f} MB cube): chunks written (either scheme) {e['writes_s']:.0f} s; "
                      f"old: {e['checkpoints']} checkpoints' copies {e['old_copies_s']:.0f} s; "
                      f"new: appends {e['appends_s']:.0f} s + {e['folds']} folds' copies {e['new_copies_s']:.0f} s")


if __name__ == "__main__":
    main()
