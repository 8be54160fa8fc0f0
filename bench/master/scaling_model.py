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
"""
import argparse
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
WORKERS = [16, 64, 256, 2048, 16384]

# Measured with callgrind on a non-lifting LHS of 8 parameters, 17 metrics, at 4 ranks, on main after the
# coordinates written during the run (each unit's worker seals its chunk of every sampled parameter, rank 0
# copies it raw with the unit) and libdeflate's Adler-32, the workers' two figures after each unit's parameters
# were computed once, by columns, rank 0's three after its serial work was taken down (the case number in chunks
# of up to 2^20 values, the last fold reading nothing again per unit) (rank_costs.py --ranks 4 --small 294912 1179648, one
# checkpoint at the end: marginal instructions between the two sizes, so that start-up cancels; rank 0's own
# work with its waits left out, and the working threads' split, both printed by rank_costs.py; studies/README.md
# "The master at cluster scale"):
MASTER_SETUP_PER_CASE = 0.1       # rank 0's main thread before the first hand-out, its wait for the workers'
                                  # pieces left out: the plan, the checks, the case number's chunks, now of up to
                                  # 2^20 values (cube::kCreationCoordinateChunk), a raw chunk write each (0.4-0.58
                                  # in chunks of 16 384, 0.48 of it those writes; 0.7 when it also wrote every
                                  # sampled parameter's chunks; 11 600 at da9ce77)
MASTER_RUN_PER_RESULT = 7.0       # rank 0's main thread during the run, its polling between messages left out:
                                  # what comes back (Master::handle), nearly all of it the parts' chunks streamed
                                  # into the next fold (CubeWriter::stream_kept: HDF5's raw chunk write with
                                  # fixed-array chunk indices, 18 variables and 8 coordinate chunks a unit; 8.1
                                  # with a tree of the coordinate chunks written and an error text built for each,
                                  # 4.9 without the coordinates)
MASTER_ASSEMBLY_PER_RESULT = 0.4  # rank 0's main thread in the last fold, after the run: HDF5 serializing each
                                  # variable's chunk index (a fixed array, 26 variables, ~240 instructions an entry)
                                  # as the fold's file closes, 0.38 a result, what remains. rank_costs.py prints
                                  # -0.2 to 0.3 here: the last chunk, stored case by case and deflated as the
                                  # variables close (120 M instructions at either size), varies with its data by
                                  # +-0.5 a result, so it is left out by its own count (H5Dclose under update).
                                  # Before: 0.4 to 0.7 (each part read again from its start, 2.2 k instructions a
                                  # unit; a part's name built and compared a chunk, 1.9 k; HDF5's storage summed
                                  # per coordinate, 4.5 k), 11 before the streaming fold, 25 at 291f9a0
NONLIFT_CASE = 13_750             # a worker's non-lifting case (CaseRunner::run), its LHS point included: each unit's
                                  # parameters computed once, by the design's columns, in its cases' set-up
                                  # (ColumnWindow, 1 410) and read from there by the sealing; its row from the
                                  # worker's pool (parallel::pooled_row). 15 190 at f1ca852, when each case computed
                                  # its point by the design's row (2 490); 16 100 at e2c9aee
WORKER_OWN_PER_CASE = 2_455       # sealing its chunk and its chunk of each coordinate 2 307 (deflating the metrics'
                                  # and the coordinates' streams 2 090, the coordinates' values read from the unit's
                                  # window 65, gathering the rows and one copy of the streams into the unit's bytes
                                  # about 150), its part (written from those bytes as they lie, libdeflate's CRC-32),
                                  # its batch of rows and messages 148. 4 910 at f1ca852 (sealing 4 050 with the
                                  # coordinates' values computed again from the plan, 1 450; the rest 860)
WORKER_CREATION_PER_CASE = 67     # the case number's pieces sealed by the workers at the creation, per case of
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

if __name__ == "__main__":
    main()
