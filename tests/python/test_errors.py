"""Bad keywords, values and files raise pcrf.InputError (a ValueError) naming the keyword
(``tail_s=``) where the command line names the flag (``--tail-s``), with the same problem."""

import pytest

import pcrf
from conftest import cli_error

SINE = "sine:amplitude_g=1.5,period_s=0.5,cycles=2"


@pytest.mark.parametrize("keywords, flags, key", [
    ({"tail_s": -1}, ["--tail-s", "-1"], "tail_s"),
    ({"preset": "bogus"}, ["--preset", "bogus"], "preset"),
    ({"rtol": "abc"}, ["--rtol", "abc"], "rtol"),
    ({"stop_at_samples": "maybe"}, ["--stop-at-samples=maybe"], "stop_at_samples"),
    ({"max_steps": 2.5}, ["--max-steps", "2.5"], "max_steps"),
    ({"theta0_rad": -3.0}, ["--theta0-rad", "-3"], "theta0_rad"),
    ({"frame": {"kappa": -1}}, ["--kappa", "-1"], "kappa"),
    ({"model": "block", "frame": {"size_m": -1}}, ["--model", "block", "--size-m", "-1"], "size_m"),
])
def test_a_bad_value_names_the_keyword_with_the_command_lines_problem(keywords, flags, key):
    flag = "--" + key.replace("_", "-")
    expected = cli_error("run", "--synthetic", SINE, *flags)
    assert expected.startswith(flag + ": ")
    with pytest.raises(pcrf.InputError) as error:
        pcrf.run(synthetic=SINE, **keywords)
    assert error.value.key == key
    assert str(error.value) == key + "=: " + expected[len(flag) + 2:]


@pytest.mark.parametrize("keywords, flags, cli, message", [
    ({"intensity": 1.0, "scale": 2.0}, ["--intensity", "1", "--scale", "2"],
     "give either --scale or --intensity, not both", "give either scale= or intensity=, not both"),
    ({"measure": "sa_g"}, ["--measure", "sa_g"], "--measure, --period-s and --damping go with --intensity VALUE",
     "measure=, period_s= and damping= go with intensity= VALUE"),
])
def test_keys_named_inside_a_problem_are_keywords_too(keywords, flags, cli, message):
    assert cli_error("run", "--synthetic", SINE, *flags) == cli
    with pytest.raises(pcrf.InputError) as error:
        pcrf.run(synthetic=SINE, **keywords)
    assert str(error.value) == message and error.value.key is None


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
    with pytest.raises(pcrf.InputError, match=r"^tail=: unknown keyword \(did you mean tail_s=\?\)$"):
        pcrf.run(synthetic=SINE, tail=1)
    with pytest.raises(pcrf.InputError, match='^kapa=: does not apply to model "pcrf" \\(its parameters: kappa=, '):
        pcrf.run(synthetic=SINE, frame={"kapa": 2})
    with pytest.raises(pcrf.InputError, match="^kapa=: unknown keyword"):
        pcrf.Frame(kapa=2)


def test_arrays_are_checked():
    with pytest.raises(ValueError, match="needs dt_s"):
        pcrf.run([0.0, 1.0])
    with pytest.raises(ValueError, match="one-dimensional"):
        pcrf.run([[0.0, 1.0]], 0.01)
    with pytest.raises(ValueError, match="ground_accel_g"):
        pcrf.run([0.0, float("nan")], 0.01)


def test_the_errors_are_value_errors():
    assert issubclass(pcrf.InputError, ValueError) and not hasattr(pcrf, "StudyError")


def test_a_scene_parameter_of_another_model_or_an_unknown_model_is_named():
    with pytest.raises(pcrf.InputError, match='^kappa=: does not apply to model "block"'):
        pcrf.run(synthetic=SINE, model="block", frame={"kappa": 2})
    with pytest.raises(pcrf.InputError, match="^model=: unknown scene 'blok'"):
        pcrf.run(synthetic=SINE, model="blok")
    # the same check as `pcrf run --model block --size-m 1 --frequency-parameter-rad-s 2`
    both = ["--size-m", "1", "--frequency-parameter-rad-s", "2"]
    expected = "give either size_m= or frequency_parameter_rad_s=, not both"
    assert cli_error("run", "--synthetic", SINE, "--model", "block", *both) == \
        "give either --size-m or --frequency-parameter-rad-s, not both"
    with pytest.raises(pcrf.InputError) as error:
        pcrf.run(synthetic=SINE, model="block", frame={"size_m": 1, "frequency_parameter_rad_s": 2})
    assert str(error.value) == expected
