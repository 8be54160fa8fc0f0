"""Ranks' parts beside a cube (issue 38, docs/checkpoint.md): what `pcrf cube info` says of
them on stderr, pcrf.open_cube warns and pcrf.cube_info's notes hold, word for word."""

import warnings

import pcrf
from pcrf import _pcrf
from conftest import cli

STUDY = """[[records]]
synthetic = ["sine:amplitude_g=1.5,period_s=0.5,cycles=2,duration_s=2"]
[axes]
kappa = [1.2, 2.4]
"""


def test_a_part_beside_the_cube_is_said_by_every_reader(tmp_path):
    study = tmp_path / "p.toml"
    study.write_text(STUDY)
    cube = tmp_path / "c.h5"
    cli("study", study, "-o", cube)
    (tmp_path / "c.h5.part-3").write_bytes(b"not a part of any cube")  # no log at all: foreign
    _, _, stderr = cli("cube", "info", cube)
    said = [line.removeprefix("pcrf cube info: ") for line in stderr.splitlines()
            if line.startswith("pcrf cube info: ")]
    parts = [line for line in said if "c.h5.part-3" in line]
    assert parts and "is not a part of this cube (--resume sets it aside)" in parts[0], stderr
    _, notes = _pcrf.cube_info(str(cube))
    assert parts[0] in notes
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        pcrf.open_cube(cube).close()
    assert parts[0] in [str(w.message) for w in caught]
