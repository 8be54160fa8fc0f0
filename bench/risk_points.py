#!/usr/bin/env python3
"""CPU time of `pcrf cube risk` against the number of hazard-curve points (issue 41: a
10^5-point curve ran for minutes, 1 000 points for 5 s, under the Simpson grid).

Makes a tiny IDA cube (6 stochastic records, one frame), then runs `pcrf cube risk` on power-law
curves of N points from 0.01 to 10 g and prints a table of the child's CPU seconds (user +
system, the median of --runs runs) per N. Give --baseline with another `pcrf` to print its
column beside (old and new interleaved run by run, so that load moves both alike).

    bench/risk_points.py --pcrf build/pcrf
    bench/risk_points.py --pcrf build/pcrf --baseline /work/main/build/pcrf --points 10,100,1000
"""

import argparse
import resource
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

STUDY = """[study]
name = "risk_points"

[[records]]
synthetic = ["stochastic:seed=1,pga_g=1,duration_s=3", "stochastic:seed=2,pga_g=1,duration_s=3",
             "stochastic:seed=3,pga_g=1,duration_s=3", "stochastic:seed=4,pga_g=1,duration_s=3",
             "stochastic:seed=5,pga_g=1,duration_s=3", "stochastic:seed=6,pga_g=1,duration_s=3",
             "stochastic:seed=7,pga_g=1,duration_s=3", "stochastic:seed=8,pga_g=1,duration_s=3",
             "stochastic:seed=9,pga_g=1,duration_s=3", "stochastic:seed=10,pga_g=1,duration_s=3"]

[intensity]
measure = "pga_g"

[ida]
start = 0.5
max_intensity = 8

[physics]
tail_s = 1
"""


def curve(points):
    """lambda = 2.625e-4 x^-3 /yr at `points` log-spaced PGAs from 0.01 to 10 g."""
    rows = []
    for i in range(points):
        x = 0.01 * 1000.0 ** (i / (points - 1))
        rows.append(f"{x:.17g},{2.625e-4 * x ** -3:.17g}")
    return "pga_g,annual_rate_per_yr\n" + "\n".join(rows) + "\n"


def cpu_of(argv, cwd):
    """User + system seconds of one run of argv (a child reaped alone), and its exit code."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    done = subprocess.run(argv, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime), done.returncode, done.stderr


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--pcrf", required=True)
    parser.add_argument("--baseline", help="another pcrf, timed interleaved with --pcrf")
    parser.add_argument("--points", default="10,100,1000,10000", help="comma-separated curve sizes")
    parser.add_argument("--runs", type=int, default=3)
    args = parser.parse_args()
    args.pcrf = str(Path(args.pcrf).resolve())
    args.baseline = args.baseline and str(Path(args.baseline).resolve())
    work = Path(tempfile.mkdtemp(prefix="risk_points_"))
    (work / "study.toml").write_text(STUDY)
    made = subprocess.run([args.pcrf, "study", "study.toml", "-o", "cube.h5"], cwd=work, capture_output=True, text=True)
    if made.returncode != 0:
        sys.exit(f"cannot make the cube: {made.stderr.strip()}")
    binaries = [("new", args.pcrf)] + ([("baseline", args.baseline)] if args.baseline else [])
    print(f"{'points':>8} " + " ".join(f"{name + ' cpu [s]':>18}" for name, _ in binaries) +
          (f" {'ratio':>8}" if args.baseline else ""))
    for n in (int(p) for p in args.points.split(",")):
        (work / "h.csv").write_text(curve(n))
        times = {name: [] for name, _ in binaries}
        for _ in range(args.runs):
            for name, binary in binaries:
                seconds, code, err = cpu_of([binary, "cube", "risk", "cube.h5", "--hazard", "h.csv"], work)
                if code != 0:
                    sys.exit(f"{name} at {n} points: exit {code}: {err.strip()[-300:]}")
                times[name].append(seconds)
        medians = [statistics.median(times[name]) for name, _ in binaries]
        line = f"{n:>8} " + " ".join(f"{m:>18.3f}" for m in medians)
        if args.baseline:
            line += f" {medians[0] / medians[1]:>8.3f}"
        print(line, flush=True)


if __name__ == "__main__":
    main()
