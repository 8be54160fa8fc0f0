#!/usr/bin/env python3
"""How far one study scales (issue 38): per-worker efficiency at 16 .. 16 384 workers, from
measured instruction counts (bench/master/rank_costs.py), for cases of three costs.

    python3 bench/master/scaling_model.py                         # the counts measured for this design
    python3 bench/master/scaling_model.py --measure --pcrf build/pcrf   # count them now (1 rank, a few minutes)
    python3 bench/master/scaling_model.py --serial-per-result 14300 --worker-own 0   # one master, 75d5fd5

The model. A worker spends t_case on a case and t_own beyond it on its own side (asking, and
since workers seal whole chunks of the cube, deflating its own results). One rank spends
t_serial per result of the whole study, serially, during the run (rank 0's main thread: the
hand-out, and copying each sealed chunk's bytes into the journal and the cube), and t_setup
per case before the first hand-out (the checks, the plan's points, the new cube's coordinates,
deflated). With W workers the serial rank is busy a share rho = W * t_serial / (t_case + t_own)
of the run; below 1 it keeps up, above it the workers wait for it. Per-worker efficiency of
the run:

    E(W) = t_case / (t_case + t_own) * min(1, 1 / rho)

and with the set-up counted (the workers wait for it): E(W) / (1 + W * t_setup / (t_case + t_own)).
A deterministic bound: queueing delays below saturation make the real figure lower, never
higher; so does the end of a run, where a worker may wait up to one chunk of cases (16 384)
for the others. Times are instructions times --ns-per-instruction (0.145 ns measured on this
project's machine, issue 38). Case costs: a frame that never lifts (measured by callgrind),
0.3 ms (a typical rocking case) and 3.6 ms (a long record's IDA step).
"""
import argparse
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
WORKERS = [16, 64, 256, 2048, 16384]

# Measured with rank_costs.py's method (callgrind, 1 rank, (131 072 - 65 536 cases) / 65 536, a
# non-lifting LHS of 8 parameters, 17 metrics; whole chunks sealed by the worker; same tail):
MASTER_PER_RESULT = 341        # rank 0's main thread during the run, per result, a checkpoint included
                               # (271 in a run without one; 383 at 4 ranks; was 14 300 at 75d5fd5)
MASTER_SETUP_PER_CASE = 9_450  # rank 0 before the first hand-out: coordinates deflated (8 600), the plan (850)
NONLIFT_CASE = 13_160          # the worker's non-lifting case (19 120 in all, less its sealing)
WORKER_OWN_PER_CASE = 5_960    # the worker sealing its chunk: shuffle and deflate 18 variables a case


def efficiency(workers, t_case, t_own, t_serial):
    rho = workers * t_serial / (t_case + t_own)
    return t_case / (t_case + t_own) * min(1.0, 1.0 / rho) if rho > 0 else t_case / (t_case + t_own)


def measure(pcrf):
    """Counts rank 0's run and set-up per case and the worker's per case now (rank_costs.py, 1 rank)."""
    out = subprocess.run([sys.executable, os.path.join(HERE, "rank_costs.py"), "--pcrf", pcrf,
                          "--small", "65536", "131072"], capture_output=True, text=True, check=True).stdout
    rows = re.findall(r"\| 0 \| (\d+) \| ([-0-9,]+) \| ([-0-9,]+) \|", out)
    counts = {int(t): float(own.replace(",", "")) for t, _, own in rows}
    counts.pop(1)
    setup = float(re.search(r"first hand-out[^:]*: ([0-9,]+)", out).group(1).replace(",", ""))
    run = float(re.search(r"during the run \(hand-out[^:]*: ([0-9,]+)", out).group(1).replace(",", ""))
    return run, setup, max(counts.values())


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--measure", action="store_true", help="count the instructions now (needs valgrind)")
    parser.add_argument("--pcrf", default=os.path.join(HERE, "..", "..", "build", "pcrf"))
    parser.add_argument("--serial-per-result", type=float, help="instructions the busiest rank spends per result")
    parser.add_argument("--nonlift-case", type=float, help="instructions of a non-lifting case")
    parser.add_argument("--worker-own", type=float, default=WORKER_OWN_PER_CASE,
                        help="instructions a worker spends per case beyond it (its messages, its own writing)")
    parser.add_argument("--setup-per-case", type=float, default=MASTER_SETUP_PER_CASE,
                        help="instructions rank 0 spends per case before the first hand-out")
    parser.add_argument("--ns-per-instruction", type=float, default=0.145)
    args = parser.parse_args()
    serial, nonlift, own, setup = MASTER_PER_RESULT, NONLIFT_CASE, args.worker_own, args.setup_per_case
    source = "counts measured for chunks sealed by workers (rank_costs.py, 1 rank)"
    if args.measure:
        serial, setup, worker = measure(os.path.abspath(args.pcrf))
        nonlift = worker - own
        source = f"counts measured now ({args.pcrf})"
    if args.serial_per_result is not None:
        serial, source = args.serial_per_result, source + f", busiest rank set to {args.serial_per_result:.0f} a result"
    if args.nonlift_case is not None:
        nonlift = args.nonlift_case
    ns = args.ns_per_instruction
    t_serial, t_own, t_setup = serial * ns * 1e-9, own * ns * 1e-9, setup * ns * 1e-9
    cases = [("non-lifting", nonlift * ns * 1e-9), ("0.3 ms", 0.3e-3), ("3.6 ms", 3.6e-3)]
    print(f"scaling_model: {source}; serial {serial:,.0f} instructions a result ({t_serial * 1e6:.3f} us), "
          f"set-up {setup:,.0f} a case, worker's own {own:,.0f} a case, {ns} ns an instruction\n")
    for title, with_setup in (("the run", False), ("the run and rank 0's set-up before it", True)):
        print(f"per-worker efficiency, {title}:\n")
        print("| case | workers one serial rank feeds | " + " | ".join(f"E({w})" for w in WORKERS) + " |")
        print("| --- | --- |" + " --- |" * len(WORKERS))
        for name, t_case in cases:
            saturation = (t_case + t_own) / t_serial
            cells = []
            for w in WORKERS:
                e = efficiency(w, t_case, t_own, t_serial)
                if with_setup:
                    e /= 1.0 + w * t_setup / (t_case + t_own)
                cells.append(f"{e:.2f}")
            print(f"| {name} ({t_case * 1e6:.1f} us) | {saturation:,.0f} | {' | '.join(cells)} |")
        print()


if __name__ == "__main__":
    main()
