#!/usr/bin/env python3
"""Same answers for the Latin hypercube by index (issue 38 items 2 and 4): the LHS now draws
other points (a Feistel permutation per dimension, docs: study/sampling.hpp), so its cases
cannot be compared with an older build's LHS. Instead: this build's LHS is run, its frames
are written out as a list plan (each parameter as its shortest round-trip decimal, which
reads back as the same double), and the reference build runs that list. Every metric and
the status of every case (wall and CPU time aside) must be equal bit for bit, row by row
(`pcrf cube export`: equal text is equal bits). Not a test (it needs two builds).

    python3 bench/master/lhs_same_answers.py --baseline /work/main/build/pcrf --pcrf build/pcrf

Prints the number of cases and columns compared and exits 1 on the first difference.
"""
import argparse
import csv
import io
import os
import subprocess
import sys
import tempfile

IGNORED = {"cpu_time_s", "wall_time_s"}
RECORDS = ('[[records]]\nsynthetic = ["sine:amplitude_g=1.5,period_s=0.5,cycles=2,duration_s=3", '
           '"stochastic:seed=1,pga_g=0.6,duration_s=6"]\n')
RANGES = {"kappa": (1.26, 2.34), "lambda": (1.4, 2.6), "tan_alpha": (0.14, 0.26), "lambda_h": (0.14, 0.26),
          "pi_sigma_b": (2.8906, 5.3682), "pi_sigma_c": (4.6249, 8.5891), "pi_e_b": (1878.9, 3489.3),
          "pi_e_c": (3006.2, 5582.9)}
SCALES = "[0.5, 1.0, 2.0]"


def export(pcrf, study, cube):
    done = subprocess.run([pcrf, "study", study, "-o", cube, "--overwrite", "--progress-interval", "0"],
                          capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"{pcrf} study {study} failed:\n{done.stderr[-2000:]}")
    out = subprocess.run([pcrf, "cube", "export", cube, "--no-record-text"], capture_output=True, text=True, check=True)
    return list(csv.DictReader(io.StringIO(out.stdout)))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--baseline", required=True, help="the reference pcrf (e.g. main's build)")
    parser.add_argument("--pcrf", default="build/pcrf")
    parser.add_argument("--samples", type=int, default=300)
    parser.add_argument("--seed", type=int, default=11)
    args = parser.parse_args()
    axes = "".join(f"{k} = {{from = {a}, to = {b}}}\n" for k, (a, b) in RANGES.items())
    with tempfile.TemporaryDirectory() as folder:
        lhs = os.path.join(folder, "lhs.toml")
        with open(lhs, "w") as f:
            f.write(f'[study]\nname = "same"\n{RECORDS}[plan]\nkind = "lhs"\nsamples = {args.samples}\n'
                    f"seed = {args.seed}\n[axes]\nscale = {SCALES}\n{axes}")
        new_rows = export(args.pcrf, lhs, os.path.join(folder, "lhs.h5"))
        frames = {}
        for row in new_rows:
            frames[int(row["case"])] = {k: row[k] for k in RANGES}
        listed = os.path.join(folder, "list.toml")
        with open(listed, "w") as f:
            f.write(f'[study]\nname = "same"\n{RECORDS}[plan]\nkind = "list"\n[axes]\nscale = {SCALES}\n')
            for i in sorted(frames):
                f.write(f'[[cases]]\nlabel = "s{i}"\n' + "".join(f"{k} = {v}\n" for k, v in frames[i].items()))
        old_rows = export(args.baseline, listed, os.path.join(folder, "list.h5"))
    if len(old_rows) != len(new_rows):
        sys.exit(f"{len(new_rows)} cases against the reference's {len(old_rows)}")
    key = ("case", "record", "scale")
    old_by = {tuple(r[k] for k in key): r for r in old_rows}
    columns = [c for c in new_rows[0] if c in old_rows[0] and c not in IGNORED and c not in ("case_label",)]
    for row in new_rows:
        ref = old_by[tuple(row[k] for k in key)]
        for c in columns:
            if row[c] != ref[c]:
                sys.exit(f"case {row['case']} record {row['record']} scale {row['scale']}: {c} {row[c]} "
                         f"against the reference's {ref[c]}")
    lifted = sum(1 for r in new_rows if r.get("status") not in ("at_rest", "0"))
    print(f"equal: {len(new_rows)} cases ({len(frames)} LHS frames x 2 records x 3 scales, {lifted} not at rest), "
          f"{len(columns)} columns compared bit for bit: {', '.join(columns)}")


if __name__ == "__main__":
    main()
