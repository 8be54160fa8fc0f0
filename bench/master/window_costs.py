#!/usr/bin/env python3
"""What a thread's window of a sampled plan's columns (src/study/plans/column_window.hpp, issue
38) does to each way cases reach a worker: every rank's instructions, counted by callgrind, for
a reference pcrf (e.g. main's build) and this one, on the studies of same_answers.py.

    python3 bench/master/window_costs.py --baseline /work/main/build/pcrf --pcrf build/pcrf
    python3 bench/master/window_costs.py --baseline OLD --pcrf NEW --studies lhs-units:1 saltelli-units:3

Each study runs once per build under `valgrind --tool=callgrind` on every rank (mpirun
--oversubscribe), and the table gives all ranks' instructions together, start-up included, and
their ratio (new / reference). The default set covers how the frames are asked:
- lhs-units at 1 rank: cases handed out in batches, in order (the window fills; no unit sealed);
- lhs-units at 3 ranks: whole chunks sealed by their workers (the window fills and is sealed);
- saltelli-units at 3 ranks: chunks of 16 380 frames (whole base samples), not aligned to the
  window's 16 384, two records: each chunk's frames asked twice, a window's end inside it;
- ida-units at 3 ranks: each frame asked for each run of its curve;
- lhs, sobol, saltelli at 3 ranks: a few dozen cases handed out one by one (the row path);
- grid-units at 3 ranks: a grid, which has no window (a control: its ratio is 1).
Instruction counts do not depend on the machine's load; a run takes minutes.
"""
import argparse
import glob
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from same_answers import ENV, STUDIES  # noqa: E402

DEFAULT = ["lhs-units:1", "lhs-units:3", "saltelli-units:3", "ida-units:3", "lhs:3", "sobol:3", "saltelli:3",
           "grid-units:3"]


def instructions(pcrf, ranks, study, folder):
    """Every rank's instructions (callgrind's totals) for one run of `study`."""
    outputs = os.path.join(folder, "cg")
    os.makedirs(outputs, exist_ok=True)
    for old in glob.glob(os.path.join(outputs, "*")):
        os.remove(old)
    command = ["valgrind", "--tool=callgrind", "--callgrind-out-file=" + os.path.join(outputs, "cg.%p"), pcrf,
               "study", study, "-o", os.path.join(folder, "cube.h5"), "--overwrite", "--progress-interval", "0"]
    if ranks > 1:
        command = ["mpirun", "--oversubscribe", "-n", str(ranks)] + command
    done = subprocess.run(command, capture_output=True, text=True, env=ENV)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(command)} failed:\n{done.stderr[-2000:]}")
    total = 0
    for path in glob.glob(os.path.join(outputs, "cg.*")):
        with open(path) as f:
            for line in f:
                if line.startswith(("summary:", "totals:")):
                    total += int(line.split()[1])
                    break
    return total


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--baseline", required=True, help="the reference pcrf")
    parser.add_argument("--pcrf", default=os.path.join(HERE, "..", "..", "build", "pcrf"))
    parser.add_argument("--studies", nargs="*", default=DEFAULT, help="STUDY:RANKS, studies of same_answers.py")
    parser.add_argument("--records", default=os.path.join(HERE, "..", "..", "..", "shared", "records"))
    args = parser.parse_args()
    print("| study | ranks | reference [G instructions] | this build [G instructions] | ratio |")
    print("| --- | --- | --- | --- | --- |")
    with tempfile.TemporaryDirectory() as folder:
        for item in args.studies:
            name, ranks = item.split(":")
            path = os.path.join(folder, name + ".toml")
            with open(path, "w") as f:
                f.write(STUDIES[name].format(records=os.path.abspath(args.records)) if name == "pairs" else STUDIES[name])
            old = instructions(os.path.abspath(args.baseline), int(ranks), path, folder)
            new = instructions(os.path.abspath(args.pcrf), int(ranks), path, folder)
            print(f"| {name} | {ranks} | {old / 1e9:.3f} | {new / 1e9:.3f} | {new / old:.3f} |", flush=True)


if __name__ == "__main__":
    main()
