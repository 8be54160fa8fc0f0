"""pcrf.Frame and pcrf.record_measures against `pcrf frame --json` and `pcrf record`."""

import numpy as np
import pytest

import pcrf
from conftest import cli_error, cli_json, same_value, in_keywords


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


def flags_of(parameters):
    return [x for k, v in parameters.items() for x in ("--" + k.replace("_", "-"), str(v))]


@pytest.mark.parametrize("model,parameters", [
    ("pcrf", {}), ("block", {}), ("rocking-frame", {}), ("block", {"slenderness_rad": 0.2, "frequency_parameter_rad_s": 2.5}),
    ("rocking-frame", {"slenderness_rad": 0.15, "size_m": 2, "beam_mass_ratio": 0.5})])
def test_every_scene_is_what_pcrf_frame_model_prints(model, parameters):
    """The scene comes from the catalogue for both: every property, the pushover arrays."""
    expected = cli_json("frame", "--model", model, "--json", *flags_of(parameters))
    frame = pcrf.Frame(model=model, **parameters)
    assert frame.model == model
    assert set(frame.properties) | {"fracture_tendon", "pushover_theta_rad", "pushover_accel_g"} == set(expected)
    for key, value in frame.properties.items():
        assert same_value(expected[key], value), key
    assert frame.fracture_tendon == expected["fracture_tendon"]
    np.testing.assert_array_equal(frame.pushover_theta_rad, expected["pushover_theta_rad"])
    np.testing.assert_array_equal(frame.pushover_accel_g, expected["pushover_accel_g"])
    for key, value in parameters.items():
        assert frame.parameters[key] == value


def test_a_frame_of_any_scene_solves_as_that_scene():
    """Frame.parameters given again make the same scene (of two exclusive keys, the one given)."""
    sine = "sine:amplitude_g=0.6,period_s=0.5,cycles=2"
    frame = pcrf.Frame(model="block", slenderness_rad=0.2, frequency_parameter_rad_s=2.5)
    assert "size_m" not in frame.parameters
    direct = pcrf.run(synthetic=sine, model="block", frame={"slenderness_rad": 0.2, "frequency_parameter_rad_s": 2.5},
                      tail_s=1)
    again = pcrf.run(synthetic=sine, frame=frame, tail_s=1)
    for key, value in direct.items():
        assert key == "cpu_time_s" or value == again[key] or (value != value and again[key] != again[key]), key
    with pytest.raises(ValueError, match="frame= is a pcrf.Frame of model 'block'"):
        pcrf.run(synthetic=sine, frame=frame, model="pcrf")


@pytest.mark.parametrize("model,parameters", [
    ("block", {"kappa": 2}), ("pcrf", {"size_m": 1}), ("rocking-frame", {"beam_mass_ratio": -1}),
    ("block", {"beam_mass_ratio": 0.5}), ("block", {"slenderness_rad": 1.6}), ("block", {"given_restitution": 1.5}),
    ("block", {"size_m": 1, "frequency_parameter_rad_s": 2}), ("pcrf", {"kappa": -1})])
def test_a_bad_scene_parameter_is_the_command_lines_message_naming_the_keyword(model, parameters):
    flags = flags_of(parameters)
    flags = [f if f != "--given-restitution" else "--restitution" for f in flags]  # the older spelling
    expected = cli_error("frame", "--model", model, *flags)
    with pytest.raises(pcrf.InputError) as error:
        pcrf.Frame(model=model, **parameters)
    assert str(error.value) == in_keywords(expected, *parameters) != expected


def test_frame_points_and_fracture_strain():
    expected = cli_json("frame", "--json", "--points", "7", "--fracture-strain", "0.02")
    frame = pcrf.Frame(points=7, fracture_strain=0.02)
    assert len(frame.pushover_theta_rad) == 7
    np.testing.assert_array_equal(frame.pushover_accel_g, expected["pushover_accel_g"])
    assert frame.fracture_angle_rad == expected["fracture_angle_rad"]


def test_basic_model_numbers():
    """docs/commands/frame.md: p = 2.12 rad/s, uplift threshold 1.021 g for the basic model."""
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
