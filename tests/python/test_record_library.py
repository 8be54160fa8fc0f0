"""pcrf.pulse, pcrf.record_spectra and pcrf.select against the command line, and the figures
pcrf.plot draws of them (pulse, selection)."""

import json
import math
import subprocess

import numpy as np
import pytest

import pcrf
from conftest import pcrf_executable, records_dir


def one_cycle_pulse_g(dt_s=0.01, period_s=2.0, amplitude_g=0.8):
    t = np.arange(0, 30, dt_s) - 5.0
    return np.where((t >= 0) & (t <= period_s), amplitude_g * np.sin(2 * math.pi * t / period_s), 0.0)


def test_pulse_of_an_array_is_pulse_like_and_series_come_on_request():
    result = pcrf.pulse(one_cycle_pulse_g(), dt_s=0.01)
    assert result["method"] == "baker-2007" and result["pulse_like"]
    assert "velocity_cm_s" not in result
    with_series = pcrf.pulse(one_cycle_pulse_g(), dt_s=0.01, series=True)
    assert len(with_series["pulse_cm_s"]) == len(one_cycle_pulse_g())
    assert with_series["period_s"] == result["period_s"]


def test_noise_is_not_pulse_like():
    rng = np.random.default_rng(3)
    assert not pcrf.pulse(0.2 * rng.standard_normal(3000), dt_s=0.01)["pulse_like"]


@pytest.fixture
def near_fault():
    base = records_dir()
    if base is None:
        pytest.skip("no PEER records (../shared/records)")
    return base / "nearfault_sehyeon9121"


def test_pulse_and_spectra_equal_the_command_line(near_fault, tmp_path):
    h1, h2 = near_fault / "RSN879_LANDERS_LCN260.AT2", near_fault / "RSN879_LANDERS_LCN345.AT2"
    ours = pcrf.pulse(h1, record_h2=h2)
    cli = json.loads(subprocess.run([pcrf_executable(), "record", "pulse", str(h1), "--h2", str(h2)],
                                    capture_output=True, text=True, check=True).stdout)
    assert ours == cli and ours["method"] == "shahi-baker-2014" and ours["pulse_like"]

    table = pcrf.record_spectra(near_fault, periods_s=[0.2, 1.0])
    assert list(table["kind"]) == ["component", "component", "rotd50"]
    out = tmp_path / "lib.csv"
    subprocess.run([pcrf_executable(), "record", "spectra", str(near_fault), "--period", "0.2", "--period", "1",
                    "-o", str(out)], capture_output=True, check=True)
    cli_table = pcrf.record_spectra(near_fault, periods_s=[0.2, 1.0])
    assert (table["sa_g_1s"] == cli_table["sa_g_1s"]).all()


def test_select_equals_the_command_line_and_plots(tmp_path):
    # A library of 60 synthetic spectra, as the command line's table.
    rng = np.random.default_rng(1)
    periods = [0.1, 0.3, 1.0, 3.0]
    rows = ["name,kind,file,file_h2,dt_s,samples,damping,pga_g," + ",".join(f"sa_g_{t:g}s" for t in periods)]
    for i in range(60):
        a, b = 0.5 * rng.standard_normal(), 0.3 * rng.standard_normal()
        sa = [math.exp(-1 + a + b * math.log(t) - 0.5 * math.log(t) * (t > 0.3)) for t in periods]
        rows.append(f"r{i},component,r{i}.AT2,,0.01,1000,0.05,0.3," + ",".join(repr(x) for x in sa))
    (tmp_path / "lib.csv").write_text("\n".join(rows) + "\n")
    (tmp_path / "t.csv").write_text("period_s,mean_ln_sa,sigma_ln_sa\n0.1,-1.1,0.5\n0.3,-1.0,0.45\n1,-1.2,0.5\n")
    ours = pcrf.select(tmp_path / "t.csv", tmp_path / "lib.csv", 8, kind="component")
    cli = json.loads(subprocess.run([pcrf_executable(), "record", "select", "--target", str(tmp_path / "t.csv"),
                                     "--library", str(tmp_path / "lib.csv"), "-n", "8", "--kind", "component", "--json"],
                                    capture_output=True, text=True, check=True).stdout)
    assert ours == cli and len(ours["records"]) == 8
    with pytest.raises(pcrf.InputError, match="bad.csv:3: period_s: 5 s is outside"):
        (tmp_path / "bad.csv").write_text("period_s,mean_ln_sa,sigma_ln_sa\n0.1,-1.1,0.5\n5,-1.0,0.45\n")
        pcrf.select(tmp_path / "bad.csv", tmp_path / "lib.csv", 8, kind="component")

    pytest.importorskip("matplotlib")
    from pcrf import plot
    (tmp_path / "sel.json").write_text(json.dumps(ours))
    fig = plot.figure("selection", tmp_path / "sel.json")
    assert len(fig.axes) == 2
    (tmp_path / "pulse.json").write_text(json.dumps(pcrf.pulse(one_cycle_pulse_g(), dt_s=0.01, series=True)))
    fig = plot.figure("pulse", tmp_path / "pulse.json")
    assert len(fig.axes) == 3
    with pytest.raises(plot.PlotError, match="not the JSON of pcrf record pulse"):
        plot.figure("pulse", tmp_path / "sel.json")
