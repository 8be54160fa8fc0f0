"""pcrf.Frame and pcrf.record_measures against `pcrf frame --json` and `pcrf record`."""

import numpy as np
import pytest

import pcrf
from conftest import cli_json, same_value


@pytest.mark.parametrize("parameters", [{}, {"kappa": 2.5, "tan_alpha": 0.25}, {"pi_e_c": 0.0}])
def test_frame_is_what_pcrf_frame_prints(parameters):
    flags = [x for k, v in parameters.items() for x in ("--" + k.replace("_", "-"), str(v))]
    expected = cli_json("frame", "--json", *flags)
    frame = pcrf.Frame(**parameters)
    for key, value in frame.properties.items():
        assert same_value(expected[key], value), key
        assert getattr(frame, key) == value or value != value
    assert frame.threshold == expected["uplift_threshold_g"]
    assert frame.fracture_tendon == expected["fracture_tendon"]
    np.testing.assert_array_equal(frame.pushover_theta_rad, expected["pushover_theta_rad"])
    np.testing.assert_array_equal(frame.pushover_accel_g, expected["pushover_accel_g"])
    for key, value in parameters.items():
        assert frame.parameters[key] == value


def test_frame_points_and_fracture_strain():
    expected = cli_json("frame", "--json", "--points", "7", "--fracture-strain", "0.02")
    frame = pcrf.Frame(points=7, fracture_strain=0.02)
    assert len(frame.pushover_theta_rad) == 7
    np.testing.assert_array_equal(frame.pushover_accel_g, expected["pushover_accel_g"])
    assert frame.fracture_angle_rad == expected["fracture_angle_rad"]


def test_basic_model_numbers():
    """README: p = 2.12 rad/s, uplift threshold 1.021 g for the basic model."""
    frame = pcrf.Frame()
    assert round(frame.frequency_parameter_rad_s, 2) == 2.12
    assert round(frame.threshold, 3) == 1.021


def test_record_measures_are_what_pcrf_record_prints(paper):
    for record in paper[:3]:
        expected = cli_json("record", record, "--period", "0.5", "--period", "1")
        assert pcrf.record_measures(record, periods_s=[0.5, 1.0]) == expected


def test_record_measures_of_a_pair(station):
    h1, h2, up = station
    expected = cli_json("record", h1, "--pair", h2, "--up", up, "--period", "0.3")
    assert pcrf.record_measures(h1, record_h2=h2, record_up=up, periods_s=0.3) == expected
