#!/usr/bin/env python3
"""IDA bench (not a test): how many runs the adaptive IDA needs to bracket each record's
collapse intensity, against a dense grid at the same resolution, and whether each bracket's
ends really are a collapse and a safe run when rerun alone with `pcrf run` (scaled by the
factor the study applied to that run, whatever the measure and normalisation).

    python3 bench/ida_bench.py --pcrf build/pcrf                  # studies/fema_p695_ida.toml
    python3 bench/ida_bench.py --pcrf build/pcrf --cube ida.h5    # an IDA cube already made

Needs ../shared/records (the study's records); prints a note and exits 0 without them.
"""
import argparse
import math
import os
import statistics
import subprocess
import sys
import tempfile

import numpy as np
import xarray as xr

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
COLLAPSE = {2, 3, 4, 5}  # tendon_fracture, overturned, and failures, as the IDA counts them


def runs_to_bracket(intensity, status, resolution):
    """Runs of a curve, in order, until collapse / last safe - 1 <= resolution (None: never)."""
    for n in range(1, len(intensity) + 1):
        x, s = intensity[:n], status[:n]
        collapses = [v for v, st in zip(x, s) if st in COLLAPSE]
        if not collapses:
            continue
        c = min(collapses)
        safe = [v for v, st in zip(x, s) if st not in COLLAPSE and v < c]
        if safe and c / max(safe) - 1.0 <= resolution:
            return n
    return None


def status_of(pcrf, source, frame_flags, scale_factor):
    """The status of `pcrf run` on the record scaled by the factor the study applied (any
    intensity measure and normalisation: the cube stores each run's own factor)."""
    command = [pcrf, "run", "--record", source.removeprefix("file "), "--scale", repr(float(scale_factor))] + frame_flags
    out = subprocess.run(command, capture_output=True, text=True, env=ENV).stdout
    at = out.find('"status": "')
    return out[at + 11:out.find('"', at + 11)]


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--pcrf", required=True)
    parser.add_argument("--study", default=os.path.join(here, "..", "studies", "fema_p695_ida.toml"))
    parser.add_argument("--cube", help="an IDA cube already computed (skips the run)")
    parser.add_argument("--ranks", type=int, default=2)
    parser.add_argument("--no-rerun", action="store_true", help="do not rerun the bracket ends with pcrf run")
    args = parser.parse_args()
    records = os.path.join(here, "..", "..", "shared", "records", "ngawest2_ff_youtian95")
    if not args.cube and not os.path.isdir(records):
        print(f"note: {records} not found: nothing to measure")
        return 0
    cube = args.cube
    if not cube:
        cube = os.path.join(tempfile.mkdtemp(), "ida.h5")
        result = subprocess.run(["mpirun", "--oversubscribe", "-n", str(args.ranks), args.pcrf, "study", args.study, "-o",
                                 cube, "--progress-interval", "0"], capture_output=True, text=True, env=ENV)
        if result.returncode != 0:
            sys.exit(result.stderr)
        print(result.stderr.strip().splitlines()[-1])
    ds = xr.open_dataset(cube)
    resolution = float(ds.attrs["ida_resolution"])
    start, cap = float(ds.attrs["ida_start"]), float(ds.attrs["ida_max_intensity"])
    grid_runs = math.floor(math.log(cap / start) / math.log(1.0 + resolution)) + 1
    frame_dim = [d for d in ds.status.dims if d not in ("record", "ida_point")]
    frames = ds[frame_dim[0]].values if frame_dim else [None]
    print(f"\nadaptive IDA: {ds.sizes['record']} records, start {start:g}, cap {cap:g} "
          f"{ds.collapse_intensity.attrs.get('units', '')}, resolution {resolution:g}, "
          f"max_runs {ds.sizes['ida_point']}; a dense grid at the same resolution needs {grid_runs} runs per record\n")
    print(f"{'frame':<14} {'curves':>6} {'bracketed':>9} {'runs to bracket: median':>24} {'max':>4} "
          f"{'runs used: median':>18} {'widest bracket':>15} {'ends rerun agree':>17}")
    for f in range(len(frames)):
        sel = {frame_dim[0]: f} if frame_dim else {}
        label = str(ds.case_label.values[f]) if "case_label" in ds else "all"
        to_bracket, used, widest, agree, checked = [], [], 0.0, 0, 0
        for r in range(ds.sizes["record"]):
            curve = ds.isel(record=r, **sel)
            status = [int(v) for v in curve.status.values if v >= 0]
            intensity = [float(v) for v, st in zip(curve.ida_intensity.values, curve.status.values) if st >= 0]
            n = runs_to_bracket(intensity, status, resolution)
            c, s = float(curve.collapse_intensity), float(curve.last_safe_intensity)
            used.append(len(status))
            if n is not None:
                to_bracket.append(n)
                widest = max(widest, c / s - 1.0)
            if not args.no_rerun and np.isfinite(c):
                source = str(ds.record_source.values[r])
                flags = []
                if "case_label" in ds:
                    for p in ("kappa", "lambda", "tan_alpha", "lambda_h", "pi_sigma_b", "pi_sigma_c", "pi_e_b", "pi_e_c"):
                        flags += ["--" + p.replace("_", "-"), repr(float(ds[p].values[f]))]
                factor = dict(zip(curve.ida_intensity.values.tolist(), curve.scale_factor.values.tolist()))
                at_c = status_of(args.pcrf, source, flags, factor[c])
                at_s = status_of(args.pcrf, source, flags, factor[s])
                checked += 1
                agree += at_c in ("tendon_fracture", "overturned") and at_s in ("at_rest", "rocking_at_end")
        median = statistics.median(to_bracket) if to_bracket else float("nan")
        print(f"{label:<14} {len(used):>6} {len(to_bracket):>9} {median:>24g} {max(to_bracket, default=0):>4} "
              f"{statistics.median(used):>18g} {widest:>15.4f} {f'{agree}/{checked}':>17}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
