"""Issue 29: a record given as an array gets the checks a file gets (PGA range, PGV/PGA with
the likely units, dt against the content), as pcrf.RecordWarning; warnings_as_errors makes
them errors. So do components from different stations and incidences that look like
radians. The messages' wording is not asserted beyond the key and the number they name."""

import warnings

import numpy as np
import pytest

import pcrf
from conftest import records_dir

DT_S = 0.01


def motion_g(peak_g=0.4, duration_s=10.0, period_s=0.5):
    """A plausible strong motion in g: a decaying sine, peak `peak_g`."""
    t = np.arange(0.0, duration_s, DT_S)
    return peak_g * np.exp(-0.3 * t) * np.sin(2 * np.pi * t / period_s)


def record_warnings(call):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        call()
    return [str(w.message) for w in caught if issubclass(w.category, pcrf.RecordWarning)]


def test_a_plausible_array_runs_without_a_record_warning():
    assert record_warnings(lambda: pcrf.run(motion_g(), DT_S, tail_s=1)) == []


def test_an_array_in_cm_s2_warns_with_the_likely_units():
    """The issue's case: cm/s² passed as g gives a PGA of hundreds of g."""
    lines = record_warnings(lambda: pcrf.run(motion_g() * 980.665, DT_S, tail_s=1))
    assert len(lines) == 1, lines
    assert "ground_accel_g" in lines[0] and "cm/s2" in lines[0], lines[0]


def test_a_wrong_dt_warns_through_pgv_over_pga():
    """dt = 1 s for samples taken every 0.01 s: PGV/PGA 100 times too long."""
    lines = record_warnings(lambda: pcrf.run(motion_g(), 1.0, tail_s=1))
    assert len(lines) == 1 and "PGV/PGA" in lines[0], lines


def test_a_dt_outside_any_record_is_refused_as_for_a_file():
    with pytest.raises(ValueError, match="dt_s"):
        pcrf.run(motion_g(), 2.0)


def test_warnings_as_errors_makes_them_errors():
    with pytest.raises(pcrf.InputError, match="warnings_as_errors"):
        pcrf.run(motion_g() * 980.665, DT_S, warnings_as_errors=True)
    with pytest.raises(pcrf.InputError, match="warnings_as_errors"):
        pcrf.record_measures(motion_g() * 980.665, dt_s=DT_S, warnings_as_errors=True)
    # and the standard filter does it too
    with warnings.catch_warnings():
        warnings.simplefilter("error", pcrf.RecordWarning)
        with pytest.raises(pcrf.RecordWarning):
            pcrf.run(motion_g() * 980.665, DT_S, tail_s=1)


def test_record_measures_checks_arrays_too():
    lines = record_warnings(lambda: pcrf.record_measures(motion_g() * 980.665, dt_s=DT_S))
    assert len(lines) == 1 and "cm/s2" in lines[0], lines


def test_a_file_read_in_python_gets_the_files_checks(tmp_path):
    """pcrf.run(record=...) warns as `pcrf run --record` does."""
    t = np.arange(0.0, 10.0, DT_S)
    path = tmp_path / "cm.txt"
    np.savetxt(path, np.column_stack([t, motion_g() * 980.665]))
    lines = record_warnings(lambda: pcrf.run(record=path, tail_s=1))
    assert len(lines) == 1 and "cm.txt" in lines[0] and "cm/s2" in lines[0], lines


def test_an_incidence_in_radians_warns_naming_the_key():
    pair = dict(ground_accel_g=motion_g(), ground_accel_h2_g=motion_g(0.3, period_s=0.7), azimuth_deg=0,
                h2_azimuth_deg=90, tail_s=1)
    lines = record_warnings(lambda: pcrf.run(dt_s=DT_S, incidence_deg=3.7, **pair))
    assert len(lines) == 1 and "incidence_deg" in lines[0] and "3.7" in lines[0], lines
    assert record_warnings(lambda: pcrf.run(dt_s=DT_S, incidence_deg=212, **pair)) == []
    assert record_warnings(lambda: pcrf.run(dt_s=DT_S, incidence_deg=3, **pair)) == []  # a whole degree


def test_components_of_two_stations_warn_naming_both():
    """The issue's pair: Rinaldi (Northridge 1994) with San Fernando 1971's PEL station."""
    base = records_dir()
    rinaldi = base / "nearfault_vacalderon" / "RSN1063_NORTHR_RRS228.AT2" if base else None
    pel = base / "vertical_sehyeon9121" / "RSN68_SFERN_PEL090.AT2" if base else None
    if not (rinaldi and rinaldi.is_file() and pel.is_file()):
        pytest.skip("no PEER records (../shared/records)")
    lines = record_warnings(lambda: pcrf.record_measures(rinaldi, record_h2=pel))
    assert len(lines) == 1, lines
    assert "Rinaldi" in lines[0] and "Northridge" in lines[0] and "San Fernando" in lines[0], lines[0]
    # The station's own components: no warning.
    rinaldi_318 = rinaldi.with_name("RSN1063_NORTHR_RRS318.AT2")
    assert record_warnings(lambda: pcrf.record_measures(rinaldi, record_h2=rinaldi_318)) == []


def test_a_study_in_python_gives_its_warnings_as_record_warnings(tmp_path):
    """pcrf.study(check=True) without progress lines: the study's warnings are RecordWarnings,
    and the check says what the run would cost."""
    t = np.arange(0.0, 5.0, DT_S)
    for name, motion in (("h1.txt", motion_g()), ("h2.txt", motion_g(0.3, period_s=0.7))):
        np.savetxt(tmp_path / name, np.column_stack([t, motion[: t.size]]))
    study = {"records": [{"h1": str(tmp_path / "h1.txt"), "h2": str(tmp_path / "h2.txt"), "az1_deg": 0, "az2_deg": 90}],
             "axes": {"scale": [1.0], "incidence_deg": [3.7, 1.2]}}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        summary = pcrf.study(study, check=True)
    lines = [str(w.message) for w in caught if issubclass(w.category, pcrf.RecordWarning)]
    assert len(lines) == 1 and "[axes] incidence_deg" in lines[0], lines
    assert "sampled cases" in summary["cost_estimate"], summary["cost_estimate"]
