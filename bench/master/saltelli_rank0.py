#!/usr/bin/env python3
"""Rank 0's cost per result in a Saltelli study (issue 38 item 1: Saltelli base samples whole
within one chunk, Saltelli studies handed out in whole chunks), of two builds: before, every
Saltelli case went out one by one through rank 0, frame by frame; now the cube's chunks hold
whole base samples and go out whole, column by column, and rank 0 hears a chunk's number.

    python3 bench/master/saltelli_rank0.py --baseline /work/main/build/pcrf --pcrf build/pcrf
    python3 bench/master/saltelli_rank0.py --baseline OLD --pcrf NEW --ranks 4 --columns 8 24

The study: a Saltelli design over eight parameters (d + 2 = 10 frames a base sample, 16 380
frames a chunk: 1 638 base samples) under two weak synthetic records, so that no frame lifts
and what surrounds a case is what shows. Its two sizes are whole columns (`--columns K1 K2`:
K chunks along `case` for each record), so that the tail (the last chunk, case by case)
cancels; the smaller must already give units (at least two chunks a worker and one more:
2·K1 ≥ 2·ranks + 1, e.g. --ranks 4 --columns 6 14). Every rank runs under `valgrind --tool=callgrind --separate-threads=yes`
(bench/master/rank_costs.py's profile_run); rank 0's main thread (the master: hand-out, results,
the cube; it computes no case) per result = (count at the larger size - count at the smaller)
/ the difference in cases. Instruction counts do not depend on the machine's load. Prints a
table: build, that count with and without Open MPI's progress and polling, and the run's phase
(hand-out, results, checkpoints) and assembly (the last fold) apart.
"""
import argparse
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from rank_costs import PHASES, profile_run  # noqa: E402 (one profiler, one parser)

RECORDS = ('[[records]]\nsynthetic = ["stochastic:seed=1,pga_g=0.026,duration_s=3,dt_s=0.01", '
           '"stochastic:seed=2,pga_g=0.02,duration_s=3,dt_s=0.01"]\n')
RANGES = "".join(f"{p} = {{from = {a}, to = {b}}}\n" for p, a, b in [
    ("kappa", 1.26, 2.34), ("tan_alpha", 0.14, 0.26), ("lambda_h", 0.14, 0.26), ("lambda", 1.5, 2.5),
    ("pi_sigma_b", 3.5, 4.5), ("pi_sigma_c", 5.5, 7.5), ("pi_e_b", 2500, 2900), ("pi_e_c", 4000, 4600)])
FRAMES_PER_CHUNK = 16380  # 1 638 base samples of 10 frames
RECORD_COUNT = 2


def write_study(folder, columns):
    samples = columns * FRAMES_PER_CHUNK // 10
    path = os.path.join(folder, f"saltelli{columns}.toml")
    with open(path, "w", encoding="utf-8") as f:
        f.write(f'[study]\nname = "saltelli_rank0"\n{RECORDS}[plan]\nkind = "saltelli"\nsamples = {samples}\n'
                f"seed = 1\n[axes]\n{RANGES}")
    return path, samples * 10 * RECORD_COUNT


def master_per_result(pcrf, ranks, sizes, folder):
    counts, phases, cases = [], [], []
    for k in sizes:
        study, n = write_study(folder, k)
        c, p = profile_run(pcrf, ranks, study, folder, f"cg{k}")[:2]
        counts.append(c.get((0, 1), (0, 0, False)))
        phases.append(p)
        cases.append(n)
    d = cases[1] - cases[0]
    return ((counts[1][0] - counts[0][0]) / d, (counts[1][1] - counts[0][1]) / d,
            {p: (phases[1][p] - phases[0][p]) / d for p in PHASES})


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--baseline", required=True, help="the build before (Saltelli case by case)")
    parser.add_argument("--pcrf", default=os.path.join(HERE, "..", "..", "build", "pcrf"))
    parser.add_argument("--ranks", type=int, default=1, help="MPI ranks (mpirun --oversubscribe)")
    parser.add_argument("--columns", type=int, nargs=2, default=[4, 8], metavar=("K1", "K2"),
                        help="the two sizes in chunks along `case` a record (default 4 8)")
    args = parser.parse_args()
    print(f"saltelli_rank0: Saltelli over 8 parameters, {RECORD_COUNT} weak records (no frame lifts), "
          f"{args.ranks} rank(s), {args.columns[0]} and {args.columns[1]} chunks of {FRAMES_PER_CHUNK} frames "
          "a record; rank 0's main thread, instructions per result (callgrind)\n")
    print("| build | per result, all | MPI left out | before the hand-out | during the run | assembly |")
    print("| --- | ---: | ---: | ---: | ---: | ---: |")
    for name, pcrf in (("before", args.baseline), ("this build", args.pcrf)):
        with tempfile.TemporaryDirectory() as folder:
            total, own, phases = master_per_result(os.path.abspath(pcrf), args.ranks, args.columns, folder)
        print(f"| {name} | {total:,.0f} | {own:,.0f} | {phases['setup']:,.0f} | {phases['run']:,.0f} | "
              f"{phases['assembly']:,.0f} |", flush=True)


if __name__ == "__main__":
    main()
