"""pcrf.study: a study in process on one rank, or under mpirun on more."""

import os
import shutil
import subprocess
import sys
import tempfile
import warnings
from pathlib import Path

from . import _pcrf
from ._cube import open_cube


def _executable():
    """The pcrf executable: $PCRF_EXECUTABLE, the one built with this module, or pcrf on PATH."""
    if os.environ.get("PCRF_EXECUTABLE"):
        return os.environ["PCRF_EXECUTABLE"]
    try:
        from ._build_info import PCRF_EXECUTABLE

        if os.path.exists(PCRF_EXECUTABLE):
            return PCRF_EXECUTABLE
    except ImportError:
        pass
    return shutil.which("pcrf") or "pcrf"


def _under_mpirun(source, output, ranks, flags, run_settings, progress):
    from . import _ENVIRONMENT_AT_IMPORT

    temporary = None
    if isinstance(source, dict):
        # Checked here with the dict's key paths; mpirun's ranks read it as a file in the working
        # directory, so that relative record paths mean what they meant in the dict.
        text = _pcrf.study_text(source)
        handle, temporary = tempfile.mkstemp(prefix=".pcrf_study_", suffix=".toml", dir=os.getcwd())
        with os.fdopen(handle, "w") as file:
            file.write(text)
        source = temporary
    command = ["mpirun", "-n", str(ranks), _executable(), "study", os.fspath(source)]
    if output is not None:
        command += ["-o", os.fspath(output)]
    command += flags
    for key, value in run_settings.items():
        command += ["--" + key.replace("_", "-"), str(value)]
    # Not the variables this process's own MPI session (an earlier pcrf.study) added: mpirun
    # would take them for its own launch.
    environment = {key: value for key, value in os.environ.items()
                   if key in _ENVIRONMENT_AT_IMPORT or key.startswith("OMPI_ALLOW")
                   or not key.startswith(("OMPI_", "PMIX_", "OPAL_", "ORTE_"))}
    print("pcrf.study: starting " + " ".join(command), file=sys.stderr)
    try:
        done = subprocess.run(command, env=environment, stderr=None if progress else subprocess.PIPE,
                              text=True)
    finally:
        if temporary is not None:
            os.unlink(temporary)
    if done.returncode != 0:
        lines = (done.stderr or "").strip().splitlines()
        message = lines[-1].removeprefix("pcrf: error: ") if lines else f"mpirun exited with {done.returncode}"
        raise (ValueError if done.returncode == 2 else RuntimeError)(message)
    return output if output is not None else Path.cwd() / (Path(source).stem + ".h5")


def study(source, output=None, ranks=1, *, overwrite=False, resume=False, check=False, progress=False,
          **run_settings):
    """Runs a study (a study file's path, or a dict with the file's tables) and returns its cube
    as an xarray.Dataset (``pcrf.open_cube``).

    One rank (default): in this process, through the C++ ``pcrf study`` runs; a dict is checked
    with the messages a file gets, naming the key path (``study: [axes] kappa: ...``) in place of
    a line; a dict needs ``output=``. ``ranks > 1``: starts ``mpirun -n ranks pcrf study`` and
    says so on stderr. ``overwrite``, ``resume``, ``check`` and the [run] keys
    (``flush_interval_s``, ...) as on the command line; ``progress=True`` shows its progress
    lines. ``check=True`` returns the summary (cases, fingerprint) instead of a cube.
    """
    if not isinstance(ranks, int) or ranks < 1:
        raise ValueError(f"ranks must be a whole number ≥ 1 (got {ranks!r})")
    if ranks > 1:
        flags = [flag for flag, on in (("--overwrite", overwrite), ("--resume", resume), ("--check", check)) if on]
        cube = _under_mpirun(source, output, ranks, flags, run_settings, progress)
        return None if check else open_cube(cube)
    summary = _pcrf.study(source, output=None if output is None else os.fspath(output), overwrite=overwrite,
                          resume=resume, check=check, progress=progress, **run_settings)
    if not progress:  # with progress=True they were printed with the progress lines
        from . import RecordWarning

        for line in summary.get("warnings", []):
            warnings.warn(line, RecordWarning, stacklevel=2)
    if check:
        return summary
    if summary["error"]:
        raise OSError(summary["error"])
    return open_cube(summary["output"])
