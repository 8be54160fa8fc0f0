#!/usr/bin/env python3
"""IDA hunt bench (not a test): how many runs each curve needs until it is bracketed, for
several `[ida] step_factor` values (the growth of the hunt's steps), on

  - the far-field set: studies/fema_p695_ida.toml (44 components x 3 frames, 0.5-12 g, 2 %);
  - pulses over 1-100 g at 1 %: one-sine, one-cosine and Ricker pulses at 8 log-spaced periods
    (0.1-2 s), on the basic prestressed frame and on a block of the same slenderness.

Each study runs with max_runs = 40 so that every curve can be bracketed; the table gives the
median and largest number of runs until the bracket closed, and how many curves a budget of
16 runs would leave unbracketed.

    python3 bench/ida_step_factor.py --pcrf build/pcrf [--factors 1 1.5 2 3]
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile

import xarray as xr

# One definition of "bracketed" and of the collapse statuses, shared with the IDA benchmark.
from ida_bench import COLLAPSE, runs_to_bracket  # noqa: E402  (bench/ is the script's folder)

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
HERE = os.path.dirname(os.path.abspath(__file__))
BUDGET = 16

PULSES = """[[records]]
synthetic = [{records}]
{frame}
[intensity]
measure = "pga_g"
[ida]
start = 1.0
max_intensity = 100.0
resolution = 0.01
max_runs = 40
step_factor = {factor}
[outputs]
metrics = ["theta_max_rad"]
"""




def run_study(pcrf, text, folder, name):
    study = os.path.join(folder, name + ".toml")
    with open(study, "w", encoding="utf-8") as f:
        f.write(text)
    cube = os.path.join(folder, name + ".h5")
    done = subprocess.run(["mpirun", "--oversubscribe", "-n", "2", pcrf, "study", study, "-o", cube, "--overwrite",
                           "--progress-interval", "0"], capture_output=True, text=True, env=ENV)
    if done.returncode != 0:
        sys.exit(done.stderr)
    return cube


def measure(cube):
    """Runs to bracket of every curve (None: never within the cube's max_runs)."""
    with xr.open_dataset(cube) as ds:
        resolution = float(ds.attrs["ida_resolution"])
        status = ds.status.values.reshape(-1, ds.sizes["ida_point"])
        intensity = ds.ida_intensity.values.reshape(-1, ds.sizes["ida_point"])
    counts = []
    for st, x in zip(status, intensity):
        keep = st >= 0
        counts.append(runs_to_bracket(list(x[keep]), [int(v) for v in st[keep]], resolution))
    return counts


def far_field_study():
    """studies/fema_p695_ida.toml with its records' paths made absolute (run from elsewhere)."""
    with open(os.path.join(HERE, "..", "studies", "fema_p695_ida.toml"), encoding="utf-8") as f:
        text = f.read()
    return text.replace("../../shared/records", os.path.abspath(os.path.join(HERE, "..", "..", "shared", "records")))


def far_field_text(factor):
    text = re.sub(r"max_runs = \d+", "max_runs = 40", far_field_study())
    return text.replace("[ida]\n", f"[ida]\nstep_factor = {factor}\n")


def pulse_text(factor, frame):
    periods = [0.1 * 20 ** (k / 7) for k in range(8)]
    records = ", ".join(f'"{shape}:period_s={t:.4g},amplitude_g=1"' for shape in ("pulse-sine", "pulse-cosine", "ricker")
                        for t in periods)
    return PULSES.format(records=records, frame=frame, factor=factor)


def row(label, factor, counts):
    done = [n for n in counts if n is not None]
    over = sum(1 for n in counts if n is None or n > BUDGET)
    median = statistics.median(done) if done else float("nan")
    print(f"| {label} | {factor:g} | {len(counts)} | {median:g} | {max(done, default=0)} | {over} |", flush=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--pcrf", required=True)
    parser.add_argument("--factors", type=float, nargs="+", default=[1.0, 1.5, 2.0, 3.0])
    args = parser.parse_args()
    pcrf = os.path.abspath(args.pcrf)
    far_field = os.path.isdir(os.path.join(HERE, "..", "..", "shared", "records", "ngawest2_ff_youtian95"))
    print("| curves | step_factor | curves | runs to bracket: median | max | unbracketed within 16 runs |")
    print("| --- | --- | --- | --- | --- | --- |")
    with tempfile.TemporaryDirectory(prefix="pcrf_step_factor_") as folder:
        for factor in args.factors:
            if far_field:
                row("far field, 0.5-12 g, 2 %", factor, measure(run_study(pcrf, far_field_text(factor), folder, "ff")))
            row("pulses on the basic frame, 1-100 g, 1 %", factor,
                measure(run_study(pcrf, pulse_text(factor, ""), folder, "pcrf")))
            block = '[frame]\nmodel = "block"\nslenderness_rad = 0.19739556\nsize_m = 1.64\n'
            row("pulses on a block (alpha = atan 0.2), 1-100 g, 1 %", factor,
                measure(run_study(pcrf, pulse_text(factor, block), folder, "block")))
    return 0


if __name__ == "__main__":
    sys.exit(main())
