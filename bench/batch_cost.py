#!/usr/bin/env python3
"""Batch cost bench (not a test): cases per second per core of a Latin-hypercube design,
one case at a time against lockstep lanes at W = 1, 2, 4, 8 (docs/batches.md).

    python3 bench/batch_cost.py --bench build/bench/batch/pcrf_batch_bench
        [--cases 10000] [--callgrind-cases 100] [--repeat 3] [--records DIR]
        [--pcrf build/pcrf --study-frames 1000 --ranks 2] [--variants W=1,W=8] [--scenes block]

Design: the block (alpha, R) and the prestressed frame (tan alpha, Pi_sigma_c, kappa), under
three of the paper's far-field records (ER1, ER3, ER7, from ../shared/records or
PCRF_RECORDS_DIR; without them the bench says so and stops), each scaled to twice the
design's median uplift threshold, the balanced preset.

Two measures, as a shared and loaded machine requires:
- instructions: valgrind's callgrind, whole process (the design's set-up and reading the
  records included, the same in every row; valgrind runs no AVX-512: its W = 8 row is two
  AVX2 registers);
- time: the one-case run and the batch run in turn (A B A B ...), --repeat pairs, the median
  of the pair ratios of the process's CPU time, and cases/s per CPU second of the batch run
  (median).
With --pcrf, also a whole study through the scheduler: `pcrf study` on --ranks MPI ranks of
an LHS of the prestressed frame (--study-frames frames) under the three records at PGA 2 g,
[run] lanes = 1 against 8 in turn, CPU time of all ranks (getrusage of the children).
Also the batch's own statistics: lane occupancy (share of lane attempts that belonged to a
case), accepted and rejected steps, root searches and events (the scalar work of a lane).
"""
import argparse
import json
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

RECORDS = ["ER1_MUL279", "ER3_BOL090", "ER7_CAP000"]
# The default sin/cos is the one-case solver's (exact); "scalar" the same lane by lane (what
# its vectorisation gains); "sleef" SLEEF's fastest (not bit for bit).
# The lanes step dopri5 (every row passes --integrator dopri5); the one-case baseline is the
# balanced preset's own path: Taylor steps for the block, dopri5 for the prestressed frame.
# "one case dopri5" is the one-case path the lanes reproduce bit for bit.
VARIANTS = [("one case dopri5", ["--one-case"]), ("W=1", ["--lanes", "1"]), ("W=2", ["--lanes", "2"]), ("W=4", ["--lanes", "4"]),
            ("W=8", ["--lanes", "8"]), ("W=8 scalar trig", ["--lanes", "8", "--trig", "scalar"]),
            ("W=8 sleef", ["--lanes", "8", "--trig", "sleef"])]


def records_folder(given):
    for candidate in [given, os.environ.get("PCRF_RECORDS_DIR"),
                      Path(__file__).resolve().parents[2] / "shared" / "records"]:
        if candidate and (Path(candidate) / "paper").is_dir():
            return Path(candidate) / "paper"
    return None


def run(bench, args):
    out = subprocess.run([str(bench)] + args, capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def instructions(bench, args):
    if shutil.which("valgrind") is None:
        return None
    with tempfile.TemporaryDirectory() as tmp:
        out = subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={tmp}/cg"] + [str(bench)] + args,
                             capture_output=True, text=True, check=True)
    for line in out.stderr.splitlines():
        if "Collected :" in line:
            return int(line.split(":")[-1])
    return None


STUDY = """[study]
name = "lanes"
[plan]
kind = "lhs"
samples = {frames}
seed = 7
[axes]
tan_alpha = {{from = 0.15, to = 0.25}}
pi_sigma_c = {{from = 2.0, to = 10.0}}
kappa = {{from = 1.0, to = 2.5}}
intensity = [2.0]
[intensity]
measure = "pga_g"
{records}
[outputs]
metrics = ["theta_max_rad", "impacts"]
"""


def study_seconds(pcrf, toml, lanes, ranks, out):
    """(CPU seconds of every rank, wall seconds) of one `pcrf study` run."""
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.monotonic()
    subprocess.run(["mpirun", "--oversubscribe", "-n", str(ranks), str(pcrf), "study", str(toml), "-o", str(out),
                    "--lanes", str(lanes), "--progress-interval", "0", "--overwrite"],
                   capture_output=True, text=True, check=True, env=env)
    wall = time.monotonic() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime, wall


def study_table(a, files):
    if shutil.which("mpirun") is None:
        print("\nstudy: mpirun not found; not measured")
        return
    records = "\n".join(f'[[records]]\nfile = "{f}"' for f in files)
    with tempfile.TemporaryDirectory() as tmp:
        toml = Path(tmp) / "lanes.toml"
        toml.write_text(STUDY.format(frames=a.study_frames, records=records))
        rows = {1: [], 8: []}
        for _ in range(a.repeat):
            for lanes in (1, 8):
                rows[lanes].append(study_seconds(a.pcrf, toml, lanes, a.ranks, Path(tmp) / f"lanes{lanes}.h5"))
    cases = a.study_frames * len(files)
    print(f"\nstudy: pcrf study, {a.ranks} ranks, LHS of {a.study_frames} prestressed frames x {len(files)} records"
          f" at PGA 2 g ({cases} cases), {a.repeat} runs each in turn")
    print("| lanes | CPU s (all ranks) | wall s | cases/s per core | CPU vs lanes = 1 |")
    print("|---|---|---|---|---|")
    base = statistics.median(c for c, _ in rows[1])
    for lanes in (1, 8):
        cpu = statistics.median(c for c, _ in rows[lanes])
        wall = statistics.median(w for _, w in rows[lanes])
        print(f"| {lanes} | {cpu:.2f} | {wall:.2f} | {cases / cpu:.0f} | {base / cpu:.2f}x |")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bench", required=True, help="pcrf_batch_bench")
    parser.add_argument("--cases", type=int, default=10000, help="frames of the design (timed runs)")
    parser.add_argument("--callgrind-cases", type=int, default=100, help="frames of the design under callgrind")
    parser.add_argument("--repeat", type=int, default=3, help="A B pairs of timed runs")
    parser.add_argument("--records", help="records folder (default: ../shared/records or PCRF_RECORDS_DIR)")
    parser.add_argument("--pcrf", help="pcrf executable: also time a study through the scheduler")
    parser.add_argument("--study-frames", type=int, default=1000, help="frames of the study's LHS")
    parser.add_argument("--ranks", type=int, default=2, help="MPI ranks of the study")
    parser.add_argument("--scenes", default="block,frame", help="scenes of the batch tables (comma-separated)")
    parser.add_argument("--variants", default=",".join(name for name, _ in VARIANTS),
                        help="rows of the batch tables (comma-separated names)")
    a = parser.parse_args()
    folder = records_folder(a.records)
    if folder is None:
        print("batch_cost: the PEER records (../shared/records/paper) are not here; nothing measured")
        return 0
    files = [str(folder / f"{r}.AT2") for r in RECORDS]
    for scene in [x for x in a.scenes.split(",") if x]:
        base = ["--scene", scene] + files
        one = ["--one-case"]
        i_one = instructions(a.bench, base + one + ["--cases", str(a.callgrind_cases)])
        print(f"\n{scene}: {a.cases} frames x {len(files)} records (timed), {a.callgrind_cases} x {len(files)} (callgrind)")
        print("| variant | kernels | instr. vs one-case | time vs one-case | cases/s | occupancy | rejected/accepted |"
              " root searches/step | events/case |")
        print("|---|---|---|---|---|---|---|---|---|")
        for name, args in [v for v in VARIANTS if v[0] in a.variants.split(",")]:
            args = args + ["--integrator", "dopri5"]
            i_batch = instructions(a.bench, base + args + ["--cases", str(a.callgrind_cases)])
            ratios, rates, stats = [], [], None
            for _ in range(a.repeat):
                t_one = run(a.bench, base + one + ["--cases", str(a.cases)])
                stats = run(a.bench, base + args + ["--cases", str(a.cases)])
                ratios.append(t_one["seconds"] / stats["seconds"])
                rates.append(stats["cases_per_s"])
            instr = f"{i_one / i_batch:.2f}x" if i_one and i_batch else "n/a"
            steps = max(stats.get("accepted", 0), 1)
            kernels = f"{stats['kernels']}/{stats['trig']}" if "kernels" in stats else "-"
            occupancy = f"{stats['occupancy']:.3f}" if "occupancy" in stats else "-"
            print(f"| {name} | {kernels} | {instr} | {statistics.median(ratios):.2f}x |"
                  f" {statistics.median(rates):.0f} | {occupancy} | {stats.get('rejected', 0) / steps:.4f} |"
                  f" {stats.get('root_searches', 0) / steps:.3f} | {stats.get('events', 0) / max(stats['cases'], 1):.0f} |")
    if a.pcrf:
        study_table(a, files)
    return 0


if __name__ == "__main__":
    sys.exit(main())
