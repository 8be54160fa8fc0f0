#!/usr/bin/env python3
"""What a change of the rigid rockers' sin/cos does to the one-case answers (not a test):
two pcrf builds, the same cases, the metrics side by side.

    python3 bench/trig_change.py --pcrf build/pcrf --old OLD/pcrf [--records DIR]

Cases: the block and the Makris-Vassiliou rocking frame of the scene-cost bench (alpha = atan
0.2, p = 2.12 rad/s; the frame with gamma = 0.5) under every record of ../shared/records/paper
(PCRF_RECORDS_DIR overrides; without them the bench says so and stops), each scaled to a PGA of
1.2x and 2x the scene's uplift threshold: `pcrf run`, the balanced preset. Prints one row per
scene and level: the largest relative change of theta_max, omega_max and t_theta_max over the
records, and how many statuses and impact counts differ (a last-bit change of sin/cos moves an
answer by about the integration error where it flips a step's acceptance; it must not move a
verdict).
"""
import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from scene_cost import SCENES, pcrf_json, records_folder, uplift_threshold_g  # noqa: E402

LEVELS = [1.2, 2.0]


def relative(a, b):
    if a is None or b is None:
        return 0.0 if a == b else float("inf")
    return abs(a - b) / max(abs(b), 1e-300)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pcrf", required=True, help="the pcrf with the new sin/cos")
    ap.add_argument("--old", required=True, help="the pcrf to compare with")
    ap.add_argument("--records")
    a = ap.parse_args()
    folder = records_folder(a.records)
    paper = folder / "paper" if folder else None
    if paper is None or not paper.is_dir():
        print("trig_change: no records (../shared/records/paper or PCRF_RECORDS_DIR): nothing compared")
        return 0
    records = sorted(paper.glob("*.AT2"))
    print(f"new: {a.pcrf}; old: {a.old}; {len(records)} records of {paper}")
    print("| scene | PGA / threshold | cases | max rel. change theta_max | omega_max | t_theta_max |"
          " statuses differ | impacts differ | median rel. change theta_max |")
    print("|---|---|---|---|---|---|---|---|---|")
    for scene in ("block", "rocking-frame"):
        thr_g = uplift_threshold_g(a.pcrf, scene)
        for level in LEVELS:
            rows = []
            for rec in records:
                args = ["run", *SCENES[scene], "--record", str(rec), "--measure", "pga_g", "--intensity", repr(level * thr_g)]
                rows.append((pcrf_json([a.pcrf, *args]), pcrf_json([a.old, *args])))
            th = sorted(relative(n["theta_max_rad"], o["theta_max_rad"]) for n, o in rows)
            om = max(relative(n["omega_max_rad_s"], o["omega_max_rad_s"]) for n, o in rows)
            tt = max(relative(n["t_theta_max_s"], o["t_theta_max_s"]) for n, o in rows)
            st = sum(n["status"] != o["status"] for n, o in rows)
            im = sum(n["impacts"] != o["impacts"] for n, o in rows)
            print(f"| {scene} | {level} | {len(rows)} | {th[-1]:.1e} | {om:.1e} | {tt:.1e} | {st} | {im} | {th[len(th) // 2]:.1e} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
