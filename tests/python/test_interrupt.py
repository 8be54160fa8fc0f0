"""Ctrl-C stops pcrf.study in process as it stops `pcrf study`: the cube is checkpointed and
resumable, and KeyboardInterrupt is raised. A child Python runs the study; SIGINT is sent once
its progress shows cases done (no assumption on how fast they are)."""

import json
import signal
import subprocess
import sys

import numpy as np

import pcrf

STUDY = {
    "study": {"name": "interrupt"},
    "plan": {"kind": "grid"},
    "records": [{"synthetic": ["stochastic:seed=1,pga_g=1.4,duration_s=10",
                               "stochastic:seed=2,pga_g=1.2,duration_s=10"]}],
    "axes": {"scale": {"from": 0.5, "to": 3.0, "count": 40}, "kappa": {"from": 1.2, "to": 2.4, "count": 20}},
    "run": {"progress_interval_s": 0.1},
}

# The child: Python's own SIGINT handler even where the child starts with SIGINT ignored (a
# background job of a non-interactive shell), as an interactive session has it.
CHILD = """
import json, signal, sys
import pcrf
signal.signal(signal.SIGINT, signal.default_int_handler)
study = json.loads(sys.argv[1])
if sys.argv[3] == "uncaught":
    pcrf.study(study, output=sys.argv[2], progress=True)
else:  # as in a Jupyter kernel: the interpreter goes on, and resumes the study itself
    try:
        pcrf.study(study, output=sys.argv[2], progress=True)
    except KeyboardInterrupt as interrupt:
        print("interrupted:", *interrupt.__notes__, flush=True)
    status = pcrf.study(study, output=sys.argv[2], resume=True)["status"].values
    print("resumed:", int((status >= 0).sum()), "of", status.size, flush=True)
print("finished", flush=True)
"""


def cases_done(line):
    """The N of a progress line 'pcrf study: N/M cases ...'; None for other lines."""
    if not line.startswith("pcrf study: ") or "/" not in line:
        return None
    return int(line.removeprefix("pcrf study: ").split("/")[0])


def interrupted_child(cube, mode):
    """Runs CHILD in `mode` and sends it SIGINT once its study has stored cases: (exit code,
    stdout, stderr)."""
    child = subprocess.Popen([sys.executable, "-c", CHILD, json.dumps(STUDY), str(cube), mode],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    lines = []
    try:
        for line in child.stderr:  # wait until the study has stored cases
            lines.append(line)
            if (cases_done(line) or 0) > 0:
                child.send_signal(signal.SIGINT)
                break
        stdout, rest = child.communicate(timeout=300)
    finally:
        child.kill()
    return child.returncode, stdout, "".join(lines) + rest


def test_ctrl_c_stops_a_study_in_process_leaving_a_resumable_cube(tmp_path):
    cube = tmp_path / "interrupted.h5"
    returncode, stdout, stderr = interrupted_child(cube, "uncaught")
    assert returncode == -signal.SIGINT, stderr  # Python's exit on an uncaught KeyboardInterrupt
    assert "finished" not in stdout
    assert "KeyboardInterrupt" in stderr, stderr
    assert "pcrf.study: stopped by SIGINT: " in stderr and "continue with pcrf.study(..., resume=True)" in stderr, stderr

    stopped = pcrf.open_cube(cube)["status"].values
    done = int((stopped >= 0).sum())
    assert 0 < done < stopped.size, "the study should stop part way"
    assert f"{done} of {stopped.size} cases saved in {cube}" in stderr, stderr

    resumed = pcrf.study(STUDY, output=cube, resume=True)
    status = resumed["status"].values
    assert int((status >= 0).sum()) == status.size
    np.testing.assert_array_equal(status[stopped >= 0], stopped[stopped >= 0])  # the saved cases kept


def test_after_ctrl_c_the_same_interpreter_resumes_the_study(tmp_path):
    """The run ended in order: its MPI session and the cube's lock serve the next study."""
    returncode, stdout, stderr = interrupted_child(tmp_path / "kernel.h5", "caught")
    assert returncode == 0, stderr
    assert "interrupted: pcrf.study: stopped by SIGINT: " in stdout, stdout + stderr
    axes = STUDY["axes"]
    total = len(STUDY["records"][0]["synthetic"]) * axes["scale"]["count"] * axes["kappa"]["count"]
    assert f"resumed: {total} of {total}" in stdout and "finished" in stdout, stdout + stderr
