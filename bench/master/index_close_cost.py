#!/usr/bin/env python3
"""What closing a fold's file costs as the cube grows (issue 38, item 5): does the last fold's
HDF5 work grow with the study, or is it bounded?

    python3 bench/master/index_close_cost.py --program build/bench/master/pcrf_index_close

rank_costs.py puts about 0.4 instructions a result in rank 0's last fold (CubeWriter::close) on
its non-lifting LHS of 72 chunks: HDF5 serializing each variable's chunk index (a fixed array,
HDF5 1.10 file format) as the fold's file closes. scaling_model.py multiplies a serial cost a
result by the workers; this bench says whether that cost is a cost a result at all.
pcrf_index_close writes CHUNKS chunks of 16 384 values into each of 26 variables (the cube's 18
and its 8 coordinates of that study) raw, as the stream does, then closes the file; callgrind
counts H5Fclose and H5Dwrite_chunk (inclusive, instructions, independent of the machine's load).
Prints, per size: the close's instructions, a result's share of them, and what a chunk write
costs during the run (where HDF5's metadata cache writes the index pages it evicts).
"""
import argparse
import os
import re
import subprocess
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
CHUNK_CASES = 16384
VARIABLES = 26


def inclusive(profile, function):
    """Inclusive instructions of `function` (an exact name) in a callgrind file."""
    out = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", profile],
                         capture_output=True, text=True, check=True).stdout
    for line in out.splitlines():
        if re.search(r":" + re.escape(function) + r" \[", line):
            return int(line.split()[0].replace(",", ""))
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--program", default=os.path.join(HERE, "..", "..", "build", "bench", "master", "pcrf_index_close"))
    parser.add_argument("--chunks", type=int, nargs="+", default=[72, 512, 1024, 2048, 4096, 8192],
                        help="chunks a variable (16 384 cases each)")
    args = parser.parse_args()
    print(f"| chunks a variable | cases | H5Fclose [instructions] | a result's share | H5Dwrite_chunk a call |")
    print("| --- | --- | --- | --- | --- |")
    with tempfile.TemporaryDirectory() as folder:
        for chunks in args.chunks:
            file, profile = os.path.join(folder, f"{chunks}.h5"), os.path.join(folder, f"cg.{chunks}")
            subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={profile}", args.program, file,
                            str(VARIABLES), str(chunks)], check=True, capture_output=True)
            close, writes = inclusive(profile, "H5Fclose"), inclusive(profile, "H5Dwrite_chunk")
            cases = chunks * CHUNK_CASES
            print(f"| {chunks:,} | {cases:,} | {close:,} | {close / cases:.3f} | {writes / (chunks * VARIABLES):,.0f} |")
            os.remove(file)


if __name__ == "__main__":
    main()
