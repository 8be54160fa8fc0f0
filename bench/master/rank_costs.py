#!/usr/bin/env python3
"""Who pays for a result (issue 38): per rank and per thread, the instructions each case costs,
counted by callgrind, for a Latin hypercube of frames that never lift (bench/nonlift_cost.py's
study: each case a scan of one weak record, so that what surrounds a case is what shows).

    python3 bench/master/rank_costs.py --pcrf build/pcrf                    # 1 rank
    python3 bench/master/rank_costs.py --pcrf build/pcrf --ranks 4 --small 1000 3000
    python3 bench/master/rank_costs.py --pcrf build/pcrf --small 65536 131072   # whole chunks

Workers compute and seal whole chunks of the cube (16 384 cases) once a study has at least two
a worker and one more (study_run.cpp, kUnitsPerWorker): below that, cases go one by one as
before. The last chunk always goes case by case (the tail that balances the end); two sizes
with the same tail (multiples of 16 384 cases) cancel it, and the count at the larger size
alone says what it adds.

Every rank runs under `valgrind --tool=callgrind --separate-threads=yes` at two study sizes;
the difference over the difference in cases cancels start-up (MPI's, the record's, the cube's
creation). Instruction counts do not depend on the machine's load (2 cores shared here).

Prints, per thread of each rank, its marginal instructions per case: all of them, and without
Open MPI's progress and polling (objects of libmpi, open-pal, pmix, ucx, hwloc, libevent,
ld.so and the kernel's vdso), which on an oversubscribed machine count how long a thread waited,
not what it did. Then:
- rank 0's main thread (the master: hand-out, results, the cube) per result, beyond its own
  cases (it computes none; rank 0's cases run in its worker thread), and how much of it is
  spent before the first hand-out (checks, creating the cube with its coordinates), during
  the run (hand-out, storing what comes back, checkpoints) and in the assembly (the last fold,
  CubeWriter::close: the worker ranks' parts and rank 0's journal written into the cube), and
  of the run's, what streaming the parts' chunks into the next fold as workers report them
  costs (CubeWriter::stream_kept: what the assembly no longer writes);
- the balance: the busiest thread's marginal instructions (MPI left out) over the mean of the
  threads that work, those that compute cases (their profile has the case runner's functions;
  rank 0's main thread and the progress threads do not), issue 38 item 5 asks for at most 1.25.
  With whole chunks (16 384 cases) handed out dynamically, a worker's share moves by a chunk:
  the difference between the two sizes should be many chunks a worker (e.g. --ranks 4
  --small 294912 1179648: 54 chunks, 13.5 a worker).
"""
import argparse
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
from nonlift_cost import ENV, function_costs, record_table, write_study  # noqa: E402 (one study, one parser)

# Objects whose instructions are MPI's progress and polling, not a thread's own work.
MPI_OBJECTS = re.compile(r"libmpi|open-pal|open-rte|libpmix|pmix|libucs|libucp|libuct|libhwloc|libevent|"
                         r"ld-linux|vdso|libfabric|libpsm")
# A working thread is one that computes cases: its profile has the case runner's functions
# (rank 0's main thread, which hands out and stores, and the progress threads do not).
CASE_FUNCTIONS = re.compile(r"pcrf::run::CaseRunner::(set_up|conclude)\(")


# Rank 0's main thread, split by what it is doing (inclusive counts, callgrind_annotate):
# before the first hand-out (reading the study and making its plan, the checks, the new cube
# with its coordinates: in prepare_master up to da9ce77, in create_cube since, which waits
# while the other ranks seal the coordinates) and during the run (hand-out, storing what
# comes back, checkpoints): run_study less what it spends in those and in the assembly,
# whatever the compiler inlined. The assembly: the writer's last fold (CubeWriter::close),
# which writes the ranks' parts (and rank 0's own journal) into the cube.
FUNCTIONS = {"study": "pcrf::run::run_study(", "load": "pcrf::study::load_study(", "prepare": "::prepare_master(",
             "create": "::create_cube(", "close": "pcrf::cube::CubeWriter::close(",
             "stream": "::stream_kept(", "wait": "pcrf::run::WorkerCoordinates::take(",
             "handle": "::Master::handle(", "idle": "_Function_handler<void (), pcrf::run::(anonymous namespace)::run_master_rank("}
PHASES = ("setup", "run", "assembly", "streamed", "setup_work", "run_work")


# A working thread's instructions, split (inclusive counts): its cases (the case runner), sealing
# the chunks it computed whole (ChunkSealer), the cube's coordinate pieces it sealed at the
# creation (a worker rank's share of it); the rest of the thread is its own side beyond them
# (asking for work, its part, messages, MPI).
WORKER_FUNCTIONS = {"case": "pcrf::run::CaseRunner::run(", "seal": "ChunkSealer::operator()(",
                    "create": "pcrf::run::seal_coordinates_for_rank0("}
WORKER_PARTS = ("case", "seal", "create", "total")


def inclusive_of(path, functions):
    """{key: inclusive instructions of the first function whose name holds functions[key]}."""
    out = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", path],
                         capture_output=True, text=True).stdout
    found = dict.fromkeys(functions, 0)
    for line in out.splitlines():
        for key, name in functions.items():
            if name in line and not found[key]:
                found[key] = int(line.split()[0].replace(",", ""))
    return found


def inclusive_phases(path):
    """Instructions of each of PHASES in one callgrind file."""
    found = inclusive_of(path, FUNCTIONS)
    setup = found["load"] + found["prepare"] + found["create"]  # create_cube: the new cube, made with every rank
    # Streamed: the parts' chunks written into the next fold as workers report them (the sink's
    # stream_kept, CubeWriter::stream_kept), during the run and counted in it.
    # Rank 0's own work, its waits left out: in the set-up, the wait for the workers' coordinate
    # pieces (WorkerCoordinates::take: polling while they seal, the creation's parallel part,
    # which scaling_model.py counts as the workers' t_create); in the run, what comes back
    # (Master::handle: the hand-out, statuses, the stream) and the checkpoints between messages
    # (the idle handler), not the polling while no message is there (absent once rank 0 is
    # saturated, the only case where its run cost limits the study).
    return {"setup": setup, "run": found["study"] - setup - found["close"], "assembly": found["close"],
            "streamed": found["stream"], "setup_work": setup - found["wait"],
            "run_work": found["handle"] + found["idle"]}


def profile_run(pcrf, ranks, study, folder, tag, keep=None):
    """Runs the study under callgrind on every rank; returns {(rank, thread): (all, own, works)}
    counts, rank 0's main thread's PHASES, the cases the study said it computed (None when it
    did not say) and the working threads' WORKER_PARTS summed. `keep` (a folder): rank 0's main
    thread's profile, and rank 1's working thread's, are copied there (for callgrind_annotate)."""
    out = os.path.join(folder, f"{tag}.%q{{OMPI_COMM_WORLD_RANK}}")
    valgrind = ["valgrind", "--tool=callgrind", "--separate-threads=yes", f"--callgrind-out-file={out}"]
    # One checkpoint, at the end: checkpoints come by the clock (every 30 s by default), and under
    # callgrind a run is some 50 times slower, so the larger size would take more of them a
    # result than at full speed, and by chance (one more or one fewer moved rank 0's run and
    # assembly by 5 to 8 instructions a result between repeats). What a checkpoint costs is a
    # cost per checkpoint (docs/checkpoint.md), not per result.
    command = valgrind + [pcrf, "study", study, "-o", os.path.join(folder, "cube.h5"), "--overwrite",
                          "--progress-interval", "0", "--flush-interval-s", "1e6"]
    if ranks > 1:
        command = ["mpirun", "--oversubscribe", "-n", str(ranks)] + command
    env = dict(ENV, OMPI_COMM_WORLD_RANK=ENV.get("OMPI_COMM_WORLD_RANK", "0"))
    done = subprocess.run(command, capture_output=True, text=True, env=env)
    if done.returncode != 0:
        sys.exit(f"rank_costs: {' '.join(command)} failed:\n{done.stderr[-3000:]}")
    counts, phases, split = {}, dict.fromkeys(PHASES, 0), dict.fromkeys(WORKER_PARTS, 0)
    for path in glob.glob(os.path.join(folder, f"{tag}.*")):
        match = re.search(r"\.(\d+)-(\d+)$", path)
        if not match:
            continue
        if (int(match.group(1)), int(match.group(2))) == (0, 1):
            phases = inclusive_phases(path)
            if keep:
                shutil.copy(path, os.path.join(keep, f"{tag}.rank0-main"))
        elif keep and (int(match.group(1)), int(match.group(2))) == (1, 1):
            shutil.copy(path, os.path.join(keep, f"{tag}.rank1-main"))  # a worker rank's working thread
        costs = function_costs(path)
        total = sum(costs.values())
        own = sum(c for (obj, _), c in costs.items() if not MPI_OBJECTS.search(obj))
        works = any(CASE_FUNCTIONS.search(fn) for (_, fn) in costs)
        counts[(int(match.group(1)), int(match.group(2)))] = (total, own, works)
        if works:
            for key, value in inclusive_of(path, WORKER_FUNCTIONS).items():
                split[key] += value
            split["total"] += total
        os.remove(path)
    said = re.search(r"(\d+) cases computed", done.stderr)
    return counts, phases, int(said.group(1)) if said else None, split


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--pcrf", default=os.path.join(HERE, "..", "..", "build", "pcrf"))
    parser.add_argument("--ranks", type=int, default=1, help="MPI ranks (mpirun --oversubscribe)")
    parser.add_argument("--small", type=int, nargs=2, default=[2000, 10000], metavar=("N1", "N2"),
                        help="the two study sizes (default 2000 10000)")
    parser.add_argument("--source", default=os.path.join(HERE, "..", ".."), help="source tree (../shared/records)")
    parser.add_argument("--keep", metavar="DIR", help="copy rank 0's main thread's callgrind profiles here "
                        "(<DIR>/cg<N>.rank0-main: compare them with callgrind_annotate), and rank 1's working "
                        "thread's (<DIR>/cg<N>.rank1-main)")
    args = parser.parse_args()
    pcrf = os.path.abspath(args.pcrf)
    label, scale, records = record_table(args.source)
    small, large = args.small
    with tempfile.TemporaryDirectory() as folder:
        if args.keep:
            os.makedirs(args.keep, exist_ok=True)
        runs = [profile_run(pcrf, args.ranks, write_study(folder, n, records, scale), folder, f"cg{n}", args.keep)
                for n in (small, large)]
    phases = {p: (runs[1][1][p] - runs[0][1][p]) / (large - small) for p in PHASES}
    split = {p: (runs[1][3][p] - runs[0][3][p]) / (large - small) for p in WORKER_PARTS}
    run_alone = (runs[1][1]["run"] + runs[1][1]["assembly"]) / large  # the run's fixed costs (its tail) included
    runs = [counts for counts, _, _, _ in runs]
    keys = sorted(set(runs[0]) & set(runs[1]))
    per_case = {k: tuple((runs[1][k][i] - runs[0][k][i]) / (large - small) for i in (0, 1)) for k in keys}
    works = {k for k in keys if runs[1][k][2]}  # threads that computed cases in the larger run
    print(f"rank_costs: non-lifting LHS over eight parameters, record {label}, {args.ranks} rank(s);")
    print(f"instructions per case = (count at {large} cases - count at {small}) / {large - small}, callgrind\n")
    print("| rank | thread | computes cases | per case, all | per case, MPI left out |")
    print("| --- | --- | --- | --- | --- |")
    for (rank, thread), (total, own) in per_case.items():
        print(f"| {rank} | {thread} | {'yes' if (rank, thread) in works else 'no'} | {total:,.0f} | {own:,.0f} |")
    total_all = sum(t for t, _ in per_case.values())
    working = [own for k, (_, own) in per_case.items() if k in works]
    master = per_case.get((0, 1), (0.0, 0.0))
    print(f"\nall threads together: {total_all:,.0f} instructions per case")
    print(f"rank 0's main thread (master, cube) per result beyond its own cases: {master[0]:,.0f} "
          f"({master[1]:,.0f} with MPI left out)")
    print(f"  of which before the first hand-out (plan, checks, the new cube's coordinates): {phases['setup']:,.0f}; "
          f"during the run (hand-out, results, checkpoints): {phases['run']:,.0f}; "
          f"the assembly (the last fold, CubeWriter::close: the parts' chunks and rank 0's journal into the cube): "
          f"{phases['assembly']:,.0f}")
    print(f"  of the run's, the parts' chunks streamed into the next fold as they are reported "
          f"(stream_kept): {phases['streamed']:,.0f}")
    print(f"  its own work, waits left out (scaling_model.py): set-up {phases['setup_work']:,.1f} (the wait for "
          f"the workers' coordinate pieces left out); run {phases['run_work']:,.1f} (Master::handle and the "
          f"checkpoints between messages, its polling left out); assembly {phases['assembly']:,.1f}")
    print(f"  during the run at {large} cases alone, its fixed costs (the last chunk, case by case) included: "
          f"{run_alone:,.0f} a case")
    print(f"the working threads together, per case: its case {split['case']:,.0f}; sealing the chunks they computed "
          f"whole {split['seal']:,.0f}; the cube's coordinate pieces at the creation {split['create']:,.0f}; "
          f"the rest of their own side {split['total'] - split['case'] - split['seal'] - split['create']:,.0f}")
    if working:
        mean = sum(working) / len(working)
        print(f"balance: busiest thread {max(working):,.0f} / mean of {len(working)} working threads "
              f"{mean:,.0f} = {max(working) / mean:.2f} (goal <= 1.25)")


if __name__ == "__main__":
    main()
