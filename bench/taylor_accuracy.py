#!/usr/bin/env python3
"""Taylor steps against dopri5 (not a test): the rigid rockers under the paper's 13 records.

    python3 bench/taylor_accuracy.py --pcrf build/pcrf [--records DIR]

Housner's block (the bench scenes' α = atan 0.2, p = 2.12 rad/s) and the Makris–Vassiliou
rocking frame (same α and p, beam mass ratio 0.5) under the 13 far-field records of the
paper at 2x and 3x each scene's uplift threshold (PGA), as the speed issue's accuracy check
asks: each case with the `reference` preset (ARKODE ERK5, rtol 1e-10), then with the `fast`
and `balanced` presets' tolerances under `--integrator dopri5` and `--integrator taylor`.
Prints, per integrator and preset, how many cases end in the reference's status and with its
impact count (all presets share the return-to-rest cut-off, [physics] rest_rise_rad), and the
median, 90th-percentile and worst relative θ_max error. Skips cleanly without the records.
"""
import argparse
import json
import statistics
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from scene_cost import SCENES, records_folder, uplift_threshold_g  # noqa: E402

MULTIPLES = (2.0, 3.0)


def run(pcrf, args):
    out = subprocess.run([pcrf, "run", *args], capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"taylor_accuracy: pcrf run {' '.join(args)} failed:\n{out.stderr}")
    return json.loads(out.stdout)


def percentile(values, q):
    values = sorted(values)
    return values[min(len(values) - 1, int(round(q * (len(values) - 1))))]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pcrf", required=True)
    parser.add_argument("--records")
    args = parser.parse_args()
    folder = records_folder(args.records)
    if folder is None or not (folder / "paper").is_dir():
        print("taylor_accuracy: no records folder: nothing to measure", file=sys.stderr)
        return
    records = sorted((folder / "paper").glob("*.AT2"))
    rows = {}
    for scene in ("block", "rocking-frame"):
        thr = uplift_threshold_g(args.pcrf, scene)
        for path in records:
            for m in MULTIPLES:
                base = [*SCENES[scene], "--record", str(path), "--measure", "pga_g", "--intensity", repr(m * thr)]
                ref = run(args.pcrf, [*base, "--preset", "reference"])
                for preset in ("fast", "balanced"):
                    for integ in ("dopri5", "taylor"):
                        r = run(args.pcrf, [*base, "--preset", preset, "--integrator", integ])
                        err = abs(r["theta_max_rad"] - ref["theta_max_rad"]) / max(abs(ref["theta_max_rad"]), 1e-300)
                        rows.setdefault((scene, preset, integ), []).append(
                            (r["status"] == ref["status"], err, r["steps"], r["impacts"] == ref["impacts"]))
    print(f"{len(records)} records x {len(MULTIPLES)} multiples of the uplift threshold, against --preset reference\n")
    print("| scene | preset | integrator | same status | same impacts | median θ_max error | 90th pct | worst | "
          "median steps |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for (scene, preset, integ), v in rows.items():
        errs = [e for _, e, _, _ in v]
        print(f"| {scene} | {preset} | {integ} | {sum(s for s, _, _, _ in v)}/{len(v)} | "
              f"{sum(i for _, _, _, i in v)}/{len(v)} | {statistics.median(errs):.2g} | "
              f"{percentile(errs, 0.9):.2g} | {max(errs):.2g} | {statistics.median(s for _, _, s, _ in v):.0f} |")


if __name__ == "__main__":
    main()
