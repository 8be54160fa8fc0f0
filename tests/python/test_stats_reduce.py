"""pcrf.stats(..., reduce_over=, reduce=) against `pcrf cube stats --reduce-over --reduce --json`
on a cube with an incidence axis (two synthetic components as two-column files)."""

import json

import numpy as np
import pytest

import pcrf
from conftest import cli, cli_error, in_keywords


def write_component(path, seed, pga_g, dt_s=0.01, duration_s=4.0):
    """A random motion in g, as a two-column text file (time, acceleration; 17 digits)."""
    generator = np.random.default_rng(seed)
    t = np.arange(0.0, duration_s, dt_s)
    accel = generator.standard_normal(t.size) * np.sin(np.pi * t / duration_s)
    np.savetxt(path, np.column_stack([t, pga_g * accel / np.abs(accel).max()]), fmt="%.17g")


def two_stations(folder):
    """Stations a and b: the two components in folder, each the other's h1."""
    station = {"units": "g", "az1_deg": 0, "az2_deg": 90}
    return [{"h1": str(folder / "h1.txt"), "h2": str(folder / "h2.txt"), "name": "a", **station},
            {"h1": str(folder / "h2.txt"), "h2": str(folder / "h1.txt"), "name": "b", **station}]


@pytest.fixture(scope="module")
def incidence_cube(tmp_path_factory):
    folder = tmp_path_factory.mktemp("incidence")
    for name, seed, pga_g in (("h1", 3, 1.6), ("h2", 4, 1.3)):
        write_component(folder / f"{name}.txt", seed, pga_g)
    study = {
        "study": {"name": "incidence"},
        "plan": {"kind": "grid"},
        "records": two_stations(folder),
        "axes": {"scale": [1.0, 1.5], "kappa": [1.8, 2.4], "incidence_deg": {"from": 0, "to": 150, "count": 6}},
    }
    cube = folder / "incidence.h5"
    pcrf.study(study, output=cube)
    return cube


@pytest.mark.parametrize("how", ["max", "median", "min"])
@pytest.mark.parametrize("by", [["scale"], ["kappa"]])
def test_stats_reduced_over_the_incidence_are_the_command_lines(incidence_cube, how, by):
    flags = [x for b in by for x in ("--by", b)]
    expected = json.loads(cli("cube", "stats", incidence_cube, *flags, "-m", "theta_max_rad",
                              "--reduce-over", "incidence_deg", "--reduce", how, "--json")[1])
    table = pcrf.stats(incidence_cube, by=by, metric="theta_max_rad", reduce_over="incidence_deg", reduce=how)
    assert list(table.columns) == [c["name"] for c in expected["columns"]["groups"]]
    assert len(table) == len(expected["groups"]) > 0
    for row, want in zip(table.to_dict("records"), expected["groups"]):
        for key, value in want.items():
            assert value == row[key] or (value is None and row[key] != row[key]), key
    assert table.attrs["fields"]["reduced_over"] == "incidence_deg" and table.attrs["fields"]["reduction"] == how


def test_the_reduction_changes_the_answer(incidence_cube):
    """max ≥ median ≥ min per group: the reduction reached the engine."""
    medians = {how: pcrf.stats(incidence_cube, by="scale", metric="theta_max_rad", reduce_over="incidence_deg",
                               reduce=how)["median"].to_numpy() for how in ("max", "median", "min")}
    assert np.all(medians["max"] >= medians["median"]) and np.all(medians["median"] >= medians["min"])
    assert np.any(medians["max"] > medians["min"])


@pytest.mark.parametrize("flags, keywords", [
    (["--reduce-over", "incidence_deg", "--reduce", "mean"], {"reduce_over": "incidence_deg", "reduce": "mean"}),
    (["--reduce", "median"], {"reduce": "median"}),
    (["--reduce-over", "incidence_deg"], {"by": "incidence_deg", "reduce_over": "incidence_deg"}),
])
def test_a_bad_reduction_is_the_command_lines_message(incidence_cube, flags, keywords):
    by = keywords.pop("by", "scale")
    expected = cli_error("cube", "stats", incidence_cube, "--by", by, "-m", "theta_max_rad", *flags, "--json")
    with pytest.raises(pcrf.InputError) as error:
        pcrf.stats(incidence_cube, by=by, metric="theta_max_rad", **keywords)
    assert str(error.value) == in_keywords(expected, "reduce", "reduce_over")


@pytest.fixture(scope="module")
def incidence_ida_cube(incidence_cube):
    """The same two stations, an adaptive IDA over three incidences."""
    folder = incidence_cube.parent
    study = {
        "study": {"name": "incidence_ida"},
        "plan": {"kind": "grid"},
        "records": two_stations(folder),
        "axes": {"incidence_deg": [0, 60, 120]},
        "intensity": {"measure": "pga_rotd50_g"},
        "ida": {"start": 0.5, "max_intensity": 8.0, "max_runs": 8},
    }
    cube = folder / "incidence_ida.h5"
    pcrf.study(study, output=cube)
    return cube


@pytest.mark.parametrize("how", [None, "median", "max"])
def test_fragility_reduced_over_the_incidence_is_the_command_lines(incidence_ida_cube, how):
    flags = ["--reduce-over", "incidence_deg"] + (["--reduce", how] if how else [])
    expected = json.loads(cli("cube", "fragility", incidence_ida_cube, *flags, "--json")[1])
    table = pcrf.fragility(incidence_ida_cube, reduce_over="incidence_deg", reduce=how)
    assert len(table) == len(expected["frames"]) == 1
    for key, value in expected["frames"][0].items():
        assert value == table.iloc[0][key] or (value is None and table.iloc[0][key] != table.iloc[0][key]), key
    assert table.attrs["fields"]["reduction"] == (how or "min")


def test_a_bad_fragility_reduction_is_the_command_lines_message(incidence_ida_cube):
    expected = cli_error("cube", "fragility", incidence_ida_cube, "--reduce-over", "incidence_deg", "--reduce", "mean")
    with pytest.raises(pcrf.InputError) as error:
        pcrf.fragility(incidence_ida_cube, reduce_over="incidence_deg", reduce="mean")
    assert str(error.value) == in_keywords(expected, "reduce") != expected
