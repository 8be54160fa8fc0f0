#!/usr/bin/env python3
"""Non-lifting case cost (issue 27): what a study case costs when its frame never leaves rest.

A Latin-hypercube study over the eight frame parameters (each +-30 % around the basic model,
as studies/sensitivity.toml) under one weak record (ER1 at scale 0.05 when ../shared/records
is there, else a synthetic stochastic record of the same length at 0.026 g): no frame lifts,
and every case is a frame of its own. One rank, no mpirun.

    python3 bench/nonlift_cost.py --pcrf build/pcrf               # 10^5 cases
    python3 bench/nonlift_cost.py --pcrf build/pcrf --cases 1000000
    python3 bench/nonlift_cost.py --pcrf build/pcrf --baseline OLD/pcrf   # old and new, interleaved
    cmake --build build --target nonlift_cost                     # the same through CMake

Two tables:
- instructions per case, from callgrind (valgrind) at two study sizes (--small, default 2000 and
  10 000 cases): the difference over the difference in cases, so start-up cancels. Counts do
  not depend on the machine's load. With --top K, the K functions that take the most of them.
- time per case at --cases (default 10^5), median of --repeat runs (programs interleaved):
  the study's own clock (first case handed out to cube closed, the `in X s` of its closing
  line: the old up-front check ran before it), and the whole command's wall and CPU time
  (user + system, both threads of the rank, the up-front check included) as the difference
  between --cases and the first --small size, so that start-up cancels. On a shared machine
  the CPU time is the steadier figure; wall time counts the other users' load too.
"""
import argparse
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")

# The eight parameters, +-30 % around the basic frame (studies/sensitivity.toml).
AXES = """kappa = {from = 1.26, to = 2.34}
lambda = {from = 1.4, to = 2.6}
tan_alpha = {from = 0.14, to = 0.26}
lambda_h = {from = 0.14, to = 0.26}
pi_sigma_b = {from = 2.8906, to = 5.3682}
pi_sigma_c = {from = 4.6249, to = 8.5891}
pi_e_b = {from = 1878.9, to = 3489.3}
pi_e_c = {from = 3006.2, to = 5582.9}
"""


def record_table(source):
    record = os.path.join(source, "..", "shared", "records", "paper", "ER1_MUL279.AT2")
    if os.path.exists(record):
        return "ER1 x 0.05", 0.05, f'[[records]]\nname = "ER1"\nfile = "{os.path.abspath(record)}"\n'
    synthetic = "stochastic:seed=1,pga_g=0.026,duration_s=29.98,dt_s=0.01"
    return synthetic, 1.0, f'[[records]]\nsynthetic = "{synthetic}"\n'


def write_study(folder, cases, records, scale):
    path = os.path.join(folder, f"nonlift_{cases}.toml")
    with open(path, "w") as f:
        f.write(f'[study]\nname = "nonlift"\n[plan]\nkind = "lhs"\nsamples = {cases}\nseed = 1\n'
                f"[axes]\nscale = {scale}\n{AXES}{records}")
    return path


def run(command):
    """Runs a command; returns (stderr, wall s, cpu s of the child)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True, env=ENV)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if done.returncode != 0:
        sys.exit(f"nonlift_cost: {' '.join(command)} failed:\n{done.stderr}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return done.stderr, wall, cpu


def check_non_lifting(pcrf, cube, cases):
    out = subprocess.run([pcrf, "cube", "info", cube], capture_output=True, text=True, env=ENV).stdout
    match = re.search(r"at_rest\D*(\d+)", out)
    if not match or int(match.group(1)) != cases:
        sys.exit(f"nonlift_cost: not every case ended at rest:\n{out}")


def callgrind(pcrf, study, cube, profile):
    err, _, _ = run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={profile}", pcrf, "study", study,
                     "-o", cube, "--overwrite", "--progress-interval", "0"])
    return int(re.search(r"Collected : (\d+)", err).group(1))


def function_costs(profile):
    """Self cost (Ir) of each function, keyed by object and function, read from the profile
    itself (callgrind_annotate merges unnamed functions of different objects)."""
    names = {"ob": {}, "fn": {}}  # compressed names: cob shares ob's table, cfn fn's
    current = {"ob": "?", "fn": "?"}
    costs, after_call = {}, False

    def name(kind, text):
        match = re.match(r"\((\d+)\)(?: (.*))?", text)
        if not match:
            return text
        if match.group(2) is not None:
            names[kind][match.group(1)] = match.group(2)
        return names[kind].get(match.group(1), text)

    with open(profile) as f:
        for line in f:
            key, _, value = line.rstrip("\n").partition("=")
            if key in ("ob", "fn"):
                current[key] = name(key, value)
            elif key in ("cob", "cfn"):
                name(key[1:], value)
            elif key == "calls":
                after_call = True  # the next cost line is the call's inclusive cost
            elif line[:1].isdigit() or line[:1] in "+-*":
                if after_call:
                    after_call = False
                    continue
                fields = line.split()
                if len(fields) > 1:
                    where = (current["ob"], current["fn"])
                    costs[where] = costs.get(where, 0) + int(fields[1])
    return costs


def short(where, width=90):
    obj, fn = where
    if re.fullmatch(r"0x[0-9a-f]+", fn):  # no symbol: say whose code it is
        fn += " in " + os.path.basename(obj)
    return fn if len(fn) <= width else fn[:width - 3] + "..."


def instructions(programs, sizes, folder, records, scale, top):
    small, large = sizes
    print(f"\ninstructions per non-lifting case (callgrind: ({large} cases - {small} cases) / {large - small})")
    print(f"{'program':>10} {'at ' + str(small):>16} {'at ' + str(large):>16} {'per case':>10}")
    for label, pcrf in programs:
        counts, profiles = [], []
        for n in (small, large):
            profile = os.path.join(folder, f"{label}_{n}.callgrind")
            counts.append(callgrind(pcrf, write_study(folder, n, records, scale), os.path.join(folder, "cg.h5"), profile))
            check_non_lifting(pcrf, os.path.join(folder, "cg.h5"), n)
            profiles.append(profile)
        per_case = (counts[1] - counts[0]) / (large - small)
        print(f"{label:>10} {counts[0]:>16,} {counts[1]:>16,} {per_case:>10,.0f}")
        if top:
            a, b = function_costs(profiles[0]), function_costs(profiles[1])
            rows = sorted(((b.get(k, 0) - a.get(k, 0)) / (large - small), k) for k in set(a) | set(b))
            for cost, name in reversed(rows[-top:]):
                print(f"{'':>10}   {cost:>8,.0f}  {short(name)}")


def timings(programs, cases, small, repeat, folder, records, scale):
    """Per case: the study's own clock over `cases`, and the command's wall and CPU time as the
    difference between `cases` and `small` cases (start-up and MPI's set-up cancel)."""
    studies = {n: write_study(folder, n, records, scale) for n in (small, cases)}
    cube = os.path.join(folder, "time.h5")
    results = {label: {"study": [], "wall": [], "cpu": []} for label, _ in programs}
    for _ in range(repeat):  # interleaved: the machine's load falls on every program alike
        for label, pcrf in programs:
            measured = {}
            for n, study in studies.items():
                err, wall, cpu = run([pcrf, "study", study, "-o", cube, "--overwrite", "--progress-interval", "0"])
                match = re.search(r"(\d+) cases computed.* in ([0-9.]+) s", err)
                if not match or int(match.group(1)) != n:
                    sys.exit(f"nonlift_cost: no closing line for {n} cases in:\n{err}")
                measured[n] = (float(match.group(2)), wall, cpu)
            check_non_lifting(pcrf, cube, cases)
            results[label]["study"].append(1e6 * measured[cases][0] / cases)
            results[label]["wall"].append(1e6 * (measured[cases][1] - measured[small][1]) / (cases - small))
            results[label]["cpu"].append(1e6 * (measured[cases][2] - measured[small][2]) / (cases - small))
    print(f"\ntime per non-lifting case [us], {cases} cases of distinct frames, one rank (median of {repeat}; "
          f"{os.cpu_count()} cores, load {os.getloadavg()[0]:.1f})")
    print(f"  study clock: the closing line's 'in X s' / cases (first case handed out to cube closed);")
    print(f"  wall, CPU (user + system, both threads): whole command, ({cases} cases - {small} cases) / {cases - small}")
    print(f"{'program':>10} {'study clock':>12} {'wall':>8} {'CPU':>8}")
    for label, _ in programs:
        r = {k: statistics.median(v) for k, v in results[label].items()}
        print(f"{label:>10} {r['study']:>12.2f} {r['wall']:>8.2f} {r['cpu']:>8.2f}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    here = os.path.dirname(os.path.abspath(__file__))
    parser.add_argument("--pcrf", default=os.path.join(here, "..", "build", "pcrf"), help="the pcrf executable")
    parser.add_argument("--baseline", help="an older pcrf to compare with (e.g. one built from commit 3de1910)")
    parser.add_argument("--source", default=os.path.join(here, ".."), help="source tree (for ../shared/records)")
    parser.add_argument("--cases", type=int, default=100000, help="cases of the timed study (default 10^5)")
    parser.add_argument("--repeat", type=int, default=3, help="timed runs per program; the median is kept")
    parser.add_argument("--small", type=int, nargs=2, default=[2000, 10000], metavar=("N1", "N2"),
                        help="the two study sizes run under callgrind (default 2000 10000)")
    parser.add_argument("--top", type=int, default=12, help="functions listed per program (0: none)")
    parser.add_argument("--no-callgrind", action="store_true", help="skip the instruction counts")
    args = parser.parse_args()
    programs = ([("baseline", os.path.abspath(args.baseline))] if args.baseline else []) + [("pcrf", os.path.abspath(args.pcrf))]
    label, scale, records = record_table(args.source)
    print(f"nonlift_cost: LHS over the eight parameters (+-30 % around the basic frame), record {label}")
    with tempfile.TemporaryDirectory() as folder:
        has_valgrind = subprocess.run(["which", "valgrind"], capture_output=True).returncode == 0
        if args.no_callgrind or not has_valgrind:
            print("\ninstructions per case: skipped" + ("" if has_valgrind else " (no valgrind)"))
        else:
            instructions(programs, args.small, folder, records, scale, args.top)
        timings(programs, args.cases, args.small[0], args.repeat, folder, records, scale)


if __name__ == "__main__":
    main()
