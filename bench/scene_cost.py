#!/usr/bin/env python3
"""Scene cost bench (not a test): what one case costs on each scene (issue 20: "a block needs
no loop closure and no tendons; its cost per case should be well below the PCRF's").

    python3 bench/scene_cost.py --pcrf build/pcrf [--repeat 7] [--records DIR]
    cmake --build build --target scene_cost                  # the same through CMake

The scenes: the paper's basic prestressed frame (`pcrf`), Housner's block of its slenderness
(alpha = atan 0.2) and frequency parameter (p = 2.12 rad/s), and the Makris-Vassiliou rocking
frame of the same alpha and p-hat with a beam of half the columns' mass (gamma = 0.5). Each
scene feels the same excitations, scaled to the same multiple of its own uplift threshold, so
that each rocks about as hard (the PCRF opens at 1.02 g, the block and frame at 0.2 g):
one-sine, one-cosine and Ricker pulses at T_p = 0.5, 1 and 2 s (a_p = 1.5x the threshold) and,
where ../shared/records exists (PCRF_RECORDS_DIR overrides; skipped cleanly otherwise), four of
the paper's far-field records at a PGA of 1.2x the threshold.

For every case it runs `pcrf run` --repeat times, interleaving the scenes so that a loaded
machine slows them alike, and keeps the median of the solver's own cpu_time_s (process
start-up and reading the record excluded; the per-case set-up counted). The integrator's work
(steps, RHS evaluations) is the same in every repeat. It prints, as markdown, one row per case
and scene, then one summary row per scene: medians over the cases of the time per case, the
steps, the RHS evaluations, the time per step and per RHS evaluation.
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys
from pathlib import Path

ALPHA_RAD = math.atan(0.2)
P_RAD_S = 2.12
SCENES = {
    "pcrf": [],
    "block": ["--model", "block", "--slenderness-rad", repr(ALPHA_RAD), "--frequency-parameter-rad-s", repr(P_RAD_S)],
    "rocking-frame": ["--model", "rocking-frame", "--slenderness-rad", repr(ALPHA_RAD),
                      "--frequency-parameter-rad-s", repr(P_RAD_S), "--beam-mass-ratio", "0.5"],
}
PULSES = [(shape, period_s) for shape in ("pulse-sine", "pulse-cosine", "ricker") for period_s in (0.5, 1.0, 2.0)]
PULSE_OVER_THRESHOLD = 1.5
RECORDS = ["ER1_MUL279", "ER3_BOL090", "ER7_CAP000", "ER10_RIO360"]
RECORD_PGA_OVER_THRESHOLD = 1.2


def pcrf_json(command):
    out = subprocess.run(command, capture_output=True, text=True)
    if out.returncode != 0:  # named after the bench that runs (case_cost.py imports this)
        sys.exit(f"{Path(sys.argv[0]).stem}: {' '.join(command)} failed:\n{out.stderr}")
    return json.loads(out.stdout)


def case_time_s(result):
    """A case's own time from `pcrf run`'s JSON: cpu_time_s (the CPU time of the thread that
    solved it), or wall_time_s from a build older than the rename (its steady clock)."""
    return result["cpu_time_s"] if "cpu_time_s" in result else result["wall_time_s"]


def uplift_threshold_g(pcrf, scene):
    return pcrf_json([pcrf, "frame", "--json", *SCENES[scene]])["uplift_threshold_g"]


def excitations(records_dir):
    """(name, arguments given the scene's uplift threshold [g]) for every excitation."""
    cases = []
    for shape, period_s in PULSES:
        def pulse(threshold_g, shape=shape, period_s=period_s):
            amplitude_g = PULSE_OVER_THRESHOLD * threshold_g
            return ["--synthetic", f"{shape}:period_s={period_s},amplitude_g={amplitude_g!r}"]
        cases.append((f"{shape} T_p = {period_s} s", pulse))
    if records_dir is None:
        print(f"scene_cost: no records folder: the far-field records are skipped", file=sys.stderr)
        return cases
    for stem in RECORDS:
        path = records_dir / "paper" / f"{stem}.AT2"
        if not path.exists():
            print(f"scene_cost: {path} absent: skipped", file=sys.stderr)
            continue
        def record(threshold_g, path=path):
            return ["--record", str(path), "--measure", "pga_g", "--intensity", repr(RECORD_PGA_OVER_THRESHOLD * threshold_g)]
        cases.append((stem, record))
    return cases


def records_folder(given):
    folder = Path(given or os.environ.get("PCRF_RECORDS_DIR") or Path(__file__).resolve().parents[1].parent / "shared" / "records")
    return folder if folder.is_dir() else None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pcrf", required=True)
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--records", help="records folder (default: ../shared/records or PCRF_RECORDS_DIR)")
    args = parser.parse_args()
    thresholds = {scene: uplift_threshold_g(args.pcrf, scene) for scene in SCENES}
    print(f"Scene cost per case, medians of {args.repeat} runs of `pcrf run` (cpu_time_s), this machine\n")
    print("| case | scene | status | impacts | steps | RHS evals | time per case [ms] | per step [µs] | per RHS eval [µs] |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    summary = {scene: [] for scene in SCENES}
    for name, arguments in excitations(records_folder(args.records)):
        times = {scene: [] for scene in SCENES}
        last = {}
        for _ in range(args.repeat):
            for scene in SCENES:
                result = pcrf_json([args.pcrf, "run", *SCENES[scene], *arguments(thresholds[scene])])
                times[scene].append(case_time_s(result))
                last[scene] = result
        for scene in SCENES:
            r, t = last[scene], statistics.median(times[scene])
            steps, rhs = max(r["steps"], 1), max(r["rhs_evals"], 1)
            summary[scene].append((t, r["steps"], r["rhs_evals"], t / steps, t / rhs))
            print(f"| {name} | {scene} | {r['status']} | {r['impacts']} | {r['steps']} | {r['rhs_evals']} | "
                  f"{1e3 * t:.3f} | {1e6 * t / steps:.2f} | {1e6 * t / rhs:.3f} |")
    print(f"\nMedians over the {len(next(iter(summary.values())))} cases\n")
    print("| scene | time per case [ms] | steps | RHS evals | per step [µs] | per RHS eval [µs] |")
    print("| --- | --- | --- | --- | --- | --- |")
    for scene, rows in summary.items():
        med = [statistics.median(column) for column in zip(*rows)]
        print(f"| {scene} | {1e3 * med[0]:.3f} | {med[1]:.0f} | {med[2]:.0f} | {1e6 * med[3]:.2f} | {1e6 * med[4]:.3f} |")


if __name__ == "__main__":
    main()
