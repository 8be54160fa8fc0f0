"""Shared fixtures of the Python module's tests: the pcrf executable beside the module, the
PEER records (../shared/records beside the checkout, PCRF_RECORDS_DIR overrides; tests that
need them skip when absent), and the command line's answers to compare with."""

import json
import os
import subprocess
from pathlib import Path

import pytest

SOURCE_DIR = Path(__file__).resolve().parents[2]


def pcrf_executable():
    return os.environ.get("PCRF_EXECUTABLE") or str(SOURCE_DIR / "build" / "pcrf")


def records_dir():
    path = Path(os.environ.get("PCRF_RECORDS_DIR") or SOURCE_DIR.parent / "shared" / "records")
    return path if path.is_dir() else None


def paper_records():
    base = records_dir()
    if base is None or not (base / "paper").is_dir():
        return []
    return sorted((base / "paper").glob("*.AT2"))


@pytest.fixture
def paper():
    records = paper_records()
    if not records:
        pytest.skip("no PEER records (../shared/records/paper)")
    return records


@pytest.fixture
def station():
    """A station's three components: Imperial Valley 1979, Bonds Corner (RSN160)."""
    base = records_dir()
    files = [base / "peer_at2_seiswave" / "RSN160_IMPVALL.H_H-BCR140.AT2",
             base / "peer_at2_seiswave" / "RSN160_IMPVALL.H_H-BCR230.AT2",
             base / "vertical_hsiifu3" / "RSN160_IMPVALL.H_H-BCR-UP.AT2"] if base else []
    if not files or not all(f.is_file() for f in files):
        pytest.skip("no station records (RSN160)")
    return files


def cli(*arguments, check=True):
    """Runs build/pcrf; returns (exit code, stdout, stderr)."""
    done = subprocess.run([pcrf_executable(), *map(str, arguments)], capture_output=True, text=True)
    if check and done.returncode != 0:
        raise AssertionError(f"pcrf {' '.join(map(str, arguments))}: {done.stderr}")
    return done.returncode, done.stdout, done.stderr


def cli_json(*arguments):
    return json.loads(cli(*arguments)[1])


def cli_error(*arguments):
    """The command line's message for bad input: its one line without 'pcrf: error: '."""
    code, _, stderr = cli(*arguments, check=False)
    assert code == 2, stderr
    line = stderr.strip().splitlines()[-1]
    assert line.startswith("pcrf: error: "), line
    return line.removeprefix("pcrf: error: ")


def same_value(a, b):
    """Equal bit for bit: the command line writes the shortest text that reads back as the same
    double (0.0 as 0); its null is the module's NaN."""
    if a is None:
        return isinstance(b, float) and b != b
    return a == b


def in_keywords(message, *keys):
    """A command-line message as Python spells it: the flag of each key (--reduce-over) as
    its keyword (reduce_over=), the problem itself the same."""
    for key in sorted(keys, key=len, reverse=True):
        message = message.replace("--" + key.replace("_", "-"), key + "=")
    return message
