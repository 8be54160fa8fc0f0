#!/usr/bin/env python3
"""Case cost bench (not a test): instructions and time of one rocking case, per scene, and
against an older build of pcrf (the speed issue: the purpose-built integrator).

    python3 bench/case_cost.py --pcrf build/pcrf [--old OLD/pcrf] [--repeat 7] [--records DIR]
    cmake --build build --target case_cost                   # the same through CMake

Cases: the paper's basic frame (`pcrf`) and Housner's block of its slenderness (alpha = atan
0.2) and frequency parameter (p = 2.12 rad/s) under four of the paper's far-field records
scaled to a PGA of 1.2x each scene's own uplift threshold (the records come from
../shared/records; PCRF_RECORDS_DIR overrides; without them the bench says so and stops).

Two measures, as a shared and loaded machine requires:
- instructions: valgrind's callgrind counts only what `pcrf::solve_case` executes (process
  start-up and reading the record excluded; the per-case set-up counted), "Collected". These
  do not depend on the load. Also the share of them spent in the right-hand side (the
  scene's terms, the record, sincos) -- what is left when the integrator's own work is small;
- time: the solver's own cpu_time_s (wall_time_s from a build before the rename), the two builds run in turn (A B A B ...), median of
  --repeat runs each, and the ratio old/new taken pair by pair (median of the pair ratios).
  On a loaded machine a long case is preempted more often than a short one, which inflates
  that ratio; so, with --old, also
- CPU per case in a study: the frame under the four records at 100 PGAs within ±0.5 % of
  1.2x its threshold (400 rocking cases, one rank, `pcrf study`), the process's user +
  system time, less that of the same study at one PGA (start-up, records, cube), over 396;
  the two builds in turn, median of --repeat runs each.

Without valgrind the instruction columns are left out, with a note.
"""
import argparse
import os
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
# The scenes, records and level of the scene-cost bench, and its way of calling pcrf.
from scene_cost import RECORD_PGA_OVER_THRESHOLD as PGA_OVER_THRESHOLD  # noqa: E402
from scene_cost import RECORDS, case_time_s, pcrf_json as run_json, uplift_threshold_g as threshold_g  # noqa: E402
from scene_cost import SCENES as ALL_SCENES  # noqa: E402

SCENES = {name: ALL_SCENES[name] for name in ("pcrf", "block")}
TOGGLE = "pcrf::solve_case(pcrf::PreparedFrame&*"


def case_command(pcrf, scene, record, thr_g):
    return [pcrf, "run", *SCENES[scene], "--record", str(record), "--measure", "pga_g",
            "--intensity", repr(PGA_OVER_THRESHOLD * thr_g)]


def instructions(command):
    """(instructions in solve_case, share in the right-hand side) from callgrind. The
    right-hand side: FlightProblem::rhs (Runge-Kutta stages, restarts) and FlightProblem::taylor
    (the series of a Taylor step, its sincos included), inclusive."""
    with tempfile.TemporaryDirectory() as tmp:
        out_file = os.path.join(tmp, "cg.out")
        res = subprocess.run(["valgrind", "--tool=callgrind", f"--toggle-collect={TOGGLE}",
                              f"--callgrind-out-file={out_file}", *command], capture_output=True, text=True)
        m = re.search(r"Collected\s*:\s*(\d+)", res.stderr)
        if res.returncode != 0 or not m:
            sys.exit(f"case_cost: callgrind failed on {' '.join(command)}:\n{res.stderr[-2000:]}")
        total = int(m.group(1))
        ann = subprocess.run(["callgrind_annotate", "--inclusive=yes", out_file], capture_output=True, text=True).stdout
        rhs = 0
        for name in ("FlightProblem::rhs(", "FlightProblem::taylor("):
            for line in ann.splitlines():
                if name in line:
                    rhs += int(line.split()[0].replace(",", ""))
                    break
        return total, rhs / total if total else float("nan")


def wall_s(command):
    return case_time_s(run_json(command))


def child_cpu_s(command):
    """User + system seconds of one finished child process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    done = subprocess.run(command, capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        sys.exit(f"case_cost: {' '.join(command)} failed:\n{done.stderr[-2000:]}")
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def study_cpu_per_case(builds, paper, thr_g, repeat):
    """{tag: median CPU seconds per rocking case} of a study (see the module's doc)."""
    records = "".join(f'[[records]]\nname = "{rec}"\nfile = "{paper / (rec + ".AT2")}"\n' for rec in RECORDS)
    levels = {"many": [PGA_OVER_THRESHOLD * thr_g * (0.995 + 0.0001 * i) for i in range(100)],
              "one": [PGA_OVER_THRESHOLD * thr_g]}
    with tempfile.TemporaryDirectory() as tmp:
        studies = {}
        for name, values in levels.items():
            studies[name] = os.path.join(tmp, f"{name}.toml")
            with open(studies[name], "w") as f:
                f.write(f'[study]\nname = "case_cost"\n[intensity]\nmeasure = "pga_g"\n[axes]\n'
                        f'intensity = [{", ".join(repr(v) for v in values)}]\n'
                        f'[outputs]\nmetrics = ["theta_max_rad", "impacts"]\n{records}')
        cpu = {(tag, name): [] for tag, _ in builds for name in studies}
        for _ in range(repeat):
            for name, study in studies.items():
                for tag, pcrf in builds:
                    cube = os.path.join(tmp, f"{tag}_{name}.h5")
                    cpu[(tag, name)].append(child_cpu_s([pcrf, "study", study, "-o", cube, "--overwrite"]))
        extra = len(levels["many"]) * len(RECORDS) - len(RECORDS)
        return {tag: (statistics.median(cpu[(tag, "many")]) - statistics.median(cpu[(tag, "one")])) / extra
                for tag, _ in builds}


def median_ratio(a, b):
    return statistics.median(x / y for x, y in zip(a, b))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pcrf", required=True, help="the pcrf to measure")
    ap.add_argument("--old", help="an older pcrf to compare with (e.g. a build of the commit before)")
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--records", default=os.environ.get("PCRF_RECORDS_DIR",
                                                         str(Path(__file__).resolve().parents[2] / "shared" / "records")))
    a = ap.parse_args()
    paper = Path(a.records) / "paper"
    if not paper.is_dir():
        print(f"case_cost: no records at {paper} (set PCRF_RECORDS_DIR): nothing measured")
        return 0
    have_valgrind = shutil.which("valgrind") is not None and shutil.which("callgrind_annotate") is not None
    builds = [("new", a.pcrf)] + ([("old", a.old)] if a.old else [])
    print(f"pcrf: {a.pcrf}" + (f"; old: {a.old}" if a.old else "") + f"; {a.repeat} timed runs per case and build")
    if not have_valgrind:
        print("note: valgrind not found (apt-get install valgrind): instruction counts left out")
    cols = ["scene", "record"]
    for tag, _ in builds:
        cols += [f"{tag} Minstr", f"{tag} RHS share", f"{tag} ms"] if have_valgrind else [f"{tag} ms"]
    if a.old:
        cols += (["instr old/new"] if have_valgrind else []) + ["time old/new"]
    print("| " + " | ".join(cols) + " |")
    print("|" + "---|" * len(cols))
    per_scene = {}
    for scene in SCENES:
        thr = threshold_g(a.pcrf, scene)
        for rec in RECORDS:
            record = paper / f"{rec}.AT2"
            if not record.exists():
                continue
            cmds = {tag: case_command(p, scene, record, thr) for tag, p in builds}
            instr = {tag: instructions(c) if have_valgrind else None for tag, c in cmds.items()}
            times = {tag: [] for tag in cmds}
            for _ in range(a.repeat):
                for tag, c in cmds.items():
                    times[tag].append(wall_s(c))
            row = [scene, rec]
            for tag, _ in builds:
                if have_valgrind:
                    row += [f"{instr[tag][0] / 1e6:.2f}", f"{100 * instr[tag][1]:.0f} %"]
                row.append(f"{1e3 * statistics.median(times[tag]):.3f}")
            if a.old:
                if have_valgrind:
                    row.append(f"{instr['old'][0] / instr['new'][0]:.4f}x")
                row.append(f"{median_ratio(times['old'], times['new']):.1f}x")
            print("| " + " | ".join(row) + " |")
            per_scene.setdefault(scene, []).append((instr, times))
    if have_valgrind and "pcrf" in per_scene and "block" in per_scene:
        frame = sum(i["new"][0] for i, _ in per_scene["pcrf"])
        block = sum(i["new"][0] for i, _ in per_scene["block"])
        per_record = " / ".join(f"{b['new'][0] / f['new'][0]:.2f}"
                                for (b, _), (f, _) in zip(per_scene["block"], per_scene["pcrf"]))
        print(f"\nblock / frame, instructions summed over the records (new): {block / frame:.3f} "
              f"(the goal: at most 1/3); per record {per_record}")
        if a.old:
            for scene, rows in per_scene.items():
                old = sum(i["old"][0] for i, _ in rows)
                new = sum(i["new"][0] for i, _ in rows)
                print(f"{scene}: old/new instructions summed over the records: {old / new:.4f}x")
    if a.old:
        cpu = study_cpu_per_case(builds, paper, threshold_g(a.pcrf, "pcrf"), a.repeat)
        print(f"\nCPU per rocking frame case in a study (400 cases, one rank, median of {a.repeat}): "
              f"new {1e3 * cpu['new']:.3f} ms, old {1e3 * cpu['old']:.3f} ms, old/new {cpu['old'] / cpu['new']:.1f}x")
    return 0


if __name__ == "__main__":
    sys.exit(main())
