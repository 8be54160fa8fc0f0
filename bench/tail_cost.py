#!/usr/bin/env python3
"""What the free vibration after the record costs (a benchmark, not a test): the far-field
P-695 IDA (studies/fema_p695_ida.toml) run with the default tail (`tail_s = "until-rest"`: every
run ends at rest or collapsed) and with `tail_s = 0` (the run stops with the record; a frame
still rocking is unresolved), interleaved, --repeats times each.

    python3 bench/tail_cost.py --pcrf build/pcrf [--ranks 2] [--repeats 3]

Prints, per tail: runs, unresolved runs, the study's computing time (its closing line; median
of the repeats), the sum of the runs' wall_time_s (median), and the geometric mean of each frame's collapse
Sa. Needs ../shared/records; prints a note and exits 0 without them.
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile

import numpy as np
import xarray as xr

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
HERE = os.path.dirname(os.path.abspath(__file__))
STUDY = os.path.join(HERE, "..", "studies", "fema_p695_ida.toml")
TAILS = {"until-rest (default)": "", "0 s": "[physics]\ntail_s = 0\n\n"}


def study_text(physics):
    """The study with its records' paths made absolute (it is run from a temporary folder)."""
    text = open(STUDY).read().replace('"../../shared/', '"' + os.path.abspath(os.path.join(HERE, "..", "..", "shared")) + "/")
    return text.replace("[intensity]", physics + "[intensity]", 1)


def run(pcrf, ranks, text, folder):
    study, cube = os.path.join(folder, "study.toml"), os.path.join(folder, "ida.h5")
    with open(study, "w") as f:
        f.write(text)
    result = subprocess.run(["mpirun", "--oversubscribe", "-n", str(ranks), pcrf, "study", study, "-o", cube,
                             "--overwrite", "--progress-interval", "0"], capture_output=True, text=True, env=ENV)
    if result.returncode != 0:
        sys.exit(result.stderr)
    seconds = float(re.search(r"in ([0-9.]+) s;", result.stderr).group(1))
    with xr.open_dataset(cube) as ds:
        status = ds.status.values
        code = dict(zip(ds.status.attrs["flag_meanings"].split(), ds.status.attrs["flag_values"].tolist()))
        medians = [float(np.exp(np.mean(np.log(ds.collapse_intensity.isel(case=c).values))))
                   for c in range(ds.sizes["case"])]
        return dict(seconds=seconds, wall=float(np.nansum(ds.wall_time_s.values)), runs=int((status >= 0).sum()),
                    unresolved=int((status == code["rocking_at_end"]).sum()), medians=medians, labels=[str(v) for v in ds.case_label.values])


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--pcrf", required=True)
    parser.add_argument("--ranks", type=int, default=2)
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    if not os.path.isdir(os.path.join(HERE, "..", "..", "shared", "records", "ngawest2_ff_youtian95")):
        print("note: ../shared/records not found: nothing to measure")
        return 0
    results = {tail: [] for tail in TAILS}
    with tempfile.TemporaryDirectory() as folder:
        for _ in range(args.repeats):
            for tail, physics in TAILS.items():
                results[tail].append(run(args.pcrf, args.ranks, study_text(physics), folder))
    labels = results[next(iter(TAILS))][0]["labels"]
    print(f"\nfar-field P-695 IDA, {args.ranks} ranks, medians of {args.repeats} interleaved runs")
    print("| tail | runs | unresolved | computing [s] | sum of wall_time_s [s] | " +
          " | ".join(f"collapse Sa, {label}: geometric mean [g]" for label in labels) + " |")
    print("| --- " * (5 + len(labels)) + "|")
    for tail, rows in results.items():
        first = rows[0]
        print(f"| {tail} | {first['runs']} | {first['unresolved']} | {statistics.median(r['seconds'] for r in rows):.2f} | "
              f"{statistics.median(r['wall'] for r in rows):.2f} | " + " | ".join(f"{m:.3f}" for m in first["medians"]) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
