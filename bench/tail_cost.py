#!/usr/bin/env python3
"""What the free vibration after the record costs (a benchmark, not a test): the far-field
P-695 IDA (studies/fema_p695_ida.toml) run with the default tail (`tail_s = "until-rest"`: every
run ends at rest or collapsed) and with `tail_s = 0` (the run stops with the record; a frame
still rocking is unresolved), interleaved, --repeats times each.

    python3 bench/tail_cost.py --pcrf build/pcrf [--ranks 2] [--repeats 3]

Prints, per tail: runs, unresolved runs, the study's computing time (its closing line; median
of the repeats), the sum of the runs' cpu_time_s (median), and the geometric mean of each frame's collapse
Sa. Needs ../shared/records; prints a note and exits 0 without them.
"""
import argparse
import os
import statistics
import sys
import tempfile

import numpy as np
import xarray as xr

from ida_step_factor import far_field_study  # noqa: E402  (bench/ is the script's folder)
from study_bench import run_study  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
TAILS = {"until-rest (default)": "", "0 s": "[physics]\ntail_s = 0\n\n"}


def run(pcrf, ranks, physics, folder):
    """The study with `physics` before its [intensity] table: its computing time and what its cube holds."""
    study, cube = os.path.join(folder, "study.toml"), os.path.join(folder, "ida.h5")
    with open(study, "w", encoding="utf-8") as f:
        f.write(far_field_study().replace("[intensity]", physics + "[intensity]", 1))
    _, seconds = run_study(pcrf, study, ranks, cube)
    with xr.open_dataset(cube) as ds:
        status = ds.status.values
        code = dict(zip(ds.status.attrs["flag_meanings"].split(), ds.status.attrs["flag_values"].tolist()))
        medians = [float(np.exp(np.mean(np.log(ds.collapse_intensity.isel(case=c).values))))
                   for c in range(ds.sizes["case"])]
        return dict(seconds=seconds, wall=float(np.nansum(ds.cpu_time_s.values)), runs=int((status >= 0).sum()),
                    unresolved=int((status == code["rocking_at_end"]).sum()), medians=medians,
                    labels=[str(v) for v in ds.case_label.values])


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
                results[tail].append(run(args.pcrf, args.ranks, physics, folder))
    labels = results[next(iter(TAILS))][0]["labels"]
    print(f"\nfar-field P-695 IDA, {args.ranks} ranks, medians of {args.repeats} interleaved runs")
    print("| tail | runs | unresolved | computing [s] | sum of cpu_time_s [s] | " +
          " | ".join(f"collapse Sa, {label}: geometric mean [g]" for label in labels) + " |")
    print("| --- " * (5 + len(labels)) + "|")
    for tail, rows in results.items():
        first = rows[0]
        print(f"| {tail} | {first['runs']} | {first['unresolved']} | {statistics.median(r['seconds'] for r in rows):.2f} | "
              f"{statistics.median(r['wall'] for r in rows):.2f} | " + " | ".join(f"{m:.3f}" for m in first["medians"]) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
