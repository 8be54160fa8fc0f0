"""pcrf.plot in process: the figures read everything through the module and start no process;
pcrf.vocabulary() is `pcrf settings --json`; pcrf.write_output follows the rule of every output."""

import json
import os
import stat
import subprocess

import pytest

import pcrf
from conftest import cli

matplotlib = pytest.importorskip("matplotlib")
import pcrf.plot  # noqa: E402

STUDY = {
    "plan": {"kind": "one-at-a-time", "include_base": True},
    "records": [{"synthetic": ["sine:amplitude_g=1.5,period_s=0.5,cycles=2,duration_s=4",
                               "stochastic:seed=1,pga_g=1.4,duration_s=6"]}],
    "axes": {"scale": [1.3], "kappa": [1.2, 2.4], "tan_alpha": [0.16, 0.22]},
    "physics": {"tail_s": 1.0},
}


@pytest.fixture(scope="module")
def cube(tmp_path_factory):
    path = tmp_path_factory.mktemp("plot") / "oat.h5"
    pcrf.study(STUDY, output=path)
    return path


@pytest.fixture
def no_process(monkeypatch):
    """Any attempt to start a process fails the test. Matplotlib's font list is built first: on a
    fresh machine its first scan starts fc-list, which is matplotlib's own cache, not the figure's."""
    import matplotlib.font_manager  # noqa: F401  (loads or builds the font cache)
    def refuse(*args, **kwargs):
        raise AssertionError(f"a process was started: {args[:2]}")
    monkeypatch.setattr(subprocess, "Popen", refuse)
    for name in ("fork", "forkpty", "posix_spawn", "posix_spawnp", "execv", "execve", "execvp", "system", "popen"):
        if hasattr(os, name):
            monkeypatch.setattr(os, name, refuse)


def test_a_figure_is_drawn_and_written_without_starting_a_process(cube, tmp_path, no_process, capsys):
    out = tmp_path / "sweep.svg"
    assert pcrf.plot.main(["sweep", str(cube), "-o", str(out)]) == 0, capsys.readouterr().err
    assert out.read_text().count('<g id="axes_') == 2  # one panel per varied parameter
    assert pcrf.plot.main(["status", str(cube), "-o", str(tmp_path / "status.png")]) == 0
    assert (tmp_path / "status.png").read_bytes()[:4] == b"\x89PNG"


def test_figure_returns_the_commands_figure_and_its_errors(cube, no_process):
    figure = pcrf.plot.figure("sweep", cube, metric="impacts")
    assert len(figure.axes) == 2
    assert "impacts" in figure.axes[0].get_ylabel()
    with pytest.raises(pcrf.plot.PlotError, match="kappa=7: no such value"):
        pcrf.plot.figure("sweep", cube, where="kappa=7")
    with pytest.raises(pcrf.plot.PlotError, match="not an IDA cube"):
        pcrf.plot.figure("ida", cube)


def test_a_refused_output_is_one_line_and_nothing_is_written(cube, tmp_path, capsys):
    existing = tmp_path / "existing.svg"
    existing.write_text("keep me")
    assert pcrf.plot.main(["sweep", str(cube), "-o", str(existing)]) == 2
    err = capsys.readouterr().err
    assert err.endswith("existing.svg: already exists; use --overwrite to replace it\n") and err.count("\n") == 1, err
    assert existing.read_text() == "keep me"


def test_vocabulary_is_the_command_lines():
    assert pcrf.vocabulary() == json.loads(cli("settings", "--json")[1])


def test_write_output_keeps_inputs_and_existing_files(tmp_path):
    target = tmp_path / "f.bin"
    pcrf.write_output(target, b"one")
    assert target.read_bytes() == b"one"
    assert stat.S_IMODE(target.stat().st_mode) == 0o666 & ~_umask()
    with pytest.raises(pcrf.OutputError, match="already exists; use --overwrite to replace it"):
        pcrf.write_output(target, b"two")
    with pytest.raises(OSError, match="already exists"):
        pcrf.check_output(target)
    pcrf.write_output(target, b"two", overwrite=True)
    assert target.read_bytes() == b"two"
    source = tmp_path / "input.txt"
    source.write_text("input")
    os.symlink(source, tmp_path / "link.txt")
    with pytest.raises(pcrf.OutputError, match="the input"):
        pcrf.write_output(tmp_path / "link.txt", b"x", inputs=[source], overwrite=True)
    assert source.read_text() == "input"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f.bin", "input.txt", "link.txt"]  # no temporary left


def _umask():
    mask = os.umask(0)
    os.umask(mask)
    return mask
