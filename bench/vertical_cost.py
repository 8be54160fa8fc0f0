#!/usr/bin/env python3
"""Vertical cost bench (not a test): what a vertical component adds to a case (issue 43), in
instructions counted inside `pcrf::solve_case`, and that the answers do not move.

    python3 bench/vertical_cost.py --pcrf build/pcrf [--old OLD/pcrf] [--records DIR] [--cpu-repeat 5]

Cases (the records come from ../shared/records; PCRF_RECORDS_DIR overrides; without them the
bench says so and stops):
- barely lifting: the basic frame under ER1 at scale 2.0 (theta_max 5.5e-7 rad) and 3.0;
- the 30 paired cases: the paper's ER1-ER10 at scales 2.0, 2.5 and 3.0, each without a
  vertical and with a vertical record of zeros (same dt and length, written by the bench);
- a real vertical: the far-field stations of studies/vertical.toml (their first horizontal and
  their vertical, ../shared/records/vertical_sehyeon9121) at the same three scales, without and
  with the vertical;
- the rigid rockers that take Taylor steps (block and rocking frame of bench/scene_cost.py's
  slenderness and frequency parameter) under ER1, ER3 and ER7 at 1.2x their uplift threshold's
  PGA, without a vertical, with zeros and with the station's vertical.

Instructions: valgrind's callgrind, only what `pcrf::solve_case` executes ("Collected"), which
no load on the machine changes; ratios are with / without the vertical, per case, and their
median and largest over a set. With --old (a build from before a change) the same counts for
it, and the answers compared: every JSON field of `pcrf run` but its time (wall_time_s, cpu_time_s), bit for bit, for
each case with a vertical. Also, always: a zero vertical against none, the largest relative
difference over the numeric fields (t_uplift_s's last bits: the threshold formula at ü_v = 0).

With --cpu-repeat N: a study's cases (lanes = 1, one rank): ER1-ER10 at 21 scales from 2 to
3, with and without the zero vertical, the builds and studies in turn, N runs each. The cases'
own time (cpu_time_s, or wall_time_s from a build before it) per case, median of the N, and
the median over the cases of the ratio zero / none; and the process's user + system time less
that of the same study at scale 0.05 (no case lifts: start-up, records, cube) over the 200
extra cases, which also counts scaling each case's records (outside the case's own time).

A real vertical changes the response (a frame that rests without it may rock with it, a ground
in free fall ends the case early), so its ratios per case range widely; the bench also gives
them over the cases that rock both ways and end with the same status, and per integration step.
"""
import argparse
import csv
import io
import math
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
from case_cost import instructions as callgrind_instructions  # noqa: E402
from scene_cost import SCENES, pcrf_json, uplift_threshold_g  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
PAPER = [f"ER{i}" for i in range(1, 11)]
SCALES = [2.0, 2.5, 3.0]
# The paper's records whose station has a vertical in vertical_sehyeon9121 (rigid rockers).
ROCKER_RECORDS = {"ER1": "RSN953_NORTHR_MUL-UP", "ER3": "RSN1602_DUZCE_BOL-UP", "ER7": "RSN752_LOMAP_CAP-UP"}
ROCKER_PGA_OVER_THRESHOLD = 1.2


def paper_file(records, er):
    return next((records / "paper").glob(f"{er}_*.AT2"))


def zero_vertical(horizontal, folder):
    """An AT2 file of zeros with the horizontal's NPTS and DT, named as a vertical (-UP)."""
    head = horizontal.read_text().splitlines()[:4]
    m = re.search(r"NPTS=\s*(\d+)", head[3])
    npts = int(m.group(1))
    out = folder / (horizontal.stem + "-UP.AT2")
    lines = [head[0], "zero vertical for bench/vertical_cost.py, UP", head[2], head[3]]
    lines += ["  0.0000000E+00" * 5] * (npts // 5) + (["  0.0000000E+00" * (npts % 5)] if npts % 5 else [])
    out.write_text("\n".join(lines) + "\n")
    return out


def station_pairs():
    """(name, h1, up) of every [[records]] with an `up` in studies/vertical.toml."""
    text = (ROOT / "studies" / "vertical.toml").read_text()
    pairs = []
    for block in text.split("[[records]]")[1:]:
        keys = dict(re.findall(r'^(\w+)\s*=\s*"([^"]*)"', block, re.M))
        if "up" in keys:
            pairs.append((keys.get("name", Path(keys["h1"]).stem), Path(keys["h1"]).name, Path(keys["up"]).name))
    return pairs


def answers(pcrf, args):
    out = pcrf_json([pcrf, "run", *args])
    out.pop("wall_time_s", None)
    out.pop("cpu_time_s", None)
    return out


# The solver's work counters: how the answer was found, not the answer.
COUNTERS = ("steps", "rhs_evals", "root_evals", "reinits")


def largest_relative_difference(a, b, counters):
    """Largest |x - y| / max(|x|, |y|) over the numeric fields, the counters' or the others'
    (infinite when another field differs)."""
    worst = 0.0
    for key, x in a.items():
        y = b.get(key)
        if (key in COUNTERS) != counters:
            continue
        if isinstance(x, (int, float)) and isinstance(y, (int, float)) and not isinstance(x, bool):
            if x != y:
                worst = max(worst, abs(x - y) / max(abs(x), abs(y)))
        elif x != y:
            return math.inf
    return worst


class Counter:
    """Instructions of `pcrf run ARGS` per build, counted once per (build, args)."""

    def __init__(self, builds):
        self.builds = builds
        self.cache = {}

    def __call__(self, tag, args):
        key = (tag, tuple(args))
        if key not in self.cache:
            self.cache[key] = callgrind_instructions([self.builds[tag], "run", *args])[0]
        return self.cache[key]


def table(title, header, rows):
    print(f"\n{title}\n")
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for row in rows:
        print("| " + " | ".join(row) + " |")


def summary(name, ratios):
    if ratios:
        print(f"{name}: median {statistics.median(ratios):.3f}x, largest {max(ratios):.3f}x over {len(ratios)} cases")


def child_cpu_s(command):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    done = subprocess.run(command, capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        sys.exit(f"vertical_cost: {' '.join(command)} failed:\n{done.stderr[-2000:]}")
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def case_time_metric(pcrf, records):
    """The per-case time a build reports: cpu_time_s (the solving thread's CPU), or wall_time_s
    from a build before it."""
    result = pcrf_json([pcrf, "run", "--record", str(paper_file(records, "ER1")), "--scale", "0.5"])
    return "cpu_time_s" if "cpu_time_s" in result else "wall_time_s"


def case_times(pcrf, study, cube, metric):
    """{(record, scale): the case's own time [s]} from a study run on one rank."""
    subprocess.run([pcrf, "study", str(study), "-o", str(cube), "--overwrite", "--progress-interval", "0"],
                   capture_output=True, text=True, check=True)
    out = subprocess.run([pcrf, "cube", "export", str(cube), "-m", metric], capture_output=True, text=True, check=True)
    return {(row["record"], row["scale"]): float(row[metric]) for row in csv.DictReader(io.StringIO(out.stdout))}


def study_cpu(builds, records, zeros, repeat, folder):
    """{build: (median case-time ratio zero / none, process CPU per case none, zero [s])} (module doc)."""
    many = [2.0 + 0.05 * i for i in range(21)]  # 21 scales from 2 to 3: 210 cases, most of them rocking

    def study(with_up, scales):
        text = '[study]\nname = "vertical_cost"\n[run]\nlanes = 1\n[axes]\nscale = [%s]\n' % ", ".join(map(repr, scales))
        text += '[outputs]\nmetrics = ["theta_max_rad", "impacts", "METRIC"]\n'
        for er in PAPER:
            h = paper_file(records, er)
            text += f'[[records]]\nname = "{er}"\nh1 = "{h}"\n' + (f'up = "{zeros[er]}"\n' if with_up else "")
        return text
    metric = {tag: case_time_metric(pcrf, records) for tag, pcrf in builds.items()}
    studies = {}
    for tag in builds:
        for up in (False, True):
            for n, scales in ((len(many), many), (1, [0.05])):
                path = folder / f"{tag}_{'up' if up else 'none'}_{n}.toml"
                path.write_text(study(up, scales).replace("METRIC", metric[tag]))
                studies[(tag, up, n)] = path
    cpu = {k: [] for k in studies}
    times = {(tag, up): [] for tag in builds for up in (False, True)}
    for _ in range(repeat):
        for (tag, up, n), path in studies.items():
            cube = folder / "c.h5"
            cpu[(tag, up, n)].append(child_cpu_s([builds[tag], "study", str(path), "-o", str(cube), "--overwrite",
                                                  "--progress-interval", "0"]))
            if n > 1:
                times[(tag, up)].append(case_times(builds[tag], path, cube, metric[tag]))
    cases = len(PAPER) * (len(many) - 1)
    out = {}
    for tag in builds:
        per_case = [(statistics.median(cpu[(tag, up, len(many))]) - statistics.median(cpu[(tag, up, 1)])) / cases
                     for up in (False, True)]
        keys = times[(tag, False)][0].keys()
        ratios = [statistics.median(t[k] for t in times[(tag, True)]) / statistics.median(t[k] for t in times[(tag, False)])
                  for k in keys]
        out[tag] = (statistics.median(ratios), metric[tag], per_case[0], per_case[1])
    return out


def print_study_cpu(builds, records, zeros, repeat, folder):
    cpu = study_cpu(builds, records, zeros, repeat, folder)
    print(f"\nA study of ER1-ER10 at 21 scales from 2 to 3 (lanes = 1, one rank), with and without the zero vertical, "
          f"builds and studies in turn, {repeat} runs each:")
    print("| build | case time | median over the 210 cases of zero / none | process CPU per case, none [ms] | "
          "zero [ms] | zero / none |")
    print("|---|---|---|---|---|---|")
    for tag, (ratio, metric, none_s, zero_s) in cpu.items():
        print(f"| {tag} | {metric} | {ratio:.3f} | {1e3 * none_s:.3f} | {1e3 * zero_s:.3f} | {zero_s / none_s:.3f} |")
    print("(process CPU: user + system less that of the same study at scale 0.05, over the 200 extra cases: it "
          "includes scaling each case's records, outside the case's own time)")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pcrf", required=True)
    ap.add_argument("--old", help="an older pcrf: its counts beside, and its answers compared bit for bit")
    ap.add_argument("--records", default=os.environ.get("PCRF_RECORDS_DIR", str(ROOT.parent / "shared" / "records")))
    ap.add_argument("--cpu-only", action="store_true", help="only the study's CPU (with --cpu-repeat)")
    ap.add_argument("--cpu-repeat", type=int, default=0, help="also time the cases of a study with and without the zero vertical, N runs each")
    a = ap.parse_args()
    records = Path(a.records)
    if not (records / "paper").is_dir() or not (records / "vertical_sehyeon9121").is_dir():
        print(f"vertical_cost: no paper/ or vertical_sehyeon9121/ records in {records} (set PCRF_RECORDS_DIR): "
              "nothing measured")
        return 0
    if shutil.which("valgrind") is None or shutil.which("callgrind_annotate") is None:
        print("vertical_cost: valgrind not found (apt-get install valgrind): nothing measured")
        return 0
    builds = {"new": a.pcrf, **({"old": a.old} if a.old else {})}
    count = Counter(builds)
    tags = list(builds)
    print(f"pcrf: {a.pcrf}" + (f"; old: {a.old}" if a.old else "") +
          "; instructions inside pcrf::solve_case (callgrind), millions")
    mismatches, compared, zero_vs_none, zero_vs_none_counters = [], 0, 0.0, 0.0

    def check(args_with_vertical, args_without=None):
        """Old and new answers with the vertical bit for bit; zero vs none within 1e-6."""
        nonlocal compared, zero_vs_none, zero_vs_none_counters
        new = answers(a.pcrf, args_with_vertical)
        if a.old:
            compared += 1
            if answers(a.old, args_with_vertical) != new:
                mismatches.append(" ".join(args_with_vertical))
        if args_without is not None:
            without = answers(a.pcrf, args_without)
            zero_vs_none = max(zero_vs_none, largest_relative_difference(new, without, False))
            zero_vs_none_counters = max(zero_vs_none_counters, largest_relative_difference(new, without, True))
        return new

    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        zeros = {er: zero_vertical(paper_file(records, er), folder) for er in PAPER}
        if a.cpu_only:
            print_study_cpu(builds, records, zeros, max(a.cpu_repeat, 1), folder)
            return 0

        # 1 and 2: the 30 paired cases (the barely lifting one first).
        header = ["record", "scale", "theta_max [rad]"] + [f"{t} none" for t in tags] + [f"{t} zero" for t in tags] + \
                 [f"{t} zero/none" for t in tags]
        rows, ratios = [], {t: [] for t in tags}
        for er in PAPER:
            for scale in SCALES:
                none = ["--record", str(paper_file(records, er)), "--scale", repr(scale)]
                zero = none + ["--record-up", str(zeros[er])]
                result = check(zero, none)
                n = {t: count(t, none) for t in tags}
                z = {t: count(t, zero) for t in tags}
                for t in tags:
                    ratios[t].append(z[t] / n[t])
                rows.append([er, f"{scale:g}", f"{result['theta_max_rad']:.3g}"] + [f"{n[t] / 1e6:.2f}" for t in tags] +
                            [f"{z[t] / 1e6:.2f}" for t in tags] + [f"{z[t] / n[t]:.3f}" for t in tags])
        table("The paper's records without a vertical and with a vertical of zeros (basic frame)", header, rows)
        for t in tags:
            summary(f"{t}: zero vertical / none", ratios[t])
            print(f"{t}: ER1 at scale 2.0 (barely lifting): {ratios[t][0]:.3f}x")

        # 3: a real vertical.
        header = ["station", "scale", "status"] + [f"{t} none" for t in tags] + [f"{t} with" for t in tags] + \
                 [f"{t} with/none" for t in tags]
        rows, ratios = [], {t: [] for t in tags}
        rocking, per_step = {t: [] for t in tags}, {t: [] for t in tags}
        far = records / "vertical_sehyeon9121"
        for name, h1, up in station_pairs():
            for scale in SCALES:
                none = ["--record", str(far / h1), "--scale", repr(scale)]
                real = none + ["--record-up", str(far / up)]
                result = check(real)
                alone = answers(a.pcrf, none)
                n = {t: count(t, none) for t in tags}
                w = {t: count(t, real) for t in tags}
                for t in tags:
                    ratios[t].append(w[t] / n[t])
                    # Cases that rock with and without the vertical, to the end: a comparable response.
                    if result["steps"] > 0 and alone["steps"] > 0 and result["status"] == alone["status"]:
                        rocking[t].append(w[t] / n[t])
                        per_step[t].append((w[t] / result["steps"]) / (n[t] / alone["steps"]))
                rows.append([name, f"{scale:g}", result["status"]] + [f"{n[t] / 1e6:.2f}" for t in tags] +
                            [f"{w[t] / 1e6:.2f}" for t in tags] + [f"{w[t] / n[t]:.3f}" for t in tags])
        table("The far-field stations without and with their vertical (basic frame)", header, rows)
        for t in tags:
            summary(f"{t}: real vertical / none", ratios[t])
            summary(f"{t}: real vertical / none, cases that rock both ways and end alike", rocking[t])
            summary(f"{t}: real vertical / none per integration step, the same cases", per_step[t])

        # 4: the rigid rockers (Taylor steps).
        header = ["scene", "record", "theta_max [rad]"] + [f"{t} {v}" for v in ("none", "zero", "real") for t in tags] + \
                 [f"{t} zero/none" for t in tags] + [f"{t} real/none" for t in tags]
        rows = []
        for scene in ("block", "rocking-frame"):
            level = ROCKER_PGA_OVER_THRESHOLD * uplift_threshold_g(a.pcrf, scene)
            for er, up in ROCKER_RECORDS.items():
                none = [*SCENES[scene], "--record", str(paper_file(records, er)), "--measure", "pga_g",
                        "--intensity", repr(level)]
                zero = none + ["--record-up", str(zeros[er])]
                real = none + ["--record-up", str(far / f"{up}.AT2")]
                result = check(zero, none)
                check(real)
                c = {(t, v): count(t, args) for t in tags for v, args in (("none", none), ("zero", zero), ("real", real))}
                rows.append([scene, er, f"{result['theta_max_rad']:.3g}"] +
                            [f"{c[(t, v)] / 1e6:.2f}" for v in ("none", "zero", "real") for t in tags] +
                            [f"{c[(t, 'zero')] / c[(t, 'none')]:.3f}" for t in tags] +
                            [f"{c[(t, 'real')] / c[(t, 'none')]:.3f}" for t in tags])
        table(f"Rigid rockers at {ROCKER_PGA_OVER_THRESHOLD}x their threshold: none, zeros, the station's vertical",
              header, rows)

        print(f"\nzero vertical against none: largest relative difference of the results {zero_vs_none:.2g} "
              f"(the goal: at most 1e-6); of the solver's counters ({', '.join(COUNTERS)}) {zero_vs_none_counters:.2g}")
        if a.old:
            print(f"answers with a vertical, old against new: {compared - len(mismatches)} of {compared} "
                  "identical bit for bit")
            for m in mismatches:
                print(f"  differs: pcrf run {m}")
        if a.cpu_repeat > 0:
            print_study_cpu(builds, records, zeros, a.cpu_repeat, folder)
    return 1 if mismatches else 0


if __name__ == "__main__":
    sys.exit(main())
