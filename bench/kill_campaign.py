#!/usr/bin/env python3
"""Kill campaign (not a test): SIGKILL a study at random instants, hundreds of times, with a
tiny flush interval, each run resuming the last; after every kill the cube must read
(`pcrf cube info` exit 0), and the resumed cube must equal an uninterrupted run.

    python3 bench/kill_campaign.py --pcrf build/pcrf [--kills 300] [--ranks 1]
    python3 bench/kill_campaign.py --pcrf build/pcrf --study units --kills 60   # chunks sealed by workers
    python3 bench/kill_campaign.py --pcrf build/pcrf --study units --ranks 3 --samples 120000 --kills 60  # ranks' parts

Prints how many kills hit, how many left a cube, whether any cube was unreadable, and
whether the final cube equals the uninterrupted one (status, every metric but wall time, and
every numeric coordinate).
"""
import argparse
import os
import random
import signal
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
STUDY = """[[records]]
synthetic = ["sine:amplitude_g=1.5,period_s=0.5,cycles=2,duration_s=3", "sine:amplitude_g=1.3,period_s=0.7,cycles=2,duration_s=3",
             "stochastic:seed=3,pga_g=1.2,duration_s=6"]
[axes]
scale = [0.9, 1.1, 1.3]
kappa = {from = 1.0, to = 3.0, count = 8}
tan_alpha = {from = 0.16, to = 0.24, count = 8}
"""
# 70 000 frames that never lift: five chunks of the cube, so that workers seal whole chunks
# (issue 38) and the kills land in sealed chunks' checkpoints and folds too.
UNITS = """[plan]
kind = "lhs"
samples = 70000
seed = 4
[[records]]
synthetic = "stochastic:seed=1,pga_g=0.026,duration_s=4,dt_s=0.01"
[axes]
kappa = {from = 1.26, to = 2.34}
tan_alpha = {from = 0.14, to = 0.26}
lambda_h = {from = 0.14, to = 0.26}
"""


def command(pcrf, ranks, output, extra):
    launcher = ["mpirun", "--oversubscribe", "-n", str(ranks)] if ranks > 1 else []
    return launcher + [pcrf, "study", "k.toml", "-o", output, "--progress-interval", "0"] + extra


def same(a, b):
    with h5py.File(a, "r") as x, h5py.File(b, "r") as y:
        if not np.array_equal(x["status"][()], y["status"][()]):
            return False
        for name, var in x.items():
            if not isinstance(var, h5py.Dataset) or name in ("status", "cpu_time_s", "wall_time_s"):
                continue  # the status compared above; times are measured, never twice the same
            # Every metric, and every numeric 1-D coordinate (issue 38: a sampled plan's are
            # written with the units, the rest at close), value for value.
            if var.shape == x["status"].shape or (var.ndim == 1 and var.dtype.kind in "fi"):
                if name not in y or not np.array_equal(var[()], y[name][()], equal_nan=True):
                    return False
    return True


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--pcrf", required=True)
    parser.add_argument("--kills", type=int, default=300)
    parser.add_argument("--ranks", type=int, default=1)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--study", choices=["grid", "units"], default="grid",
                        help="grid: 1 728 rocking cases; units: 70 000 non-lifting ones in sealed chunks")
    parser.add_argument("--samples", type=int, default=70000,
                        help="cases of the units study (units need 2 chunks of 16 384 a rank and one more: "
                             "120000 for 3 ranks, where worker ranks keep their chunks in parts)")
    args = parser.parse_args()
    pcrf = os.path.abspath(args.pcrf)
    work = tempfile.mkdtemp(prefix="pcrf_kills_")
    os.chdir(work)
    open("k.toml", "w").write(STUDY if args.study == "grid" else UNITS.replace("samples = 70000",
                                                                                 f"samples = {args.samples}"))
    t0 = time.time()
    subprocess.run(command(pcrf, args.ranks, "whole.h5", []), check=True, capture_output=True, env=ENV)
    whole_s = time.time() - t0
    rng = random.Random(args.seed)
    hit = left = unreadable = 0
    for k in range(args.kills):
        p = subprocess.Popen(command(pcrf, args.ranks, "killed.h5", ["--resume", "--flush-interval-s", "0.001"]),
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=ENV, start_new_session=True)
        time.sleep(rng.uniform(0.0, 1.2 * whole_s))
        if p.poll() is None:
            hit += 1
            os.killpg(p.pid, signal.SIGKILL)
        p.wait()
        if os.path.exists("killed.h5"):
            left += 1
            info = subprocess.run([pcrf, "cube", "info", "killed.h5"], capture_output=True, env=ENV)
            if info.returncode != 0:
                unreadable += 1
                print(f"kill {k}: unreadable cube:\n{info.stderr.decode()}")
        if os.path.exists("killed.h5") and subprocess.run([pcrf, "cube", "info", "killed.h5"], capture_output=True,
                                                          env=ENV).stdout.decode().find("(100.0 %)") >= 0:
            os.remove("killed.h5")  # finished: start over, so that creation gets hit again
    subprocess.run(command(pcrf, args.ranks, "killed.h5", ["--resume"]), check=True, capture_output=True, env=ENV)
    print(f"{args.kills} runs, {hit} killed while running, {left} left a cube, {unreadable} unreadable; "
          f"resumed cube equals the uninterrupted one: {same('whole.h5', 'killed.h5')}")
    return 1 if unreadable else 0


if __name__ == "__main__":
    sys.exit(main())
