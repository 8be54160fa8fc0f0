#!/usr/bin/env python3
"""How far one study scales (issue 38): per-worker efficiency at 16 .. 16 384 workers, from
measured instruction counts (bench/master/rank_costs.py), for cases of three costs.

    python3 bench/master/scaling_model.py                         # the counts measured for this design
    python3 bench/master/scaling_model.py --measure --pcrf build/pcrf   # count them now (1 and 4 ranks, minutes)
    python3 bench/master/scaling_model.py --serial-per-result 14300 --worker-own 0 --setup-per-case 6000 \\
        --assembly-per-result 0 --creation-per-case 0          # one master, 75d5fd5

The model. A study of N cases runs on W workers. Each worker spends t_case on a case and t_own
beyond it on its own side (asking for work, sealing its chunks of the cube and each sampled
parameter's chunk of its cases, writing them to its part), and t_create per case of its share
of the cube's creation (the coordinates written there: the case number's chunks, before the
first hand-out). Rank 0 spends, on one thread:
  - t_setup per case of the study before the first hand-out, serially (the plan, the checks,
    writing the creation's sealed chunks into the new cube);
  - t_serial per result during the run, concurrently with the workers (the hand-out, what comes
    back, its checkpoints, and each part's sealed chunks streamed into the next fold as its
    worker reports them): it limits the run only once it saturates, at a share
    rho = W * t_serial / (t_case + t_own) of the run above 1;
  - t_assembly per result after the run, serially (the last fold: what the stream does not
    hold, each chunk's statuses, and the coordinates' chunks no unit brought).
The run's wall time is then N (t_setup + t_assembly) + N (t_create + (t_case + t_own) max(1, rho)) / W,
against N t_case / W for perfect workers, so the per-worker efficiency is

    E(W) = t_case / (W (t_setup + t_assembly) + t_create + (t_case + t_own) max(1, rho)).

A deterministic bound: queueing below saturation and the end of a run (a worker may wait up to
one chunk of 16 384 cases for the others) only lower it. Instructions are turned into time at
--ns-per-instruction (0.145 ns measured on this project's machine, issue 38).

Two more things. The last column, "no rank 0", is the bound with rank 0 free (t_setup =
t_serial = t_assembly = 0): t_case / (t_case + t_own + t_create), what the workers' own side
allows at any W. The second table adds the bytes that rank 0, the cube's one writer, puts in
the file (HDF5's direct chunk write is "not supported with parallel HDF5", H5Dpublic.h of
1.10.8 and of 1.14), at --write-gb-s, an assumed sustained single-writer bandwidth (no cluster
file system can be measured here), from pcrf_cube_filters on the non-lifting LHS:
  - the coordinates' chunks written at the creation, --coordinate-bytes-per-case (the case
    number's, 0.07 B; 53.5 B when every sampled parameter was written there): serial, t_setup
    grows by them;
  - the results' chunks with the sampled parameters' chunks, --result-bytes-per-case (88.3 B),
    streamed into the next fold while the run goes on (CubeWriter::stream_kept): t_serial grows
    by them. --assembled-at-end puts them in t_assembly instead, as the design before the
    streaming fold did.
Case costs: a frame that never lifts (measured by callgrind), 0.3 ms (a typical rocking case)
and 3.6 ms (a long record's IDA step).

A third table is a study past ~3.4e7 cases (2 048 chunks a variable). rank_costs.py's study has 72
chunks a variable, and HDF5 then keeps every chunk index's entries in its metadata cache until the
last fold's file closes (t_assembly). bench/master/index_close_cost.py writes the cube's 26
variables' chunks as the stream does at growing sizes: the close grows with the chunks up to ~2 048
a variable, then stays at 13.5 M instructions (~2 ms, a fixed cost), since HDF5 writes the index
pages it evicts during the run, where each raw chunk write costs ~1 170 instructions more (3 360 ->
4 530): --index-evictions-per-result (1.9) goes to t_serial, and t_assembly is taken as zero there
(instructions alone, as the first table).
"""
import argparse
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
WORKERS = [16, 64, 256, 2048, 16384]

# Measured with callgrind on a non-lifting LHS of 8 parameters, 17 metrics, at 4 ranks, on main at 210be1d
# (rank_costs.py --ranks 4 --small 294912 1179648, one checkpoint at the end: marginal instructions between the
# two sizes, so that start-up cancels; rank 0's own work with its waits left out, and the working threads'
# split, both printed by rank_costs.py; studies/README.md "The master at cluster scale"):
MASTER_SETUP_PER_CASE = 0.1       # rank 0's main thread before the first hand-out, its wait for the workers'
                                  # pieces left out: the plan, the checks, the case number's chunks of up to 2^20
                                  # values (cube::kCreationCoordinateChunk), a raw chunk write each (0.4-0.58 in
                                  # chunks of 16 384 at f1ca852; 11 600 at da9ce77)
MASTER_RUN_PER_RESULT = 6.9       # rank 0's main thread during the run, its polling between messages left out:
                                  # what comes back (Master::handle), nearly all of it the parts' chunks streamed
                                  # into the next fold (CubeWriter::stream_kept: HDF5's raw chunk write with
                                  # fixed-array chunk indices, 18 variables and 8 coordinate chunks a unit); 8.1
                                  # at f1ca852, with an error text built for each coordinate chunk
MASTER_ASSEMBLY_PER_RESULT = 0.4  # rank 0's main thread in the last fold, after the run: HDF5 serializing each
                                  # variable's chunk index as the fold's file closes (26 fixed arrays, ~240
                                  # instructions an entry), 0.38 a result at this study's 72 chunks a variable.
                                  # rank_costs.py prints -0.2 to 0.3 here: the last chunk, stored case by case and
                                  # deflated as its variables close (120 M instructions at either size), varies
                                  # with its data by +-0.5 a result; its own count is left out. 0.4 to 0.7 at
                                  # f1ca852 (each part read again from its start, a part's name built a chunk,
                                  # HDF5's storage summed per coordinate), 11 before the streaming fold
INDEX_EVICTIONS_PER_RESULT = 1.9  # past ~2 048 chunks a variable, HDF5's index pages written during the run as the
                                  # metadata cache evicts them (26 chunk writes a unit, ~1 170 instructions more
                                  # each: bench/master/index_close_cost.py), while the close stays at 13.5 M
NONLIFT_CASE = 13_755             # a worker's non-lifting case (CaseRunner::run), its LHS point included: each unit's
                                  # parameters computed once, by the design's columns, in its cases' set-up
                                  # (ColumnWindow, 1 410), read from there by the sealing; its row from the worker's
                                  # pool (parallel::pooled_row). 15 190 at f1ca852, when each case computed its point
                                  # by the design's row (2 490); 16 100 at e2c9aee
WORKER_OWN_PER_CASE = 2_432       # sealing its chunk and its chunk of each coordinate 2 281 (deflating the metrics'
                                  # and the coordinates' streams ~2 090, the coordinates' values read from the unit's
                                  # window 65, gathering the rows and one copy of the streams into the unit's bytes
                                  # ~150), its part (written from those bytes as they lie, libdeflate's CRC-32), its
                                  # batch of rows and messages 151. 4 910 at f1ca852 (sealing 4 050 with the
                                  # coordinates' values computed again from the plan, 1 450; the rest 860)
WORKER_CREATION_PER_CASE = 68     # the case number's pieces sealed by the workers at the creation, per case of
                                  # the study (2 565 when the sampled parameters were sealed there too)


def efficiency(workers, t_case, t_own, t_create, t_serial, t_setup, t_assembly):
    """E(W) of the docstring."""
    rho = workers * t_serial / (t_case + t_own)
    return t_case / (workers * (t_setup + t_assembly) + t_create + (t_case + t_own) * max(1.0, rho))


def table(cases, t_own, t_create, t_serial, t_setup, t_assembly):
    """Prints E(W) for each case cost, with rank 0's saturation and the bound without rank 0."""
    print("| case | workers rank 0 feeds in the run | " + " | ".join(f"E({w})" for w in WORKERS) + " | no rank 0 |")
    print("| --- | --- |" + " --- |" * (len(WORKERS) + 1))
    for name, t_case in cases:
        saturation = (t_case + t_own) / t_serial if t_serial > 0 else float("inf")
        cells = [f"{efficiency(w, t_case, t_own, t_create, t_serial, t_setup, t_assembly):.2f}" for w in WORKERS]
        bound = t_case / (t_case + t_own + t_create)
        print(f"| {name} ({t_case * 1e6:.1f} us) | {saturation:,.0f} | {' | '.join(cells)} | {bound:.2f} |")


def measure(pcrf):
    """Rank 0's set-up, run and assembly per case now (rank_costs.py at 4 ranks, a few minutes)."""
    out = subprocess.run([sys.executable, os.path.join(HERE, "rank_costs.py"), "--pcrf", pcrf, "--ranks", "4",
                          "--small", "294912", "1179648"], capture_output=True, text=True, check=True).stdout
    figure = lambda pattern: float(re.search(pattern, out).group(1).replace(",", ""))  # noqa: E731
    # Its own work, its waits left out (rank_costs.py says which): the set-up's wait for the
    # workers' pieces is the creation's parallel part (t_create), its polling in the run idle time.
    return (figure(r"own work, waits left out[^:]*: set-up ([0-9.,-]+)"), figure(r"; run ([0-9.,-]+) \(Master::handle"),
            figure(r"pieces left out\); run [^;]*; assembly ([0-9.,-]+)"))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--measure", action="store_true", help="count rank 0's instructions now (needs valgrind)")
    parser.add_argument("--pcrf", default=os.path.join(HERE, "..", "..", "build", "pcrf"))
    parser.add_argument("--serial-per-result", type=float, default=MASTER_RUN_PER_RESULT,
                        help="instructions rank 0 spends per result during the run")
    parser.add_argument("--setup-per-case", type=float, default=MASTER_SETUP_PER_CASE,
                        help="instructions rank 0 spends per case before the first hand-out")
    parser.add_argument("--assembly-per-result", type=float, default=MASTER_ASSEMBLY_PER_RESULT,
                        help="instructions rank 0 spends per result after the run (the parts into the cube)")
    parser.add_argument("--nonlift-case", type=float, default=NONLIFT_CASE, help="instructions of a non-lifting case")
    parser.add_argument("--worker-own", type=float, default=WORKER_OWN_PER_CASE,
                        help="instructions a worker spends per case beyond it (its messages, its own writing)")
    parser.add_argument("--creation-per-case", type=float, default=WORKER_CREATION_PER_CASE,
                        help="instructions the workers spend together per case of the study creating the cube")
    parser.add_argument("--ns-per-instruction", type=float, default=0.145)
    parser.add_argument("--coordinate-bytes-per-case", type=float, default=0.07,
                        help="bytes a case the coordinates written at the cube's creation take [B] (the case "
                             "number's; pcrf_cube_filters, non-lifting LHS)")
    parser.add_argument("--result-bytes-per-case", type=float, default=88.3,
                        help="bytes a case streamed during the run take [B]: its metrics and status, and its "
                             "sampled parameters (pcrf_cube_filters)")
    parser.add_argument("--assembled-at-end", action="store_true",
                        help="the results' bytes written after the run (the design before the streaming fold)")
    parser.add_argument("--index-evictions-per-result", type=float, default=INDEX_EVICTIONS_PER_RESULT,
                        help="instructions a result rank 0's run gains past ~2 048 chunks a variable, where the "
                             "last fold's close stops growing (index_close_cost.py)")
    parser.add_argument("--write-gb-s", type=float, default=1.0,
                        help="sustained bandwidth of the cube's one writer [GB/s] (an assumption)")
    args = parser.parse_args()
    setup, serial, assembly = args.setup_per_case, args.serial_per_result, args.assembly_per_result
    source = "counts measured for this design (4 ranks, callgrind)"
    if args.measure:
        setup, serial, assembly = measure(os.path.abspath(args.pcrf))
        source = f"rank 0's counts measured now ({args.pcrf}, 4 ranks)"
    ns = args.ns_per_instruction * 1e-9
    t_serial, t_setup, t_assembly = serial * ns, setup * ns, assembly * ns
    t_own, t_create = args.worker_own * ns, args.creation_per_case * ns
    cases = [("non-lifting", args.nonlift_case * ns), ("0.3 ms", 0.3e-3), ("3.6 ms", 3.6e-3)]
    print(f"scaling_model: {source}; rank 0: set-up {setup:,.1f}, run {serial:,.1f}, assembly {assembly:,.1f} "
          f"instructions a case; a worker's own {args.worker_own:,.0f} a case, the cube's creation "
          f"{args.creation_per_case:,.0f} a case of the study; {args.ns_per_instruction} ns an instruction\n")
    table(cases, t_own, t_create, t_serial, t_setup, t_assembly)
    coordinate_s = args.coordinate_bytes_per_case / (args.write_gb_s * 1e9)
    result_s = args.result_bytes_per_case / (args.write_gb_s * 1e9)
    when = "after the run, serially" if args.assembled_at_end else "during the run, streamed"
    print(f"\nWith the cube's bytes written by one writer at {args.write_gb_s} GB/s: the coordinates' "
          f"{args.coordinate_bytes_per_case:.1f} B a case ({coordinate_s * 1e9:.0f} ns) at the creation, serially; "
          f"the results' {args.result_bytes_per_case:.1f} B ({result_s * 1e9:.0f} ns) {when}:\n")
    if args.assembled_at_end:
        table(cases, t_own, t_create, t_serial, t_setup + coordinate_s, t_assembly + result_s)
    else:
        table(cases, t_own, t_create, t_serial + result_s, t_setup + coordinate_s, t_assembly)
    evictions = args.index_evictions_per_result
    print(f"\nA study past ~3.4e7 cases (2 048 chunks a variable): rank 0's run {serial + evictions:,.1f} "
          f"instructions a result (HDF5's chunk index written during the run as its cache evicts it), its last "
          f"fold a fixed 13.5 M (none a result); instructions alone, as the first table:\n")
    table(cases, t_own, t_create, t_serial + evictions * ns, t_setup, 0.0)

if __name__ == "__main__":
    main()
