"""Bad keywords, values and files raise ValueError with the command line's message."""

import pytest

import pcrf
from conftest import cli_error

SINE = "sine:amplitude_g=1.5,period_s=0.5,cycles=2"


@pytest.mark.parametrize("keywords, flags", [
    ({"tail_s": -1}, ["--tail-s", "-1"]),
    ({"preset": "bogus"}, ["--preset", "bogus"]),
    ({"rtol": "abc"}, ["--rtol", "abc"]),
    ({"stop_at_samples": "maybe"}, ["--stop-at-samples=maybe"]),
    ({"max_steps": 2.5}, ["--max-steps", "2.5"]),
    ({"theta0_rad": -3.0}, ["--theta0-rad", "-3"]),
    ({"frame": {"kappa": -1}}, ["--kappa", "-1"]),
    ({"intensity": 1.0, "scale": 2.0}, ["--intensity", "1", "--scale", "2"]),
    ({"measure": "sa_g"}, ["--measure", "sa_g"]),
])
def test_bad_values_have_the_command_lines_message(keywords, flags):
    expected = cli_error("run", "--synthetic", SINE, *flags)
    with pytest.raises(ValueError) as error:
        pcrf.run(synthetic=SINE, **keywords)
    assert str(error.value) == expected


def test_a_bad_file_has_the_command_lines_message(tmp_path):
    missing = tmp_path / "missing.AT2"
    broken = tmp_path / "broken.AT2"
    broken.write_text("not a record\n")
    for path in (missing, broken):
        expected = cli_error("run", "--record", path)
        with pytest.raises(ValueError) as error:
            pcrf.run(record=path)
        assert str(error.value) == expected
        with pytest.raises(ValueError) as error:
            pcrf.record_measures(path)
        assert str(error.value) == cli_error("record", path)


def test_an_unknown_keyword_is_named_with_a_suggestion():
    with pytest.raises(ValueError, match=r"unknown keyword 'tail' \(did you mean 'tail_s'\?\)"):
        pcrf.run(synthetic=SINE, tail=1)
    with pytest.raises(ValueError, match='kapa does not apply to model "pcrf"'):
        pcrf.run(synthetic=SINE, frame={"kapa": 2})
    with pytest.raises(ValueError, match="unknown keyword 'kapa'"):
        pcrf.Frame(kapa=2)


def test_arrays_are_checked():
    with pytest.raises(ValueError, match="needs dt_s"):
        pcrf.run([0.0, 1.0])
    with pytest.raises(ValueError, match="one-dimensional"):
        pcrf.run([[0.0, 1.0]], 0.01)
    with pytest.raises(ValueError, match="ground_accel_g"):
        pcrf.run([0.0, float("nan")], 0.01)


def test_the_errors_are_value_errors():
    assert issubclass(pcrf.InputError, ValueError) and issubclass(pcrf.StudyError, ValueError)


def test_a_scene_parameter_of_another_model_or_an_unknown_model_is_named():
    with pytest.raises(ValueError, match='kappa does not apply to model "block"'):
        pcrf.run(synthetic=SINE, model="block", frame={"kappa": 2})
    with pytest.raises(ValueError, match="model: unknown scene 'blok'"):
        pcrf.run(synthetic=SINE, model="blok")
    # the same check as `pcrf run --model block --size-m 1 --frequency-parameter-rad-s 2`
    both = ["--size-m", "1", "--frequency-parameter-rad-s", "2"]
    expected = cli_error("run", "--synthetic", SINE, "--model", "block", *both)
    with pytest.raises(ValueError) as error:
        pcrf.run(synthetic=SINE, model="block", frame={"size_m": 1, "frequency_parameter_rad_s": 2})
    assert str(error.value) == expected
