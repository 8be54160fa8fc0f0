"""[run] device through the module: the keyword `device=` is a [run] setting like the others
(pcrf.settings() lists it), and asking for "gpu" where no device is usable (a build without
PCRF_CUDA, a machine without a GPU: here and in CI) raises pcrf.InputError naming the keyword
and the reason, and writes nothing."""

import os
import subprocess

import pytest

import pcrf
from conftest import pcrf_executable

STUDY = {
    "study": {"name": "device"},
    "records": [{"synthetic": "sine:amplitude_g=1.5,period_s=0.5,cycles=2,duration_s=3"}],
    "axes": {"kappa": [1.5, 2.5]},
    "physics": {"tail_s": 0.5},
}


def gpu_usable(tmp_path):
    """Whether `pcrf study --device gpu --check` runs here (a CUDA build on a GPU machine)."""
    (tmp_path / "probe.toml").write_text(pcrf._pcrf.study_text(STUDY))
    probe = subprocess.run([pcrf_executable(), "study", str(tmp_path / "probe.toml"), "--check", "--device", "gpu"],
                           capture_output=True, text=True)
    return probe.returncode == 0


def test_device_is_a_run_setting():
    rows = [s for s in pcrf.settings() if s["table"] == "run" and s["key"] == "device"]
    assert len(rows) == 1
    assert rows[0]["kind"] == '"cpu" or "gpu"' and rows[0]["default"] == "cpu"


@pytest.mark.parametrize("ranks", [1, 2])
def test_gpu_without_a_usable_device_raises_input_error_and_writes_nothing(tmp_path, monkeypatch, ranks):
    if ranks > 1 and os.geteuid() == 0:  # Open MPI refuses root unless told (docs/setup.md)
        monkeypatch.setenv("OMPI_ALLOW_RUN_AS_ROOT", "1")
        monkeypatch.setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    if gpu_usable(tmp_path):
        pytest.skip("a usable GPU is here: the error cannot be provoked")
    output = tmp_path / "gpu.h5"
    with pytest.raises(pcrf.InputError, match=r'^device=: "gpu" cannot be used here: .+; use "cpu"') as error:
        pcrf.study(STUDY, output=output, ranks=ranks, device="gpu")
    assert error.value.key == "device"
    assert not output.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["probe.toml"]


def test_cpu_is_the_engine_as_before(tmp_path):
    a = pcrf.study(STUDY, output=tmp_path / "a.h5")
    b = pcrf.study(STUDY, output=tmp_path / "b.h5", device="cpu")
    assert (a["theta_max_rad"].values == b["theta_max_rad"].values).all()
