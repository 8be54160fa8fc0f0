"""The example session (examples/notebook.py, the cells of a notebook) runs end to end."""

import os
import subprocess
import sys

from conftest import SOURCE_DIR


def test_the_example_session_runs(tmp_path):
    done = subprocess.run([sys.executable, str(SOURCE_DIR / "examples" / "notebook.py")], cwd=tmp_path,
                          capture_output=True, text=True, env=dict(os.environ), timeout=240)
    assert done.returncode == 0, done.stderr
    assert "{'tail_s': -1}: tail_s=: must not be negative (got -1)" in done.stdout
    assert (tmp_path / "notebook_demo.h5").is_file()
