"""Counts and intervals from input are checked by the same code for both front ends (issue 41,
item 2): pcrf.Frame(points=…) and pcrf.run(history_dt_s=…) refuse what `pcrf frame --points` and
`pcrf run --history-dt-s` refuse, with the same problem, named by keyword."""

import pytest

import pcrf
from conftest import cli_error, in_keywords


@pytest.mark.parametrize("points", ["1e9", "1", "2.5"])
def test_frame_points_out_of_bounds_are_the_command_lines_refusal(points):
    expected = cli_error("frame", "--points", points)
    with pytest.raises(pcrf.InputError) as error:
        pcrf.Frame(points=float(points))
    assert str(error.value) == in_keywords(expected, "points") != expected


def test_a_history_interval_beyond_its_bound_is_refused_before_the_case():
    pulse = "sine:amplitude_g=1.5,period_s=0.5,cycles=2"
    expected = cli_error("run", "--synthetic", pulse, "--tail-s", "0.5", "--history", "unused.csv",
                         "--history-dt-s", "1e-12")
    with pytest.raises(pcrf.InputError) as error:
        pcrf.run(synthetic=pulse, tail_s=0.5, history="numpy", history_dt_s=1e-12)
    assert str(error.value) == in_keywords(expected, "history_dt_s") != expected
