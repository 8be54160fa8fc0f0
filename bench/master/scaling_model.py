#!/usr/bin/env python3
"""How far one study scales (issue 38): per-worker efficiency at 16 .. 16 384 workers, from
measured instruction counts (bench/master/rank_costs.py), for cases of three costs.

    python3 bench/master/scaling_model.py                         # the counts measured at 75d5fd5
    python3 bench/master/scaling_model.py --measure --pcrf build/pcrf   # count them now (1 rank, ~1 min)
    python3 bench/master/scaling_model.py --serial-per-result 200       # a design whose busiest rank pays 200

The model. A worker spends t_case on a case and t_own beyond it on its own side of the
hand-out (asking, sending its row); one rank spends t_serial per result of the whole study,
serially (today: rank 0's master thread, which receives, folds and deflates every result into
the cube). With W workers the serial rank is busy a share rho = W * t_serial / (t_case + t_own)
of the time; below 1 it keeps up, above it the workers wait for it. Per-worker efficiency:

    E(W) = t_case / (t_case + t_own) * min(1, 1 / rho)

(a deterministic bound: queueing delays below saturation make the real figure lower, never
higher). Times are instructions times --ns-per-instruction (0.145 ns measured on this
project's machine, issue 38). Case costs: a frame that never lifts (its instructions measured
by callgrind, 12.4 k), 0.3 ms (a typical rocking case) and 3.6 ms (a long record's IDA step).
"""
import argparse
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
WORKERS = [16, 64, 256, 2048, 16384]

# Measured at 75d5fd5 with rank_costs.py (callgrind, (3000 - 1000 cases) / 2000, 1 rank and 4 ranks):
MASTER_PER_RESULT = 14_300     # rank 0's main thread per result: hand-out, result, cube store and fold
NONLIFT_CASE = 12_400          # rank 0's worker thread per non-lifting case (1 rank: it computes every case)
WORKER_OWN_PER_CASE = 0        # measured within NONLIFT_CASE at 1 rank; see --worker-own


def efficiency(workers, t_case, t_own, t_serial):
    rho = workers * t_serial / (t_case + t_own)
    return t_case / (t_case + t_own) * min(1.0, 1.0 / rho) if rho > 0 else t_case / (t_case + t_own)


def measure(pcrf):
    """Counts rank 0's master and worker instructions per case now (rank_costs.py, 1 rank)."""
    out = subprocess.run([sys.executable, os.path.join(HERE, "rank_costs.py"), "--pcrf", pcrf,
                          "--small", "1000", "3000"], capture_output=True, text=True, check=True).stdout
    rows = re.findall(r"\| 0 \| (\d+) \| ([-0-9,]+) \|", out)
    counts = {int(t): float(c.replace(",", "")) for t, c in rows}
    master = counts.pop(1)
    worker = max(counts.values())
    return master, worker


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--measure", action="store_true", help="count the instructions now (needs valgrind)")
    parser.add_argument("--pcrf", default=os.path.join(HERE, "..", "..", "build", "pcrf"))
    parser.add_argument("--serial-per-result", type=float, help="instructions the busiest rank spends per result")
    parser.add_argument("--nonlift-case", type=float, help="instructions of a non-lifting case")
    parser.add_argument("--worker-own", type=float, default=WORKER_OWN_PER_CASE,
                        help="instructions a worker spends per case beyond it (its messages, its own writing)")
    parser.add_argument("--ns-per-instruction", type=float, default=0.145)
    args = parser.parse_args()
    serial, nonlift = MASTER_PER_RESULT, NONLIFT_CASE
    source = "counts measured at 75d5fd5 (rank_costs.py)"
    if args.measure:
        serial, nonlift = measure(os.path.abspath(args.pcrf))
        source = f"counts measured now ({args.pcrf})"
    if args.serial_per_result is not None:
        serial, source = args.serial_per_result, source + f", busiest rank set to {args.serial_per_result:.0f} a result"
    if args.nonlift_case is not None:
        nonlift = args.nonlift_case
    ns = args.ns_per_instruction
    t_serial, t_own = serial * ns * 1e-9, args.worker_own * ns * 1e-9
    cases = [("non-lifting", nonlift * ns * 1e-9), ("0.3 ms", 0.3e-3), ("3.6 ms", 3.6e-3)]
    print(f"scaling_model: {source}; serial {serial:,.0f} instructions a result "
          f"({t_serial * 1e6:.2f} us), worker's own {args.worker_own:,.0f} a case, {ns} ns an instruction\n")
    print("| case | workers one serial rank feeds | " + " | ".join(f"E({w})" for w in WORKERS) + " |")
    print("| --- | --- |" + " --- |" * len(WORKERS))
    for name, t_case in cases:
        saturation = (t_case + t_own) / t_serial
        row = " | ".join(f"{efficiency(w, t_case, t_own, t_serial):.2f}" for w in WORKERS)
        print(f"| {name} ({t_case * 1e6:.1f} us) | {saturation:,.0f} | {row} |")


if __name__ == "__main__":
    main()
