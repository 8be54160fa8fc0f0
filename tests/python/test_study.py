"""pcrf.study in process and pcrf.open_cube against `pcrf study` and its cube."""

import os

import numpy as np
import pytest

import pcrf
from conftest import cli

STUDY = {
    "study": {"name": "python"},
    "plan": {"kind": "grid"},
    "records": [{"synthetic": ["sine:amplitude_g=1.5,period_s=0.5,cycles=2,duration_s=4",
                               "stochastic:seed=1,pga_g=1.4,duration_s=6"]}],
    "axes": {"scale": [0.8, 1.25], "kappa": {"from": 1.2, "to": 2.4, "count": 3}},
    "physics": {"tail_s": 1.0},
}


def test_a_dict_study_in_process_equals_the_command_lines(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    cube = pcrf.study(STUDY, output=tmp_path / "module.h5")
    (tmp_path / "python.toml").write_text(pcrf._pcrf.study_text(STUDY))
    cli("study", tmp_path / "python.toml", "-o", tmp_path / "cli.h5")
    expected = pcrf.open_cube(tmp_path / "cli.h5")
    assert cube.sizes == expected.sizes
    assert cube["status"].dtype == np.int8
    assert "at_rest" in cube["status"].attrs["flag_meanings"].split()
    for name in ("theta_max_rad", "impacts", "status", "t_end_s"):
        np.testing.assert_array_equal(cube[name].values, expected[name].values, err_msg=name)
    assert cube.sel(kappa=1.8)["theta_max_rad"].size == 4  # the value the study meant
    assert int((cube["status"] >= 0).sum()) == cube["status"].size


def test_a_study_file_in_process(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "s.toml").write_text(pcrf._pcrf.study_text(STUDY))
    cube = pcrf.study(tmp_path / "s.toml")
    assert (tmp_path / "s.h5").is_file() and cube["theta_max_rad"].sizes["kappa"] == 3
    summary = pcrf.study(tmp_path / "s.toml", check=True)
    assert summary["total"] == 12


@pytest.mark.parametrize("change, message", [
    ({"axes": {"kappa": [1.0, -2.0]}}, "study: [axes] kappa"),
    ({"axes": {"kapa": [1.0]}}, "study: [axes] kapa: unknown key (did you mean 'kappa'?)"),
    ({"physics": {"tail_s": "long"}}, "study: [physics] tail_s"),
    ({"solver": {"preset": "bogus"}}, "study: [solver] preset"),
])
def test_a_dict_study_is_checked_with_key_paths(change, message, tmp_path):
    study = {**STUDY, **change}
    with pytest.raises(ValueError) as error:
        pcrf.study(study, output=tmp_path / "bad.h5")
    assert str(error.value).startswith(message), str(error.value)
    assert not (tmp_path / "bad.h5").exists()


def test_a_study_file_error_is_the_command_lines(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('[plan]\nkind = "grid"\n[axes]\nkapa = [1.0]\n')
    code, _, stderr = cli("study", bad, "--check", check=False)
    with pytest.raises(ValueError) as error:
        pcrf.study(bad, check=True)
    assert code == 2 and stderr.strip() == "pcrf: error: " + str(error.value)


def test_more_ranks_start_mpirun(tmp_path, monkeypatch, capfd):
    monkeypatch.chdir(tmp_path)
    if os.geteuid() == 0:  # Open MPI refuses root unless told (README, set-up; docs/setup.md)
        monkeypatch.setenv("OMPI_ALLOW_RUN_AS_ROOT", "1")
        monkeypatch.setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    cube = pcrf.study(STUDY, output=tmp_path / "two.h5", ranks=2)
    assert "mpirun -n 2" in capfd.readouterr().err
    assert cube["theta_max_rad"].sizes["scale"] == 2
    assert not list(tmp_path.glob(".pcrf_study_*"))  # the temporary study file is gone


def test_cube_reports_are_the_command_lines(tmp_path, monkeypatch):
    import json

    monkeypatch.chdir(tmp_path)
    pcrf.study(STUDY, output=tmp_path / "r.h5")
    expected = json.loads(cli("cube", "stats", tmp_path / "r.h5", "--by", "kappa", "--by", "scale", "-m",
                              "theta_max_rad", "--json")[1])
    table = pcrf.stats(tmp_path / "r.h5", by=["kappa", "scale"], metric="theta_max_rad")
    assert list(table.columns) == [c["name"] for c in expected["columns"]["groups"]]
    assert len(table) == len(expected["groups"]) == 6
    for row, want in zip(table.to_dict("records"), expected["groups"]):
        for key, value in want.items():
            assert value == row[key] or (value is None and row[key] != row[key]), key
    code, _, stderr = cli("cube", "fragility", tmp_path / "r.h5", check=False)
    with pytest.raises(ValueError) as error:
        pcrf.fragility(tmp_path / "r.h5")
    assert code == 2 and stderr.strip().splitlines()[-1] == "pcrf: error: " + str(error.value)


def test_pulse_dimensions_unstack_the_records_into_the_pulse_axes(tmp_path):
    """open_cube(pulse_dimensions=True): every record's values land at its own (shape, period)."""
    study = {"study": {"name": "pulses"}, "plan": {"kind": "grid"},
             "records": [{"pulse": ["pulse-sine", "ricker"]}],
             "axes": {"pulse_period_s": [0.3, 0.6, 1.2], "intensity": [0.4, 0.8]},
             "intensity": {"measure": "pga_g"}}
    stacked = pcrf.study(study, output=tmp_path / "pulses.h5")
    unstacked = pcrf.open_cube(tmp_path / "pulses.h5", pulse_dimensions=True)
    assert "record" not in unstacked.dims
    assert unstacked.sizes["pulse_shape"] == 2 and unstacked.sizes["pulse_period_s"] == 3
    assert unstacked["status"].dtype == np.int8
    for r in range(stacked.sizes["record"]):
        shape, period = str(stacked.pulse_shape.values[r]), float(stacked.pulse_period_s.values[r])
        at = unstacked.sel(pulse_shape=shape, pulse_period_s=period)
        for name in ("theta_max_rad", "status"):
            expected = stacked[name].isel(record=r)
            np.testing.assert_array_equal(at[name].transpose(*expected.dims).values, expected.values, strict=True)
    pcrf.study(STUDY, output=tmp_path / "records.h5")
    with pytest.raises(ValueError, match="not all pulses"):
        pcrf.open_cube(tmp_path / "records.h5", pulse_dimensions=True)


def test_a_study_of_several_scenes_gives_each_case_what_run_gives(tmp_path):
    """A list plan whose cases name their model: one cube, a scene_model coordinate, and each
    case's values those of pcrf.run on that scene (every metric, as pcrf.run computes them)."""
    block = {"slenderness_rad": 0.2, "frequency_parameter_rad_s": 2.12}
    study = {"study": {"name": "scenes"}, "plan": {"kind": "list"},
             "cases": [{"label": "frame"}, {"label": "block", "model": "block", **block}],
             "records": [{"synthetic": ["pulse-sine:period_s=0.5,amplitude_g=1.5",
                                        "ricker:period_s=1,amplitude_g=0.6"]}]}
    cube = pcrf.study(study, output=tmp_path / "scenes.h5")
    assert list(cube["scene_model"].values) == ["pcrf", "block"]
    assert np.isnan(cube["kappa"].sel(case=1)) and np.isnan(cube["slenderness_rad"].sel(case=0))
    scenes = {0: {}, 1: {"model": "block", "frame": block}}
    for r, record in enumerate(cube["record"].values):
        for case, keywords in scenes.items():
            result = pcrf.run(synthetic=str(record), **keywords)
            assert cube["theta_max_rad"].isel(record=r, scale=0).sel(case=case) == result["theta_max_rad"], (record, case)


def test_open_cube_refuses_a_fifo_at_once(tmp_path):
    """Issue 41: xarray (netCDF) waited for ever on a FIFO; refused before it opens, by name."""
    fifo = tmp_path / "pipe.h5"
    os.mkfifo(fifo)
    with pytest.raises(pcrf.InputError, match=r"pipe\.h5: is a FIFO, not a regular file"):
        pcrf.open_cube(fifo)
