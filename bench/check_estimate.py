#!/usr/bin/env python3
"""Check-estimate bench (not a test): how close `pcrf study --check`'s cost estimate comes to
what the study then costs (issue 41 item 7).

    python3 bench/check_estimate.py --pcrf build/pcrf [--checks 3] [--records DIR] [--busy 1]

Three studies of the paper's records (../shared/records/paper; PCRF_RECORDS_DIR overrides):
- an IDA of 20 frames (5 kappa x 4 tan alpha) under ER1-ER10 (200 curves, [ida] start 0.5,
  step 0.5, at most 12 runs each) -- the kind of study whose estimate used to be timed at
  [ida] start, where nothing rocks;
- an LHS of 2000 frames under three records at PGA 2 g (6000 cases);
- a grid: ER1-ER10 at 20 scales from 0.5 to 5 and 4 kappa (800 cases).
Each study's --check runs --checks times (its estimate and stated range each time), then the
study once on one rank: the process's CPU (user + system), and the cases' CPU, that less the
median of three runs of a baseline (the same records at scale 0.01, where no frame lifts:
start-up, reading the records, a cube), which is what the estimate covers. The table gives the
estimates' median over the cases' CPU, their spread between checks, and whether the cases' CPU
lies in the stated range.
With --busy N, N processes spin on the CPU meanwhile (the estimate is in CPU time: a loaded
machine should not move it much).
"""
import argparse
import multiprocessing
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
UNITS = {"seconds": 1.0, "minutes": 60.0, "hours": 3600.0}
AMOUNT = r"([0-9.e+-]+) (?:CPU|core)-(seconds|minutes|hours)"  # core-: a build before CPU time


def records_block(paper, names):
    return "".join(f'[[records]]\nname = "{n}"\nfile = "{next(paper.glob(n + "_*.AT2"))}"\n' for n in names)


def studies(paper):
    ten = [f"ER{i}" for i in range(1, 11)]
    outputs = '[outputs]\nmetrics = ["theta_max_rad", "impacts"]\n'
    return {
        "IDA, 200 curves": '[study]\nname = "ida"\n[axes]\nkappa = {from = 1.2, to = 2.4, count = 5}\n'
                           'tan_alpha = {from = 0.16, to = 0.24, count = 4}\n[intensity]\nmeasure = "pga_g"\n'
                           '[ida]\nstart = 0.5\nstep = 0.5\nmax_intensity = 10\nmax_runs = 12\n' + outputs +
                           records_block(paper, ten),
        "LHS, 6000 cases": '[study]\nname = "lhs"\n[plan]\nkind = "lhs"\nsamples = 2000\nseed = 7\n[axes]\n'
                           'tan_alpha = {from = 0.15, to = 0.25}\npi_sigma_c = {from = 2.0, to = 10.0}\n'
                           'kappa = {from = 1.0, to = 2.5}\nintensity = [2.0]\n[intensity]\nmeasure = "pga_g"\n' +
                           outputs + records_block(paper, ["ER1", "ER3", "ER7"]),
        "grid, 800 cases": '[study]\nname = "grid"\n[axes]\nscale = {from = 0.5, to = 5.0, count = 20}\n'
                           'kappa = {from = 1.2, to = 2.4, count = 4}\n' + outputs + records_block(paper, ten),
    }


def baseline(text):
    """The same records at one scale that lifts no frame: start-up, reading the records, a cube."""
    records = text[text.index("[[records]]"):]
    return '[study]\nname = "baseline"\n[axes]\nscale = [0.01]\n[outputs]\nmetrics = ["theta_max_rad"]\n' + records


def check(pcrf, study):
    """(estimate, low, high) [CPU-seconds] from --check's line (low, high NaN when not stated)."""
    out = subprocess.run([pcrf, "study", str(study), "--check"], capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"check_estimate: --check failed on {study}:\n{out.stderr}")
    line = next(l for l in (out.stdout + out.stderr).splitlines() if "cost estimate" in l)
    amounts = [float(x) * UNITS[u] for x, u in re.findall(AMOUNT, line)]
    if "upper bound" in line:
        print(f"note: the line calls itself an upper bound: {line}")
    return amounts[0], (amounts[1] if len(amounts) >= 3 else float("nan")), \
        (amounts[2] if len(amounts) >= 3 else float("nan")), line


def study_cpu_s(pcrf, study, cube):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    out = subprocess.run([pcrf, "study", str(study), "-o", str(cube), "--overwrite", "--progress-interval", "0"],
                         capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if out.returncode != 0:
        sys.exit(f"check_estimate: the study {study} failed:\n{out.stderr}")
    return after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime


def spin():
    while True:
        pass


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pcrf", required=True)
    ap.add_argument("--checks", type=int, default=3)
    ap.add_argument("--busy", type=int, default=0, help="processes that load the CPU meanwhile")
    ap.add_argument("--records", default=os.environ.get("PCRF_RECORDS_DIR", str(ROOT.parent / "shared" / "records")))
    a = ap.parse_args()
    paper = Path(a.records) / "paper"
    if not paper.is_dir():
        print(f"check_estimate: no records at {paper} (set PCRF_RECORDS_DIR): nothing measured")
        return 0
    spinners = [multiprocessing.Process(target=spin, daemon=True) for _ in range(a.busy)]
    for p in spinners:
        p.start()
    print(f"pcrf: {a.pcrf}; {a.checks} checks per study; {a.busy} busy processes beside")
    print("\n| study | estimates [CPU-s] | max/min between checks | stated range (last) [CPU-s] | process [CPU-s] | "
          "cases [CPU-s] | median estimate / cases | cases in range |")
    print("|---|---|---|---|---|---|---|---|")
    lines = []
    try:
        with tempfile.TemporaryDirectory() as tmp:
            for name, text in studies(paper).items():
                study = Path(tmp) / f"{name.split(',')[0].lower()}.toml"
                study.write_text(text)
                base = Path(tmp) / "baseline.toml"
                base.write_text(baseline(text))
                results = [check(a.pcrf, study) for _ in range(a.checks)]
                estimates = [r[0] for r in results]
                low, high, line = results[-1][1], results[-1][2], results[-1][3]
                process = study_cpu_s(a.pcrf, study, Path(tmp) / "cube.h5")
                cases = process - statistics.median(study_cpu_s(a.pcrf, base, Path(tmp) / "b.h5") for _ in range(3))
                inside = "yes" if low <= cases <= high else ("no range" if low != low else "no")
                print(f"| {name} | {', '.join(f'{e:.3g}' for e in estimates)} | {max(estimates) / min(estimates):.2f} | "
                      f"{low:.3g} to {high:.3g} | {process:.3g} | {cases:.3g} | "
                      f"{statistics.median(estimates) / cases:.2f} | {inside} |")
                lines.append(f"{name}: {line}")
    finally:
        for p in spinners:
            p.terminate()
    print("\nThe last check's line per study:")
    for line in lines:
        print(f"  {line}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
