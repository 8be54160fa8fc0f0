#!/usr/bin/env python3
"""The Python module's costs (a benchmark, not a test), on the paper's records:

1. a thread pool over cases: wall time of the same cases on 1 and 2 threads (the engine
   releases the GIL while it solves), median of --repeats runs;
2. the in-process overhead: the time of a pcrf.run call against the case's own cpu_time_s,
   median of --calls calls per record.

    PYTHONPATH=build/python python3 bench/python_module.py [--records DIR] [--repeats 5] [--calls 41]

Records: ../shared/records/paper beside the checkout (PCRF_RECORDS_DIR overrides).
"""

import argparse
import concurrent.futures
import os
import statistics
import time
from pathlib import Path

import numpy as np

import pcrf


def read_at2(path):
    """The accelerations [g] and dt of a PEER .AT2 file (NPTS=, DT= header)."""
    lines = Path(path).read_text().splitlines()
    header = lines[3].replace(",", " ").split()
    dt_s = float(header[header.index("DT=") + 1])
    return np.array([float(v) for line in lines[4:] for v in line.split()]), dt_s


def records(folder):
    return [(p.stem, *read_at2(p)) for p in sorted(Path(folder).glob("*.AT2"))]


def pool_seconds(cases, threads):
    start = time.perf_counter()
    with concurrent.futures.ThreadPoolExecutor(max_workers=threads) as pool:
        list(pool.map(lambda case: pcrf.run(case[1], case[2], scale=case[3]), cases))
    return time.perf_counter() - start


def thread_table(motions, repeats):
    cases = [(name, accel, dt, scale) for name, accel, dt in motions for scale in (2.0, 2.5, 3.0)]
    pool_seconds(cases[:2], 2)  # warm-up
    print(f"\nThread pool: {len(cases)} cases (paper records x scales 2, 2.5, 3; balanced), median of {repeats}")
    print("| threads | wall [s] | cases/s | speed-up |")
    print("| --- | --- | --- | --- |")
    one = None
    for threads in (1, 2):
        # Interleaved with the other thread count would be fairer under load; each row is a median.
        seconds = statistics.median(pool_seconds(cases, threads) for _ in range(repeats))
        one = one or seconds
        print(f"| {threads} | {seconds:.3f} | {len(cases) / seconds:.1f} | {one / seconds:.2f} |")


def overhead_table(motions, calls):
    print(f"\nIn-process overhead: pcrf.run(array, dt, scale=2.5) against its cpu_time_s, median of {calls} calls")
    print("| record | cpu_time_s [ms] | call [ms] | call / cpu_time_s |")
    print("| --- | --- | --- | --- |")
    ratios = []
    for name, accel, dt in motions:
        pcrf.run(accel, dt, scale=2.5)
        per_call, walls = [], []
        for _ in range(calls):
            start = time.perf_counter()
            result = pcrf.run(accel, dt, scale=2.5)
            per_call.append(time.perf_counter() - start)
            walls.append(result["cpu_time_s"])
        ratio = statistics.median(c / w for c, w in zip(per_call, walls))
        ratios.append(ratio)
        print(f"| {name} | {1e3 * statistics.median(walls):.3f} | {1e3 * statistics.median(per_call):.3f} | {ratio:.4f} |")
    print(f"| median over records | | | {statistics.median(ratios):.4f} |")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    default = Path(os.environ.get("PCRF_RECORDS_DIR") or Path(__file__).resolve().parents[2] / "shared" / "records")
    parser.add_argument("--records", type=Path, default=default / "paper")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--calls", type=int, default=41)
    args = parser.parse_args()
    motions = records(args.records)
    if not motions:
        raise SystemExit(f"no .AT2 records in {args.records}")
    print(f"pcrf {pcrf.__version__}, {len(motions)} records from {args.records}, {os.cpu_count()} cores")
    thread_table(motions, args.repeats)
    overhead_table(motions, args.calls)


if __name__ == "__main__":
    main()
