"""pcrf.study: a study in process on one rank, or under mpirun on more."""

import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from . import _pcrf
from ._cube import opened
from ._notices import RecordWarning, warn
from ._pcrf import InputError, OutputError


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


# What `pcrf study` prints on stderr, by the prefix of the line: notes and record warnings,
# raised here as ranks=1 raises them.
_NOTE, _WARNING, _ERROR = "pcrf study: note: ", "pcrf study: warning: ", "pcrf: error: "


def _input_error(key, message, file=None, line=None):
    """pcrf.InputError as the engine raises it: its message, .key, .file and .line."""
    error = InputError(message)
    error.key, error.file, error.line = key, file, line
    return error


def _error_of(line, returncode):
    """The exception ranks=1 raises for the error line of `pcrf study` (a JSON object under
    PCRF_ERROR_FORMAT=json: its kind, message in keyword spelling, key, file and line)."""
    text = line.removeprefix(_ERROR) if line else f"mpirun exited with {returncode}"
    try:
        error = json.loads(text)
    except ValueError:
        error = None
    if not isinstance(error, dict):
        return RuntimeError(text)  # an internal error, or mpirun's own
    if error.get("kind") == "input":
        return _input_error(error.get("key") or None, error["message"], error.get("file") or None,
                            error.get("line") or None)
    if error.get("kind") == "output":
        return OutputError(error["message"])
    return OSError(error["message"])  # "write": the cube could not be written, as ranks=1 raises it


def _under_mpirun(source, output, ranks, flags, run_settings, progress):
    from . import _ENVIRONMENT_AT_IMPORT

    temporary = None
    text = _pcrf.study_text(source) if isinstance(source, dict) else None
    run_flags = _pcrf.run_flags(**run_settings)  # checked here, after the dict, as ranks=1 checks them
    if text is not None:
        # Checked above with the dict's key paths; mpirun's ranks read it as a file in the working
        # directory, so that relative record paths mean what they meant in the dict.
        handle, temporary = tempfile.mkstemp(prefix=".pcrf_study_", suffix=".toml", dir=os.getcwd())
        with os.fdopen(handle, "w") as file:
            file.write(text)
        source = temporary
    command = ["mpirun", "-n", str(ranks), _executable(), "study", os.fspath(source)]
    if output is not None:
        command += ["-o", os.fspath(output)]
    command += flags + run_flags
    # Not the variables this process's own MPI session (an earlier pcrf.study) added: mpirun
    # would take them for its own launch.
    environment = {key: value for key, value in os.environ.items()
                   if key in _ENVIRONMENT_AT_IMPORT or key.startswith("OMPI_ALLOW")
                   or not key.startswith(("OMPI_", "PMIX_", "OPAL_", "ORTE_"))}
    environment["PCRF_ERROR_FORMAT"] = "json"  # its error line, to be raised as ranks=1 raises it
    print("pcrf.study: starting " + " ".join(command), file=sys.stderr)
    error_line = None
    try:
        with subprocess.Popen(command, env=environment, stderr=subprocess.PIPE, text=True, encoding="utf-8",
                              errors="replace") as child:
            for line in child.stderr:
                line = line.rstrip("\n")
                if line.startswith(_ERROR):
                    error_line = line
                elif line.startswith(_NOTE):
                    warn([line.removeprefix(_NOTE)])
                elif line.startswith(_WARNING) and not progress:
                    warn([line.removeprefix(_WARNING)], RecordWarning)
                elif progress or not line.startswith("pcrf study: "):  # mpirun's own lines are always shown
                    print(line, file=sys.stderr, flush=True)
        returncode = child.returncode
    finally:
        if temporary is not None:
            os.unlink(temporary)
    if returncode != 0:
        raise _error_of(error_line, returncode)
    return output if output is not None else Path.cwd() / (Path(source).stem + ".h5")


def study(source, output=None, ranks=1, *, overwrite=False, resume=False, check=False, progress=False,
          **run_settings):
    """Runs a study (a study file's path, or a dict with the file's tables) and returns its cube
    as an xarray.Dataset (``pcrf.open_cube``).

    One rank (default): in this process, through the C++ ``pcrf study`` runs; a dict is checked
    with the messages a file gets, naming the key path (``study: [axes] kappa: ...``) in place of
    a line; a dict needs ``output=``. ``ranks > 1``: starts ``mpirun -n ranks pcrf study`` and
    says so on stderr; its errors raise what ranks=1 raises (``InputError`` naming the keyword,
    ``OSError`` for a cube that could not be written), its notes and warnings are warned as
    ranks=1 warns them. ``overwrite``, ``resume``, ``check`` and the [run] keys
    (``flush_interval_s``, ...) as on the command line; ``progress=True`` shows its progress
    lines. ``check=True`` returns the summary (cases, fingerprint) instead of a cube.

    Notes (a record's components padded, cases left unresolved) are ``pcrf.PcrfWarning``s, the
    records' checks ``pcrf.RecordWarning``s, as the command line prints them.
    """
    if not isinstance(ranks, int) or isinstance(ranks, bool) or ranks < 1:
        raise _input_error("ranks", f"ranks=: must be a whole number ≥ 1 (got {ranks!r})")
    if ranks > 1:
        flags = [flag for flag, on in (("--overwrite", overwrite), ("--resume", resume), ("--check", check)) if on]
        cube = _under_mpirun(source, output, ranks, flags, run_settings, progress)
        return None if check else opened(cube)
    summary = _pcrf.study(source, output=None if output is None else os.fspath(output), overwrite=overwrite,
                          resume=resume, check=check, progress=progress, **run_settings)
    warn(summary["notes"])
    if not progress:  # with progress=True they were printed with the progress lines
        warn(summary["warnings"], RecordWarning)
    warn(summary["verdict_notes"])
    if check:
        return summary
    if summary["error"]:
        raise OSError(summary["error"])
    return opened(summary["output"])
