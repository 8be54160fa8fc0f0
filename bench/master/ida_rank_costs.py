#!/usr/bin/env python3
"""What rank 0 pays per IDA run (issue 38: IDA curves whole within one chunk): rank_costs.py's
method (every rank under callgrind, threads apart, two study sizes whose difference cancels
start-up) on an adaptive IDA whose frames never lift, so that what surrounds a run is what shows.

    python3 bench/master/ida_rank_costs.py --pcrf build/pcrf --ranks 4
    python3 bench/master/ida_rank_costs.py --pcrf /work/main/build/pcrf --ranks 4   # before

The study: an LHS of frames (tan alpha 0.15-0.26) under one weak synthetic record, an IDA at PGA
from 0.04 g to 0.16 g with max_runs 4: every curve runs 0.04, 0.08 and 0.16 g, stays at rest and
is right-censored at the cap (3 runs; its fourth point never run). A chunk of the cube holds 4 096
curves (16 384 cases); the sizes are whole chunks (--chunks N1 N2, default 10 and 20: at 4 ranks
at least 2 a worker and a tail chunk, so that whole chunks are handed out). A result is a run
(the curves times 3, checked against what the study says it computed).

Prints rank 0's main thread (hand-out, results, the cube, the IDA's summaries) per result, all
instructions and with Open MPI's progress and polling left out (rank_costs.MPI_OBJECTS), and
every thread's marginal instructions per result.
"""
import argparse
import os
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.dirname(HERE))
from rank_costs import profile_run  # noqa: E402 (one profiler, one parser)

CURVES_PER_CHUNK = 4096  # 16 384 cases of 4 points
RUNS_PER_CURVE = 3


def write_study(folder, curves):
    path = os.path.join(folder, f"ida_{curves}.toml")
    with open(path, "w") as f:
        f.write(f'[study]\nname = "ida_costs"\n[plan]\nkind = "lhs"\nsamples = {curves}\nseed = 4\n'
                '[[records]]\nsynthetic = "stochastic:seed=1,pga_g=0.1,duration_s=3,dt_s=0.01"\n'
                "[axes]\nkappa = {from = 1.26, to = 2.34}\ntan_alpha = {from = 0.15, to = 0.26}\n"
                'lambda_h = {from = 0.14, to = 0.26}\n[intensity]\nmeasure = "pga_g"\n'
                "[ida]\nstart = 0.04\nmax_intensity = 0.16\nmax_runs = 4\n"
                '[outputs]\nmetrics = ["theta_max_rad", "impacts"]\n')
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--pcrf", default=os.path.join(HERE, "..", "..", "build", "pcrf"))
    parser.add_argument("--ranks", type=int, default=4)
    parser.add_argument("--chunks", type=int, nargs=2, default=[10, 20], metavar=("N1", "N2"))
    args = parser.parse_args()
    pcrf = os.path.abspath(args.pcrf)
    sizes = [n * CURVES_PER_CHUNK for n in args.chunks]
    with tempfile.TemporaryDirectory() as folder:
        runs = [profile_run(pcrf, args.ranks, write_study(folder, n), folder, f"cg{n}")[::2] for n in sizes]
    for (_, computed), curves in zip(runs, sizes):
        if computed != curves * RUNS_PER_CURVE:
            sys.exit(f"ida_rank_costs: {curves} curves computed {computed} runs, not {curves * RUNS_PER_CURVE}")
    results = (sizes[1] - sizes[0]) * RUNS_PER_CURVE
    keys = sorted(set(runs[0][0]) & set(runs[1][0]))
    per = {k: tuple((runs[1][0][k][i] - runs[0][0][k][i]) / results for i in (0, 1)) for k in keys}
    print(f"ida_rank_costs: {pcrf}, {args.ranks} rank(s); IDA of {sizes[0]} and {sizes[1]} curves "
          f"({RUNS_PER_CURVE} runs each, frames at rest);")
    print(f"instructions per result = (count at {sizes[1]} curves - count at {sizes[0]}) / {results} runs, callgrind\n")
    print("| rank | thread | per result, all | per result, MPI left out |")
    print("| --- | --- | --- | --- |")
    for (rank, thread), (total, own) in per.items():
        print(f"| {rank} | {thread} | {total:,.0f} | {own:,.0f} |")
    master = per.get((0, 1), (0.0, 0.0))
    print(f"\nrank 0's main thread per result: {master[0]:,.0f} ({master[1]:,.0f} with MPI left out)")


if __name__ == "__main__":
    main()
