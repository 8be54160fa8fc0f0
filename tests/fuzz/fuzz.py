#!/usr/bin/env python3
"""Mutation fuzzing of every input path of the `pcrf` command line (docs/robustness.md).

Each target starts from seeds it writes itself (an AT2 record, a two-column and a one-column
text record, synthetic-motion strings, study files, a small cube that a tiny study makes,
hazard curves read against a tiny IDA cube and as a study's hazard-consistent stripes, the
Python module's keywords and dict studies: python_containers.py), mutates them, runs `pcrf`
(or a child Python calling the module) on each mutant and judges the outcome by the engine's
rule for bad input: exit 0, or exit 2 with one `pcrf: error:` line. Anything else is a finding: a signal,
a hang (past --timeout-s), exit 1 ("internal error"), a sanitizer report, or exit 2 with
more or less than one error line. Each finding's input and command are saved in --out.

Deterministic: mutant k of a target is the same for the same --seed, whatever the budget;
the budget only decides how many are run. Standard library only.

    tests/fuzz/fuzz.py --pcrf build/pcrf                      # every target, 600 s in all
    tests/fuzz/fuzz.py --pcrf build/pcrf --budget-s 60 --targets cube,study --seed 7

Exit status: 0 when no mutant gave a finding, 1 when one did, 2 on bad arguments.
"""

import argparse
import json
import math
import os
import random
import re
import shutil
import struct
import subprocess
import sys
import time
import zlib
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from python_containers import PythonContainers, module_available  # noqa: E402

ERROR_LINE = re.compile(r"^pcrf: error: ")
SANITIZER = re.compile(r"AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer|runtime error:")

# Values that break parsers and sizes: zero, signs, extremes, non-numbers, long runs.
INTERESTING_NUMBERS = ["0", "-0", "1", "-1", "0.0", "1e308", "-1e308", "1e-320", "4.9e-324", "nan", "inf", "-inf",
                       "9223372036854775807", "-9223372036854775808", "18446744073709551616", "2147483648",
                       "1e12", "1e999", "0x10", "1,5", "1..2", "+", "-", ".", "e5", "1e", "00000000000000000001",
                       "3.7", "1" * 400]
INTERESTING_BYTES = [0x00, 0x01, 0x7F, 0x80, 0xFF, 0xFE, 0x0A, 0x0D, 0x20, 0x22, 0x27, 0x2C, 0x3D, 0x5B, 0x5D, 0x2E]
NUMBER = re.compile(rb"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eEdD][-+]?\d+)?")


# ---- mutations ------------------------------------------------------------------------------

def flip_bits(rng, data):
    data = bytearray(data)
    for _ in range(rng.randint(1, 4)):
        if data:
            data[rng.randrange(len(data))] ^= 1 << rng.randrange(8)
    return bytes(data)


def set_bytes(rng, data):
    data = bytearray(data)
    for _ in range(rng.randint(1, 3)):
        if data:
            data[rng.randrange(len(data))] = rng.choice(INTERESTING_BYTES)
    return bytes(data)


def replace_number(rng, data):
    spans = [m.span() for m in NUMBER.finditer(data)]
    if not spans:
        return set_bytes(rng, data)
    start, end = rng.choice(spans)
    return data[:start] + rng.choice(INTERESTING_NUMBERS).encode() + data[end:]


def edit_lines(rng, data):
    lines = data.split(b"\n")
    i = rng.randrange(len(lines))
    how = rng.randrange(4)
    if how == 0:
        del lines[i]
    elif how == 1:
        lines.insert(i, lines[i])
    elif how == 2:
        lines[i] = lines[i] * rng.randint(2, 50)
    else:
        j = rng.randrange(len(lines))
        lines[i], lines[j] = lines[j], lines[i]
    return b"\n".join(lines)


def splice(rng, data):
    if len(data) < 2:
        return data + data
    a, b = sorted(rng.randrange(len(data)) for _ in range(2))
    how = rng.randrange(3)
    if how == 0:
        return data[:a] + data[b:]  # cut
    if how == 1:
        return data[:b] + data[a:b] * rng.randint(1, 20) + data[b:]  # repeat
    return data[:a]  # truncate


def insert_junk(rng, data):
    at = rng.randrange(len(data) + 1)
    junk = bytes(rng.randrange(256) for _ in range(rng.randint(1, 16)))
    return data[:at] + junk + data[at:]


TEXT_MUTATIONS = [flip_bits, set_bytes, replace_number, replace_number, edit_lines, splice, insert_junk]


def mutate_text(rng, data):
    for _ in range(rng.randint(1, 3)):
        data = rng.choice(TEXT_MUTATIONS)(rng, data)
    return data


def mutate_binary(rng, data, hot_bytes, avoid=()):
    """Bytes changed mostly in the first `hot_bytes` (an HDF5 file's metadata), a few anywhere;
    none in the [start, end) ranges of `avoid`."""
    data = bytearray(data)
    for _ in range(rng.choice([1, 1, 1, 2, 3, 8])):
        span = hot_bytes if rng.random() < 0.8 else len(data)
        at = rng.randrange(min(span, len(data)))
        if any(start - 4 < at < end for start, end in avoid):
            continue
        how = rng.randrange(3)
        if how == 0:
            data[at] ^= 1 << rng.randrange(8)
        elif how == 1:
            data[at] = rng.choice(INTERESTING_BYTES)
        else:  # a little-endian length or address field set to something huge
            data[at:at + 4] = rng.choice([b"\xff\xff\xff\xff", b"\x00\x00\x00\x00", b"\x00\x00\x00\x80"])
    return bytes(data)


# ---- targets --------------------------------------------------------------------------------

def at2_record(samples=200, dt=0.01):
    values = [0.3 * math.sin(2 * math.pi * k * dt / 0.4) * math.exp(-k * dt) for k in range(samples)]
    rows = ["".join(f"{v:15.7E}" for v in values[i:i + 5]) for i in range(0, samples, 5)]
    return ("PEER NGA STRONG MOTION DATABASE RECORD\nFuzz event, 1/1/2000, Fuzz station, 090\n"
            "ACCELERATION TIME SERIES IN UNITS OF G\n"
            f"NPTS= {samples:6d}, DT= {dt:.4f} SEC\n" + "\n".join(rows) + "\n").encode()


def two_column_record(samples=200, dt=0.01):
    return "".join(f"{k * dt:.3f} {0.2 * math.sin(k * dt * 9.0):.6f}\n" for k in range(samples)).encode()


def one_column_record(samples=200):
    return "".join(f"{0.2 * math.cos(k * 0.07):.6f}\n" for k in range(samples)).encode()


class Target:
    name = ""
    suffix = ".txt"

    def seeds(self, work):
        """[(label, bytes, extra arguments)]"""
        raise NotImplementedError

    def mutate(self, rng, data):
        return mutate_text(rng, data)

    def command(self, pcrf, file, extra):
        raise NotImplementedError


class Records(Target):
    """AT2, two-column and one-column text records read by `pcrf record`."""
    name = "records"

    def seeds(self, work):
        return [("at2", at2_record(), ["--format", "at2"]),
                ("two_column", two_column_record(), ["--format", "two-column", "--units", "g"]),
                ("one_column", one_column_record(), ["--format", "one-column", "--units", "g", "--dt", "0.01"])]

    def command(self, pcrf, file, extra):
        return [pcrf, "record", str(file), *extra, "--period", "0.5"]


class Synthetic(Target):
    """Synthetic-motion and pulse strings, run by `pcrf run --synthetic` (with no tail)."""
    name = "synthetic"

    def seeds(self, work):
        texts = ["sine:amplitude_g=1.5,period_s=0.5,cycles=2,duration_s=3",
                 "stochastic:seed=1,pga_g=0.8,duration_s=4",
                 "ricker:amplitude_g=1.2,period_s=0.6",
                 "sine:amplitude_g=0.5,period_s=0.3,cycles=1"]
        return [(f"s{i}", t.encode(), []) for i, t in enumerate(texts)]

    def mutate(self, rng, data):
        # Keep the strings to a command-line argument: no NUL, no new line.
        return mutate_text(rng, data).replace(b"\x00", b"").replace(b"\n", b"")

    def command(self, pcrf, file, extra):
        text = file.read_bytes().decode("utf-8", "surrogateescape")
        return [pcrf, "run", "--synthetic", text, "--tail-s", "0"]


TINY_STUDY = """[study]
name = "fuzz"

[plan]
kind = "grid"

[[records]]
synthetic = ["sine:amplitude_g=1.5,period_s=0.5,cycles=2,duration_s=2", "stochastic:seed=1,pga_g=1.4,duration_s=3"]

[axes]
scale = [1.0, 4.0]
kappa = [1.2, 2.4]

[physics]
tail_s = 0.5

[outputs]
[[outputs.histories]]
label = "one"
record = "sine:amplitude_g=1.5,period_s=0.5,cycles=2,duration_s=2"
scale = 1.0
kappa = 1.2
"""


class Studies(Target):
    """Study files checked by `pcrf study --check`: the tiny study and the repository's
    studies that need no record files."""
    name = "study"
    suffix = ".toml"

    def __init__(self, source_dir):
        self.source_dir = source_dir

    def seeds(self, work):
        seeds = [("tiny", TINY_STUDY.encode(), [])]
        for name in ("demo.toml", "sensitivity.toml", "vertical.toml", "extremes.toml"):
            path = self.source_dir / "studies" / name
            if path.is_file() and b"files" not in path.read_bytes() and b"file =" not in path.read_bytes():
                seeds.append((name[:-5], path.read_bytes(), []))
        return seeds

    def command(self, pcrf, file, extra):
        return [pcrf, "study", str(file), "--check"]


def global_heaps(data):
    """[start, end) of each HDF5 global heap collection in a file: "GCOL", version 1, three
    reserved bytes, the collection's size (8 bytes, little-endian)."""
    ranges = []
    at = data.find(b"GCOL")
    while at >= 0:
        if data[at + 4:at + 5] == b"\x01":
            size = int.from_bytes(data[at + 8:at + 16], "little")
            if 16 <= size <= len(data) - at:
                ranges.append((at, at + size))
        at = data.find(b"GCOL", at + 1)
    return ranges


class Cubes(Target):
    """Cubes made by the tiny study, a few bytes changed, read by `cube info`, `export`
    and `stats`. With `spare_global_heaps`, no byte of a global heap collection is changed:
    HDF5 1.10 crashes on those itself (KNOWN_HDF5_FAULTS), which only a stack tells apart
    from a crash of pcrf's, and a smoke run must pass where no debugger is installed."""
    name = "cube"
    suffix = ".h5"
    commands = (["info"], ["export"], ["stats", "--by", "kappa", "-m", "theta_max_rad"], ["export", "--history", "one"])

    def __init__(self, pcrf, timeout_s, spare_global_heaps):
        self.pcrf, self.timeout_s = pcrf, timeout_s
        self.spare = spare_global_heaps
        self.avoid = ()

    def seeds(self, work):
        _, cube = make_seed_cube(self.pcrf, work, self.timeout_s, "seed.h5")
        if self.spare:
            self.avoid = global_heaps(cube.read_bytes())
        return [(f"c{i}", cube.read_bytes(), c) for i, c in enumerate(self.commands)]

    def mutate(self, rng, data):
        return mutate_binary(rng, data, hot_bytes=min(len(data), 16384), avoid=self.avoid)

    def command(self, pcrf, file, extra):
        return [pcrf, "cube", extra[0], str(file), *extra[1:]]


HAZARD_STUDY = """[study]
name = "fuzz_hazard"

[[records]]
synthetic = ["stochastic:seed=1,pga_g=1,duration_s=3", "stochastic:seed=2,pga_g=1,duration_s=3",
             "stochastic:seed=3,pga_g=1,duration_s=3"]

[intensity]
measure = "pga_g"

[ida]
start = 0.5
max_intensity = 6
max_runs = 6

[physics]
tail_s = 0.5
"""

STRIPES_STUDY = """[study]
name = "fuzz_stripes"

[[records]]
synthetic = ["stochastic:seed=1,pga_g=1,duration_s=3"]

[intensity]
measure = "pga_g"
hazard = "mutant.csv"
return_periods_yr = [475, 2475]
"""


def hazard_curve(points=6, k0=2.625e-4, k=3.0, low=0.05, high=3.0, scale=1.0):
    xs = [low * (high / low) ** (i / (points - 1)) for i in range(points)]
    return ("pga_g,annual_rate_per_yr\n" + "".join(f"{x * scale:.6g},{k0 * x ** -k:.6g}\n" for x in xs)).encode()


class Hazards(Target):
    """Hazard curves (CSV) read by `pcrf cube risk` against a tiny IDA cube, and by `pcrf study
    --check` as hazard-consistent stripes. The seeds are the findings of issue 41: a segment
    1e-6 wide with a decade of rate (an internal error before the integral was exact), a
    byte-order mark, a curve in cm/s² and one of 50-year probabilities under pga_g (both
    warned of), and the most points a curve may have (a 10⁵-point curve took minutes)."""
    name = "hazard"
    suffix = ".csv"

    def __init__(self, pcrf, timeout_s):
        self.pcrf, self.timeout_s = pcrf, timeout_s

    def seeds(self, work):
        (work / "stripes.toml").write_text(STRIPES_STUDY)
        make_seed_cube(self.pcrf, work, self.timeout_s, "seed.h5", study_text=HAZARD_STUDY)
        probabilities = "".join(f"{x:.6g},{-math.expm1(-50 * 2.625e-4 * x ** -3):.6g}\n"
                                for x in (0.05, 0.1, 0.2, 0.5, 1.0, 2.0))
        curves = [("power_law", hazard_curve()),
                  ("steep", b"pga_g,annual_rate_per_yr\n0.1,1e-2\n0.5,1e-3\n0.5000005,1e-4\n2,1e-6\n"),
                  ("bom", b"\xef\xbb\xbf" + hazard_curve()),
                  ("cm_s2", hazard_curve(scale=980.665)),
                  ("probabilities", ("pga_g,annual_rate_per_yr\n" + probabilities).encode()),
                  ("sa", b"# period_s = 1.0\nsa_g,annual_rate_per_yr\n0.1,1e-2\n1,1e-4\n"),
                  ("most_points", hazard_curve(points=10000, low=0.01, high=10.0))]
        return [(f"{label}_{how}", data, [how]) for label, data in curves for how in ("risk", "stripes")]

    def command(self, pcrf, file, extra):
        if extra[0] == "risk":
            return [pcrf, "cube", "risk", "seed.h5", "--hazard", str(file)]
        return [pcrf, "study", "stripes.toml", "--check"]


def make_seed_cube(pcrf, work, timeout_s, name, shard=None, study_text=TINY_STUDY):
    """The cube of `study_text` (the tiny study; shard K/N of it, when given) at WORK/NAME; its
    study file beside, as WORK/seed_study.toml."""
    study = work / "seed_study.toml"
    study.write_text(study_text)
    cube = work / name
    for leftover in (cube, Path(str(cube) + ".journal")):
        if leftover.exists():
            leftover.unlink()
    argv = [pcrf, "study", str(study), "-o", str(cube), "--progress-interval-s", "0"] + (["--shard", shard] if shard else [])
    done = subprocess.run(argv, capture_output=True, text=True, timeout=max(120, 10 * timeout_s), cwd=work)
    if done.returncode != 0 or not cube.is_file():
        raise RuntimeError(f"cannot make the seed cube: {done.stderr.strip()}")
    return study, cube


# The journal's format (src/io/include/pcrf/io/record_log.hpp, src/cube/include/pcrf/cube/cube_journal.hpp).
JOURNAL_MAGIC = b"pcrf-log"
HEADER, CASES, NOTES, HISTORY, COMMIT = 1, 2, 3, 4, 5


def frame(kind, payload):
    head = kind.to_bytes(4, "little") + len(payload).to_bytes(8, "little")
    return head + payload + zlib.crc32(payload, zlib.crc32(head)).to_bytes(4, "little")


def frames(data):
    """[(start, kind, payload)] of a journal's records, up to the first that does not fit."""
    out, at = [], len(JOURNAL_MAGIC)
    while at + 16 <= len(data):
        kind = int.from_bytes(data[at:at + 4], "little")
        size = int.from_bytes(data[at + 4:at + 12], "little")
        if at + 16 + size > len(data):
            break
        out.append((at, kind, data[at + 12:at + 12 + size]))
        at += 16 + size
    return out


def text_bytes(text):
    return len(text).to_bytes(4, "little") + text


def journal_of(journal_id, cases, metrics, checkpoints):
    """A journal extending the cube of `journal_id`: each checkpoint its records, then a commit."""
    data = JOURNAL_MAGIC + frame(HEADER, journal_id.to_bytes(8, "little", signed=True) + cases.to_bytes(8, "little") +
                                 metrics.to_bytes(4, "little"))
    for records in checkpoints:
        for kind, payload in records:
            data += frame(kind, payload)
        data += frame(COMMIT, b"")
    return data


def cases_payload(offsets, status, metrics, same_last=True):
    out = (0).to_bytes(8, "little") + len(offsets).to_bytes(4, "little")
    out += b"".join(o.to_bytes(4, "little") for o in offsets) + bytes(status & 0xff for _ in offsets)
    for m in range(metrics):
        if same_last and m == metrics - 1:
            out += b"\x01" + struct.pack("<d", 0.0)
        else:
            out += b"\x00" + b"".join(struct.pack("<d", 1e-3 * (o + m)) for o in offsets)
    return out


def history_payload(name, rows):
    out = text_bytes(name) + (1).to_bytes(4, "little") + text_bytes(b"case_index") + b"\x02" + (5).to_bytes(8, "little")
    out += (2).to_bytes(4, "little")
    for column in (b"t_s", b"theta_rad"):
        out += text_bytes(column) + text_bytes(b"s" if column == b"t_s" else b"rad") + text_bytes(b"")
        out += rows.to_bytes(8, "little") + b"".join(struct.pack("<d", 0.01 * k) for k in range(rows))
    return out


class Journals(Target):
    """Journals beside the tiny study's first shard, made by this harness in the journal's
    format with the cube's id: read by `cube info`, replayed by `study --resume` and checked
    by `cube merge`. Mutants change bytes (a damaged journal: torn at its first bad CRC), cut
    it, or change a record's payload and fix its CRC (a forged journal, which the engine must
    check against the cube's layout and set aside on --resume)."""
    name = "journal"
    suffix = ".h5.journal"
    commands = (["info"], ["resume"], ["merge"])

    def __init__(self, pcrf, timeout_s):
        self.pcrf, self.timeout_s = pcrf, timeout_s

    def seeds(self, work):
        self.study, self.cube = make_seed_cube(self.pcrf, work, self.timeout_s, "seed_shard.h5", "1/2")
        info = json.loads(subprocess.run([self.pcrf, "cube", "info", "--json", str(self.cube)], capture_output=True,
                                         text=True, timeout=60, check=True).stdout)
        journal_id = int(info["attributes"]["journal_id"])
        cases = math.prod(d["size"] for d in info["dimensions"])
        metrics = len(info["metrics"])
        rest = list(range(cases // 2, cases))  # the second shard's cases, not in this cube
        notes = (1).to_bytes(4, "little") + rest[0].to_bytes(8, "little") + text_bytes(b"a note")
        one = journal_of(journal_id, cases, metrics, [[(CASES, cases_payload(rest, 0, metrics)), (NOTES, notes),
                                                       (HISTORY, history_payload(b"h_fuzz", 3))]])
        two = journal_of(journal_id, cases, metrics, [[(CASES, cases_payload(rest[:1], 0, metrics))],
                                                      [(CASES, cases_payload(rest[1:], 0, metrics, False)),
                                                       (HISTORY, history_payload(b"h_empty", 0))]])
        return [(f"j{i}{c[0]}", journal, c) for i, journal in enumerate((one, two)) for c in self.commands]

    def mutate(self, rng, data):
        how = rng.randrange(4)
        if how == 0:  # damaged bytes: the first bad CRC ends what is read
            return mutate_binary(rng, data, hot_bytes=len(data))
        if how == 1:  # torn, or with junk after its end
            return data[:rng.randrange(len(data))] if rng.random() < 0.7 else data + insert_junk(rng, b"")
        records = frames(data)
        start, kind, payload = rng.choice(records)
        if how == 2:  # a forged record: its payload changed, its CRC made to match
            changed = mutate_binary(rng, payload, hot_bytes=len(payload)) if payload else payload
            if payload and rng.random() < 0.3:
                at = rng.randrange(max(1, len(payload) - 8))
                changed = payload[:at] + rng.choice([b"\xff" * 8, b"\x00" * 8, b"\x80" * 8]) + payload[at + 8:]
            new_kind = kind if rng.random() < 0.9 else rng.randrange(8)
            return data[:start] + frame(new_kind, changed) + data[start + 16 + len(payload):]
        # a record declaring a huge size: more than the file has (a torn tail), never allocated
        huge = rng.choice([1 << 36, 1 << 62, len(data) * 2])
        return data[:start + 4] + huge.to_bytes(8, "little") + data[start + 12:]

    def command(self, pcrf, file, extra):
        cube = Path(str(file)[:-len(".journal")])
        shutil.copyfile(self.cube, cube)  # --resume folds the cube: each mutant starts from the seed
        for aside in cube.parent.glob(cube.name + ".journal.set-aside-*"):
            aside.unlink()
        if extra[0] == "info":
            return [pcrf, "cube", "info", str(cube)]
        if extra[0] == "resume":
            return [pcrf, "study", str(self.study), "-o", str(cube), "--resume", "--shard", "1/2", "--progress-interval-s", "0"]
        return [pcrf, "cube", "merge", str(cube), "-o", str(cube.parent / "merged.h5"), "--overwrite", "--allow-missing"]


class Merges(Target):
    """`cube merge` of the tiny study's two shards, the first one's bytes changed (as the
    cube target's); the merged cube is written beside."""
    name = "merge"
    suffix = ".h5"

    def __init__(self, pcrf, timeout_s, spare_global_heaps):
        self.pcrf, self.timeout_s = pcrf, timeout_s
        self.spare = spare_global_heaps
        self.avoid = ()

    def seeds(self, work):
        _, first = make_seed_cube(self.pcrf, work, self.timeout_s, "part1.h5", "1/2")
        _, self.second = make_seed_cube(self.pcrf, work, self.timeout_s, "part2.h5", "2/2")
        if self.spare:
            self.avoid = global_heaps(first.read_bytes())
        return [("m0", first.read_bytes(), [])]

    def mutate(self, rng, data):
        return mutate_binary(rng, data, hot_bytes=min(len(data), 16384), avoid=self.avoid)

    def command(self, pcrf, file, extra):
        return [pcrf, "cube", "merge", str(file), str(self.second), "-o", str(file.parent / "merged.h5"), "--overwrite"]


# ---- running --------------------------------------------------------------------------------

# Faults inside HDF5 1.10 itself on crafted files, which no cheap check of pcrf's avoids
# (docs/robustness.md): HDF5 trusts the object sizes of a global heap collection (where
# variable-length data lives: text values, dimension-scale lists), reads past it in
# H5HG_read and later frees a corrupted cache entry when the file is closed. A crash whose
# innermost HDF5 frames include one of these is counted as a known HDF5 fault, not a finding
# of pcrf's; any other crash is a finding.
KNOWN_HDF5_FAULTS = ("H5HG_read", "H5HG__protect", "H5C__flush_single_entry")
FRAME = re.compile(r"^\s*#\d+\s+(?:0x[0-9a-f]+\s+)?in\s+(\S+)(.*)$")
SYSTEM_FRAME = re.compile(r"libc\.so|libstdc\+\+|libgcc|libasan|libubsan|ld-linux|\bat \./|\bat \.\./|"
                          r"^__|^raise$|^abort$|^malloc_printerr$|^_int_free$|^memmove$|^memcpy$|^free$")


def crash_frames(argv, stderr, cwd):
    """The crash's stack, innermost first: from a sanitizer's report, else from gdb where
    installed; [] when neither tells."""
    text = stderr
    if not any(FRAME.match(line) for line in text.splitlines()) and shutil.which("gdb"):
        try:
            text = subprocess.run(["gdb", "-batch", "-nx", "-ex", "run", "-ex", "bt", "--args", *argv],
                                  capture_output=True, text=True, timeout=120, cwd=cwd).stdout
        except subprocess.TimeoutExpired:
            return []
    return [(m.group(1), m.group(2)) for m in map(FRAME.match, text.splitlines()) if m]


def known_hdf5_fault(frames):
    """The known HDF5 fault a crash's stack shows, or None: its innermost frames not of the C
    runtime are HDF5's, and one of them names a fault of KNOWN_HDF5_FAULTS."""
    own = [(name, where) for name, where in frames if not (SYSTEM_FRAME.search(name) or SYSTEM_FRAME.search(where))]
    hdf5 = []
    for name, where in own:
        if "libhdf5" not in where:
            break
        hdf5.append(name)
    return next((name for name in hdf5 if name in KNOWN_HDF5_FAULTS), None)


def judge(returncode, stderr):
    """The problem with one run's outcome, or None when it keeps the rule."""
    if returncode is None:
        return "hang"
    if SANITIZER.search(stderr):
        return "sanitizer report"
    if returncode < 0:
        return f"signal {-returncode}"
    if "internal error" in stderr:
        return "internal error"
    if returncode not in (0, 2):
        return f"exit {returncode}"
    if returncode == 2:
        errors = [line for line in stderr.splitlines() if ERROR_LINE.match(line)]
        if len(errors) != 1:
            return f"exit 2 with {len(errors)} error lines"
    return None


def run_one(argv, timeout_s, cwd):
    try:
        done = subprocess.run(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, timeout=timeout_s, cwd=cwd)
        return done.returncode, done.stderr.decode("utf-8", "replace")
    except subprocess.TimeoutExpired as e:
        return None, (e.stderr or b"").decode("utf-8", "replace")


def campaign(target, args, work, budget_s):
    """Runs mutants of `target` until its budget is spent; returns (counts, findings)."""
    folder = work / target.name
    folder.mkdir(parents=True, exist_ok=True)
    seeds = target.seeds(folder)
    rng = random.Random(f"{args.seed}/{target.name}")
    counts = {"runs": 0, "exit 0": 0, "exit 2": 0, "hdf5": 0, "findings": 0}
    findings, known = [], []
    end = time.monotonic() + budget_s
    k = 0
    while time.monotonic() < end and (args.runs is None or k < args.runs):
        label, seed, extra = seeds[k % len(seeds)] if k < len(seeds) else rng.choice(seeds)
        data = seed if k < len(seeds) else target.mutate(rng, seed)  # the seeds themselves first
        mutant = folder / f"mutant{target.suffix}"
        mutant.write_bytes(data)
        argv = target.command(args.pcrf, mutant, extra)
        returncode, stderr = run_one(argv, args.timeout_s, folder)
        counts["runs"] += 1
        if returncode in (0, 2):
            counts[f"exit {returncode}"] += 1
        problem = judge(returncode, stderr)
        if problem is not None and problem != "hang" and not problem.startswith("exit"):
            fault = known_hdf5_fault(crash_frames(argv, stderr, folder))
            if fault is not None:
                counts["hdf5"] += 1
                known.append(f"{target.name} mutant {k} ({label}): {problem} in HDF5's {fault}")
                problem = None
        if problem is not None:
            counts["findings"] += 1
            kept = args.out / f"{target.name}-{k}{target.suffix}"
            args.out.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(mutant, kept)
            shown = " ".join(str(kept) if a == str(mutant) else a for a in argv)
            (args.out / f"{target.name}-{k}.txt").write_text(
                f"{problem}\nseed {args.seed}, mutant {k} of {label}\ncommand: {shown}\n--- stderr\n{stderr[-4000:]}")
            findings.append(f"{target.name} mutant {k} ({label}): {problem}: {shown}")
        k += 1
    return counts, findings, known


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--pcrf", required=True, help="the pcrf executable to fuzz")
    parser.add_argument("--budget-s", type=float, default=600.0, help="time for all targets together [s]")
    parser.add_argument("--seed", type=int, default=1, help="seed of the mutations (deterministic per seed)")
    parser.add_argument("--runs", type=int, help="at most this many inputs per target (default: until the budget)")
    parser.add_argument("--targets", default="records,synthetic,study,cube,hazard,python,journal,merge", help="comma-separated targets")
    parser.add_argument("--module-dir", type=Path,
                        help="python: the folder holding the module `pcrf` (default: python/ beside --pcrf)")
    parser.add_argument("--timeout-s", type=float, default=20.0, help="a run longer than this is a hang [s]")
    parser.add_argument("--work", type=Path, default=Path("fuzz-work"), help="folder for seeds and mutants")
    parser.add_argument("--spare-global-heaps", action="store_true",
                        help="cubes: change no byte of an HDF5 global heap (HDF5 1.10 crashes there itself)")
    parser.add_argument("--out", type=Path, help="folder for the findings (default: WORK/findings)")
    args = parser.parse_args()
    args.pcrf = str(Path(args.pcrf).resolve())
    args.work = args.work.resolve()
    args.out = (args.out or args.work / "findings").resolve()
    source_dir = Path(__file__).resolve().parents[2]
    targets = {"records": lambda: Records(), "synthetic": lambda: Synthetic(), "study": lambda: Studies(source_dir),
             "cube": lambda: Cubes(args.pcrf, args.timeout_s, args.spare_global_heaps),
             "hazard": lambda: Hazards(args.pcrf, args.timeout_s),
             "python": lambda: PythonContainers(args.module_dir),
             "journal": lambda: Journals(args.pcrf, args.timeout_s),
             "merge": lambda: Merges(args.pcrf, args.timeout_s, args.spare_global_heaps)}
    names = [n for n in args.targets.split(",") if n]
    unknown = [n for n in names if n not in targets]
    if unknown or not names or args.budget_s <= 0:
        parser.error(f"--targets: choose among {', '.join(targets)}" if unknown or not names else "--budget-s: must be > 0")
    if not os.access(args.pcrf, os.X_OK):
        parser.error(f"--pcrf: {args.pcrf} is not an executable")
    args.module_dir = (args.module_dir or Path(args.pcrf).parent / "python").resolve()
    if "python" in names and not module_available(args.module_dir):
        print(f"fuzz: python: no module pcrf in {args.module_dir} (a build without it): target left out")
        names.remove("python")
    args.work.mkdir(parents=True, exist_ok=True)
    if args.out.exists():
        shutil.rmtree(args.out)
    print(f"fuzz: {args.pcrf}, seed {args.seed}, {args.budget_s:g} s over {', '.join(names)}", flush=True)
    print(f"{'target':<10} {'runs':>6} {'exit 0':>7} {'exit 2':>7} {'HDF5 faults':>12} {'findings':>9}")
    all_findings, all_known = [], []
    start = time.monotonic()
    for i, name in enumerate(names):
        share = (args.budget_s - (time.monotonic() - start)) / (len(names) - i)  # what the others left
        counts, findings, known_faults = campaign(targets[name](), args, args.work, share)
        print(f"{name:<10} {counts['runs']:>6} {counts['exit 0']:>7} {counts['exit 2']:>7} {counts['hdf5']:>12} "
              f"{counts['findings']:>9}", flush=True)
        all_findings += findings
        all_known += known_faults
    for line in all_known:
        print("known HDF5 fault (docs/robustness.md):", line)
    for line in all_findings:
        print("FINDING:", line)
    if all_findings:
        print(f"fuzz: {len(all_findings)} findings, inputs and commands in {args.out}")
    return 1 if all_findings else 0


if __name__ == "__main__":
    sys.exit(main())
