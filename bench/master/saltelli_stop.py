#!/usr/bin/env python3
"""What a stopped Saltelli cube holds (issue 38 item 1), two builds: the share of the cases done
that lie in whole base samples (every frame of the sample done for every record), the only ones
`pcrf cube sensitivity` uses. Before, every Saltelli case went out frame by frame over the whole
cube; now chunks of whole base samples go out whole, column by column, and the column in
progress at the stop is what a stop loses against that order.

    python3 bench/master/saltelli_stop.py --baseline /work/main/build/pcrf --pcrf build/pcrf
    python3 bench/master/saltelli_stop.py --baseline OLD --pcrf NEW --at 0.3 0.6 --ranks 2

The study: 16 384 base samples of three parameters (81 920 frames: 5 chunks of 16 380 and an
edge one a record) under two synthetic records that lift some frames (tests/study/
saltelli_units_test.cpp's). Each run is sent SIGTERM once its progress lines report the given
share of the cases (`--at`); what it saved is read back with `pcrf cube export`. Which cases
are done when the signal lands depends on the machine's load: a table of a few stops, not a
distribution.
"""
import argparse
import csv
import io
import os
import re
import signal
import subprocess
import tempfile
import time

ENV = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
GROUP = 5  # d + 2 frames a base sample
STUDY = ('[study]\nname = "saltelli_stop"\n[[records]]\nsynthetic = ["stochastic:seed=1,pga_g=0.76,duration_s=2,'
         'dt_s=0.01", "stochastic:seed=2,pga_g=0.74,duration_s=2,dt_s=0.01"]\n[plan]\nkind = "saltelli"\n'
         'samples = 16384\nseed = 7\n[axes]\nkappa = {from = 1.26, to = 2.34}\ntan_alpha = {from = 0.14, to = 0.26}\n'
         'lambda_h = {from = 0.14, to = 0.26}\n')
PROGRESS = re.compile(r"pcrf study: (\d+)/(\d+) cases")


def stopped_run(pcrf, ranks, study, cube, share):
    """Runs the study, SIGTERM at `share` of the progress; (cases done, whole base samples, samples)."""
    err_path = cube + ".err"
    command = [pcrf, "study", study, "-o", cube, "--overwrite", "--progress-interval-s", "0.02"]
    if ranks > 1:
        command = ["mpirun", "--oversubscribe", "-n", str(ranks)] + command
    with open(err_path, "w", encoding="utf-8") as err:
        child = subprocess.Popen(command, stderr=err, env=ENV)
        while child.poll() is None:
            time.sleep(0.02)
            with open(err_path, encoding="utf-8") as text:
                seen = PROGRESS.findall(text.read())
            if seen and int(seen[-1][0]) >= share * int(seen[-1][1]):
                child.send_signal(signal.SIGTERM)
                break
        child.wait()
    out = subprocess.run([pcrf, "cube", "export", cube, "--no-record-text"], capture_output=True, text=True,
                         env=ENV, check=True).stdout
    whole, done = {}, 0
    for row in csv.DictReader(io.StringIO(out)):
        ran = row["status"] != "not_run"
        done += ran
        sample = int(row["saltelli_sample"])
        whole[sample] = whole.get(sample, True) and ran
    return done, sum(whole.values()), len(whole)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--baseline", required=True, help="the build before (Saltelli frame by frame)")
    parser.add_argument("--pcrf", default=os.path.join(os.path.dirname(__file__), "..", "..", "build", "pcrf"))
    parser.add_argument("--ranks", type=int, default=1, help="MPI ranks (mpirun --oversubscribe)")
    parser.add_argument("--at", type=float, nargs="*", default=[0.2, 0.45, 0.7], help="progress shares to stop at")
    args = parser.parse_args()
    print(f"saltelli_stop: 163 840 cases (2 records x 81 920 frames), {args.ranks} rank(s), SIGTERM at a share "
          "of the progress\n")
    print("| build | stopped at | cases done | whole base samples | done cases in whole base samples |")
    print("| --- | ---: | ---: | ---: | ---: |")
    with tempfile.TemporaryDirectory() as folder:
        study = os.path.join(folder, "s.toml")
        with open(study, "w", encoding="utf-8") as f:
            f.write(STUDY)
        for share in args.at:
            for name, pcrf in (("before", args.baseline), ("this build", args.pcrf)):
                done, whole, samples = stopped_run(os.path.abspath(pcrf), args.ranks, study,
                                                   os.path.join(folder, "c.h5"), share)
                records = 2
                kept = whole * GROUP * records / done if done else float("nan")
                print(f"| {name} | {share:.0%} | {done:,} | {whole:,} of {samples:,} | {kept:.1%} |", flush=True)


if __name__ == "__main__":
    main()
