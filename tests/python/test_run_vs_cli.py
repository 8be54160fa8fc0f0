"""pcrf.run against `pcrf run` on the paper's records: every metric equal, bit for bit."""

import numpy as np

import pcrf
from conftest import cli, cli_json, same_value

NOT_COMPARED = {"cpu_time_s"}  # the CPU clock, not the case


def assert_same_record(module, command_line):
    assert list(module) == list(command_line)  # the same keys in the same order
    for key, value in command_line.items():
        if key in NOT_COMPARED:
            continue
        assert same_value(value, module[key]), f"{key}: pcrf run {value!r}, pcrf.run {module[key]!r}"


def read_at2(path):
    """The accelerations [g] and dt of a PEER .AT2 file in its NPTS=, DT= header form."""
    lines = path.read_text().splitlines()
    header = lines[3].replace(",", " ").split()
    dt_s = float(header[header.index("DT=") + 1]) if "DT=" in header else float(header[1])
    values = [float(v) for line in lines[4:] for v in line.split()]
    return np.array(values), dt_s


def test_every_paper_record_as_a_file(paper):
    for record in paper:
        for preset in ("balanced", "reference"):
            expected = cli_json("run", "--record", record, "--scale", "2.5", "--preset", preset)
            got = pcrf.run(record=record, scale=2.5, preset=preset)
            assert_same_record(got, expected)


def test_an_array_read_from_the_file_is_the_same_case(paper):
    record = paper[0]
    accel_g, dt_s = read_at2(record)
    expected = cli_json("run", "--record", record, "--scale", "2.5")
    got = pcrf.run(accel_g, dt_s, scale=2.5)
    for key, value in expected.items():
        if key not in NOT_COMPARED:
            assert same_value(value, got[key]), key


def test_settings_and_frame_as_keywords(paper):
    record = paper[1]
    expected = cli_json("run", "--record", record, "--scale", "3", "--kappa", "2.5", "--tail-s", "2",
                        "--rtol", "1e-8", "--no-stop-at-samples", "--integrator", "cvode-bdf")
    got = pcrf.run(record=record, scale=3, frame={"kappa": 2.5}, tail_s=2, rtol=1e-8, stop_at_samples=False,
                   integrator="cvode-bdf")
    assert_same_record(got, expected)
    assert_same_record(pcrf.run(record=record, scale=3, frame=pcrf.Frame(kappa=2.5), tail_s=2, rtol=1e-8,
                                stop_at_samples=False, integrator="cvode-bdf"), expected)


def test_intensity_scaling(paper):
    record = paper[2]
    expected = cli_json("run", "--record", record, "--intensity", "1.2", "--measure", "sa_g", "--period-s", "0.5")
    assert_same_record(pcrf.run(record=record, intensity=1.2, measure="sa_g", period_s=0.5), expected)


def test_history_equals_the_csv(paper, tmp_path):
    record = paper[3]
    csv = tmp_path / "h.csv"
    expected = cli_json("run", "--record", record, "--scale", "2.5", "--history", csv, "--history-dt-s", "0.01")
    result, history = pcrf.run(record=record, scale=2.5, history="numpy", history_dt_s=0.01)
    assert_same_record(result, expected)
    table = np.genfromtxt(csv, delimiter=",", names=True)
    assert history.dtype.names == table.dtype.names
    assert len(history) == len(table) > 100
    for name in table.dtype.names:
        np.testing.assert_array_equal(history[name], table[name], err_msg=name)
    frame = pcrf.run(record=record, scale=2.5, history="pandas", history_dt_s=0.01)[1]
    assert list(frame.columns) == list(table.dtype.names)
    np.testing.assert_array_equal(frame["theta1_rad"].to_numpy(), table["theta1_rad"])


def test_a_station_pair_with_its_vertical(station):
    h1, h2, up = station
    expected = cli_json("run", "--record", h1, "--record-h2", h2, "--record-up", up, "--incidence-deg", "30",
                        "--scale", "2")
    got = pcrf.run(record=h1, record_h2=h2, record_up=up, incidence_deg=30, scale=2)
    assert_same_record(got, expected)


def test_synthetic_motion():
    spec = "sine:amplitude_g=1.5,period_s=0.5,cycles=2"
    expected = cli_json("run", "--synthetic", spec, "--kappa", "3")
    assert_same_record(pcrf.run(synthetic=spec, frame={"kappa": 3}), expected)
    assert cli("run", "--synthetic", spec)[0] == 0


SINE = "sine:amplitude_g=0.5,period_s=1.0,cycles=3"


def test_the_other_scenes_by_model():
    """model= and the scene's keys in frame= build the scene as `pcrf run --model` does
    (model/scene_catalog.hpp): the same record bit for bit."""
    cases = [
        ("block", {"slenderness_rad": 0.2, "size_m": 1.5}, ["--slenderness-rad", "0.2", "--size-m", "1.5"]),
        ("block", {"frequency_parameter_rad_s": 2.0, "given_restitution": 0.9},
         ["--frequency-parameter-rad-s", "2", "--restitution", "0.9"]),
        ("rocking-frame", {"slenderness_rad": 0.25, "beam_mass_ratio": 0.5}, ["--slenderness-rad", "0.25",
                                                                             "--beam-mass-ratio", "0.5"]),
    ]
    for model, keys, flags in cases:
        expected = cli_json("run", "--synthetic", SINE, "--model", model, *flags)
        assert_same_record(pcrf.run(synthetic=SINE, model=model, frame=keys), expected)


def test_a_block_on_a_paper_record(paper):
    record = paper[0]
    expected = cli_json("run", "--record", record, "--scale", "0.5", "--model", "block", "--size-m", "2")
    assert_same_record(pcrf.run(record=record, scale=0.5, model="block", frame={"size_m": 2}), expected)


def test_a_frame_still_rocking_at_its_end_warns_naming_the_setting_that_helps():
    import pytest

    synthetic = "sine:amplitude_g=1.2,period_s=0.8,cycles=3,duration_s=2.4"
    with pytest.warns(UserWarning, match=r"rocking_at_end.*physics\.tail_s"):
        fixed = pcrf.run(synthetic=synthetic, tail_s=0)
    assert fixed["status"] == "rocking_at_end"
    with pytest.warns(UserWarning, match=r"physics\.max_tail_s"):
        assert pcrf.run(synthetic=synthetic, max_tail_s=0.01)["status"] == "rocking_at_end"
