"""pcrf.risk against `pcrf cube risk --json`: the same report (same C++), as DataFrames, and the
hazard file's refusals as InputError with the command line's message."""

import json

import pytest

import pcrf
from conftest import cli, cli_error, same_value

HAZARD = "pga_g,annual_rate_per_yr\n0.05,0.178885\n0.1,0.0316228\n0.3,0.00202837\n1,0.0001\n3,6.415e-06\n"


@pytest.fixture(scope="module")
def ida_cube(tmp_path_factory):
    folder = tmp_path_factory.mktemp("risk")
    # Ten records: the fewest that get a bootstrap interval (kFewestForInterval, cube_fragility.hpp).
    records = [f"stochastic:seed={s},pga_g=1,duration_s=6" for s in range(1, 11)]
    study = {"study": {"name": "risk"}, "records": [{"synthetic": records}],
             "intensity": {"measure": "pga_g"}, "ida": {"start": 0.5, "max_intensity": 8.0}}
    cube = folder / "ida.h5"
    pcrf.study(study, output=cube)
    (folder / "hazard.csv").write_text(HAZARD)
    return cube, folder / "hazard.csv"


@pytest.mark.parametrize("table", ["frames", "deaggregation"])
def test_risk_is_the_command_lines_report(ida_cube, table):
    cube, hazard = ida_cube
    expected = json.loads(cli("cube", "risk", cube, "--hazard", hazard, "--years", "10", "--json")[1])
    frame = pcrf.risk(cube, hazard, years=10, table=table)
    assert list(frame.columns) == [c["name"] for c in expected["columns"][table]]
    assert len(frame) == len(expected[table]) > 0
    for row, want in zip(frame.to_dict("records"), expected[table]):
        for key, value in want.items():
            assert same_value(value, row[key]), key
    for name in ("risk_targeted_intensity", "tail", "years", "group_lambda_collapse_per_yr"):
        assert same_value(expected[name], frame.attrs["fields"][name]), name


def test_bad_hazard_file_is_an_input_error_with_file_and_line(ida_cube, tmp_path):
    cube, _ = ida_cube
    bad = tmp_path / "flat.csv"
    bad.write_text("pga_g,annual_rate_per_yr\n0.1,1e-2\n0.2,1e-2\n")
    message = cli_error("cube", "risk", cube, "--hazard", bad)
    assert f"{bad}:3: the curve is not decreasing" in message
    with pytest.raises(pcrf.InputError, match="flat.csv:3: the curve is not decreasing"):
        pcrf.risk(cube, bad)
