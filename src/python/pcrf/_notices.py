"""The warnings of pcrf: every note and warning the command line prints on stderr, raised in
Python through ``warnings.warn`` as a ``pcrf.PcrfWarning`` (``tests/python/test_one_voice.py``
keeps the two in step)."""

import os
import sys
import warnings

_PACKAGE = os.path.dirname(os.path.abspath(__file__))


class PcrfWarning(UserWarning):
    """What the command line prints as a note or a warning on stderr (``pcrf run: note: …``,
    ``pcrf cube risk: warning: …``, ``pcrf study: note: …``): a record padded, a cube still
    being written or partial, cases left unresolved, a report's caveats (few curves bracket a
    collapse, a tail that carries much of λ_c, …). ``warnings.simplefilter("error",
    pcrf.PcrfWarning)`` makes every one an error; the reports also keep theirs in
    ``attrs["warnings"]``."""


class RecordWarning(PcrfWarning):
    """A record whose measures no earthquake record has (a PGA above 3 g or below 0.01 g,
    PGV/PGA outside its range: wrong units or a wrong ``dt_s``), or whose components' headers
    name different events or stations: the checks ``pcrf run`` makes of a file, made of arrays
    too. ``warnings_as_errors=True`` (a keyword of ``run`` and ``record_measures``), or
    ``warnings.simplefilter("error", pcrf.RecordWarning)``, makes them errors."""


def _caller_level():
    """The stacklevel of warnings.warn, called from warn(), that names the first frame outside
    this package: the user's line that called pcrf."""
    level, frame = 2, sys._getframe(2)
    while frame is not None and os.path.abspath(frame.f_code.co_filename).startswith(_PACKAGE + os.sep):
        level, frame = level + 1, frame.f_back
    return level


def warn(lines, category=PcrfWarning):
    """Each line (without the command line's "pcrf COMMAND: note: " prefix) as a warning of
    `category`, attributed to the user's code."""
    level = _caller_level()
    for line in lines:
        if line:
            warnings.warn(line, category, stacklevel=level)
