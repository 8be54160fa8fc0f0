#!/usr/bin/env python3
"""Study bench (not a test): runs a study at 1..N MPI ranks and prints cases/s, the per-case
median wall time and the parallel efficiency.

    python3 bench/study_bench.py --pcrf build/pcrf               # demo, plus the paper's
                                                                 # one-at-a-time study when
                                                                 # ../shared/records exists
    cmake --build build --target study_bench                     # the same through CMake

Time is the study's own (from the closing line of `pcrf study`: first case handed out to
cube closed), so MPI start-up is not counted; the best of --repeat runs is kept. Efficiency
at k ranks is (cases/s at k) / (k x cases/s at 1 rank).
"""
import argparse
import csv
import io
import os
import re
import statistics
import subprocess
import sys
import tempfile

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")


def run_study(pcrf, study, ranks, cube):
    command = ["mpirun", "--oversubscribe", "-n", str(ranks), pcrf, "study", study, "-o", cube,
               "--overwrite", "--progress-interval", "0"]
    result = subprocess.run(command, capture_output=True, text=True, env=ENV)
    if result.returncode != 0:
        sys.exit(f"study_bench: {' '.join(command)} failed:\n{result.stderr}")
    match = re.search(r"(\d+) cases computed.* in ([0-9.]+) s", result.stderr)
    if not match:
        sys.exit(f"study_bench: no summary line in:\n{result.stderr}")
    return int(match.group(1)), float(match.group(2))


def case_median_s(pcrf, cube):
    out = subprocess.run([pcrf, "cube", "export", cube, "-m", "cpu_time_s"], capture_output=True,
                         text=True, check=True).stdout
    times = [float(row["cpu_time_s"]) for row in csv.DictReader(io.StringIO(out)) if row["cpu_time_s"]]
    return statistics.median(times)


def bench(pcrf, study, max_ranks, repeat, workdir):
    print(f"\n{os.path.relpath(study)}  (best of {repeat})")
    print(f"{'ranks':>5} {'cases':>6} {'time [s]':>9} {'cases/s':>9} {'case median [ms]':>17} {'efficiency':>10}")
    base_rate = None
    for ranks in range(1, max_ranks + 1):
        cube = os.path.join(workdir, f"bench_{ranks}.h5")
        best = None
        for _ in range(repeat):
            cases, seconds = run_study(pcrf, study, ranks, cube)
            best = seconds if best is None else min(best, seconds)
        rate = cases / best
        base_rate = base_rate or rate
        median_ms = 1e3 * case_median_s(pcrf, cube)
        print(f"{ranks:>5} {cases:>6} {best:>9.3f} {rate:>9.1f} {median_ms:>17.3f} {rate / (ranks * base_rate):>10.2f}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    here = os.path.dirname(os.path.abspath(__file__))
    parser.add_argument("--pcrf", default=os.path.join(here, "..", "build", "pcrf"), help="the pcrf executable")
    parser.add_argument("--source", default=os.path.join(here, ".."), help="source tree (for studies/)")
    parser.add_argument("--max-ranks", type=int, default=os.cpu_count() or 1, help="ranks to go up to (default: cores)")
    parser.add_argument("--repeat", type=int, default=3, help="runs per rank count; the fastest is kept")
    parser.add_argument("studies", nargs="*", help="study files (default: demo, and the paper's section 7)")
    args = parser.parse_args()
    studies = args.studies or [os.path.join(args.source, "studies", "demo.toml")]
    records = os.path.join(args.source, "..", "shared", "records", "paper")
    if not args.studies and os.path.isdir(records):
        studies.append(os.path.join(args.source, "studies", "paper_section7.toml"))
    print(f"study bench: {os.cpu_count()} cores, 1..{args.max_ranks} ranks")
    with tempfile.TemporaryDirectory() as workdir:
        for study in studies:
            bench(os.path.abspath(args.pcrf), os.path.abspath(study), args.max_ranks, args.repeat, workdir)


if __name__ == "__main__":
    main()
