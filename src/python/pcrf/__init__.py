"""pcrf in Python: the engine in process.

Every function calls the C++ that the ``pcrf`` command line calls, so a result is the
command line's, bit for bit, and a bad input raises ``pcrf.InputError`` (a ``ValueError``) with
the command line's message, its keys spelt as keywords (``tail_s=: must be positive``).

>>> import numpy as np, pcrf
>>> t = np.arange(0, 4, 0.01)
>>> result = pcrf.run(ground_accel_g=1.5 * np.sin(2 * np.pi * t / 0.5), dt_s=0.01, preset="reference")
>>> result["status"], result["theta_max_rad"]

- ``run(...)``: one case (``pcrf run``); the history as a numpy structured array or a pandas
  DataFrame with ``history="numpy"`` / ``"pandas"``.
- ``Frame(model="pcrf"|"block"|"rocking-frame", **parameters)``: a scene's properties and
  pushover curve (``pcrf frame``).
- ``record_measures(...)``: a record's intensity measures (``pcrf record``).
- ``pulse(...)``, ``record_spectra(...)``, ``select(...)``: pulses identified, a library's
  spectra, records selected to a target (``pcrf record pulse|spectra|select``).
- ``study(dict or path, output=...)``: a study, returned as an xarray.Dataset (``pcrf study``).
- ``open_cube(path)``: a result cube as an xarray.Dataset, ``status`` as integer flags.
- ``stats``, ``fragility``, ``sensitivity``, ``p695``, ``risk``: ``pcrf cube``'s reports as DataFrames.
- ``settings()``: every [physics] / [solver] / intensity / [run] key, with unit and default;
  ``vocabulary()``: the statuses, history events, parameters (``pcrf settings --json``).
- ``write_output(path, bytes)``, ``check_output(path)``: the rule of every file pcrf writes.
- ``pcrf.plot.figure(kind, input, ...)``: the figures of ``pcrf plot`` (matplotlib).

The compiled part releases the GIL while it computes: a thread pool over cases uses every core.
"""

import json as _json
import os as _os
import warnings as _warnings

from . import _pcrf
from ._pcrf import InputError  # a ValueError naming the keyword (its .key), or file and line
from ._pcrf import OutputError  # an OSError: an output the never-destroy rule refused or that failed

__version__ = _pcrf.__version__

# The environment before MPI started in this process (pcrf.study): mpirun gets this one.
_ENVIRONMENT_AT_IMPORT = dict(_os.environ)


class RecordWarning(UserWarning):
    """A record whose measures no earthquake record has (a PGA above 3 g or below 0.01 g,
    PGV/PGA outside its range: wrong units or a wrong ``dt_s``), or whose components' headers
    name different events or stations: the checks ``pcrf run`` makes of a file, made of arrays
    too. ``warnings_as_errors=True`` (a keyword of ``run`` and ``record_measures``), or
    ``warnings.simplefilter("error", pcrf.RecordWarning)``, makes them errors."""


def _warn_notes(notes, category=UserWarning):
    for note in notes:
        _warnings.warn(note, category, stacklevel=3)


def _history_table(array, history):
    if history in (True, "numpy"):
        return array
    if history == "pandas":
        import pandas

        return pandas.DataFrame(array)
    raise ValueError(f"history: expected False, True, 'numpy' or 'pandas' (got {history!r})")


def run(ground_accel_g=None, dt_s=None, *, history=False, **keywords):
    """Solves one case as ``pcrf run`` does and returns its result record (a dict with the
    keys of ``pcrf run``'s JSON; NaN where it writes null).

    The ground motion: ``ground_accel_g`` (a 1-D array in g, sample interval ``dt_s``), with
    ``ground_accel_h2_g`` and ``ground_accel_up_g`` for a station's other components; or
    ``record`` (a file: .AT2, two-column or one-column text with ``format``, ``units``,
    ``dt_s``, ``skip_rows``, ``column``) with ``record_h2`` and ``record_up``, or
    ``synthetic="sine:..."``. ``azimuth_deg``, ``h2_azimuth_deg``, ``incidence_deg`` as on the
    command line. ``scale=`` or ``intensity=`` (with ``measure``, ``period_s``, ``damping``).

    The frame: ``frame=`` a dict of parameters (kappa, lambda, tan_alpha, lambda_h, pi_sigma_b,
    pi_sigma_c, pi_e_b, pi_e_c, h_m, m_c_kg) or a ``pcrf.Frame`` (of any model); default the
    paper's basic model. ``model="block"`` or ``"rocking-frame"`` (as ``pcrf run --model``)
    solves another scene; ``frame=`` then holds its keys as a study spells them
    (slenderness_rad, size_m or frequency_parameter_rad_s, given_restitution, beam_mass_ratio). Every key of a study's [physics] and [solver] tables is a keyword (``preset``,
    ``tail_s``, ``rtol``, ...; ``pcrf.settings()`` lists them).

    ``history``: False (default), True or "numpy" (a structured array), "pandas" (a DataFrame);
    then ``(result, history)`` is returned. ``history_dt_s`` sets its interval.

    A record (array or file) is checked as ``pcrf run`` checks a file: an implausible PGA or
    PGV/PGA (likely units, a wrong ``dt_s``) or components from different stations give a
    ``pcrf.RecordWarning``; ``warnings_as_errors=True`` makes them an ``InputError``.
    """
    if ground_accel_g is not None:
        keywords["ground_accel_g"] = ground_accel_g
    if dt_s is not None:
        keywords["dt_s"] = dt_s
    result, rows, notes, record_warnings = _pcrf.run(history=bool(history), **keywords)
    _warn_notes(notes)
    _warn_notes(record_warnings, RecordWarning)
    if not history:
        return result
    return result, _history_table(rows, history)


class Frame:
    """A scene before any ground motion (``pcrf frame --model M``): ``Frame(kappa=2.5)`` (the
    prestressed frame; its other parameters the paper's basic model's),
    ``Frame(model="block", slenderness_rad=0.2, size_m=1)`` (Housner's block),
    ``Frame(model="rocking-frame", ..., beam_mass_ratio=0.5)``; the parameters are the scene
    catalogue's keys, as a study's [frame] spells them, checked with the command line's
    messages (a parameter of another model, a value outside its domain: ``ValueError``).
    Its properties are attributes (``threshold`` is ``uplift_threshold_g``, also
    ``frequency_parameter_rad_s``, ``restitution``, ``fracture_angle_rad``,
    ``overturn_angle_rad``, ...; ``properties`` holds them all as ``pcrf frame --json`` prints
    them, NaN where it prints null, ``units`` their units), the pushover curve is
    ``pushover_theta_rad`` and ``pushover_accel_g`` (numpy arrays, ``points`` rotations,
    default 41). ``fracture_strain`` (a [physics] key) sets where tendons fracture.
    ``model`` and ``parameters`` (every parameter of the scene, defaults included) describe it:
    ``pcrf.run(frame=Frame(...))`` solves this scene.
    """

    def __init__(self, model="pcrf", **parameters):
        described = _pcrf.frame(model=model, **parameters)
        self.model = described["model"]
        self.parameters = described["parameters"]
        self.properties = described["properties"]
        self.units = described["units"]
        self.fracture_tendon = described["fracture_tendon"]
        self.pushover_theta_rad = described["pushover_theta_rad"]
        self.pushover_accel_g = described["pushover_accel_g"]

    @property
    def threshold(self):
        """The ground acceleration that opens the frame, prestress included [g]."""
        return self.properties["uplift_threshold_g"]

    def __getattr__(self, name):
        properties = self.__dict__.get("properties", {})
        if name in properties:
            return properties[name]
        raise AttributeError(f"pcrf.Frame has no attribute {name!r} (properties: {', '.join(properties)})")

    def __dir__(self):
        return sorted(set(super().__dir__()) | set(self.properties))

    def __repr__(self):
        given = ", ".join(f"{k}={v!r}" for k, v in self.parameters.items())
        return f"pcrf.Frame(model={self.model!r}, {given})"


def record_measures(record=None, **keywords):
    """What ``pcrf record`` prints, as a dict: PGA, PGV, PGD, Arias intensity, D5-95, Sa at
    ``periods_s`` (``damping``, default 0.05), the header's metadata; with ``record_h2`` (the
    command line's ``--pair``) RotD50/RotD100 and the pair's measures, with ``record_up`` the
    vertical's. ``record`` is a file (keywords as for ``run``) or an array in g (then
    ``dt_s=``)."""
    if record is not None:
        if isinstance(record, (str, _os.PathLike)):
            keywords["record"] = record
        else:
            keywords["ground_accel_g"] = record
    periods = keywords.get("periods_s")
    if periods is not None and not hasattr(periods, "__len__"):
        keywords["periods_s"] = [periods]
    text, notes, record_warnings = _pcrf.record_measures(**keywords)
    _warn_notes(notes)
    _warn_notes(record_warnings, RecordWarning)
    return _json.loads(text)


def pulse(record=None, series=False, **keywords):
    """What ``pcrf record pulse`` prints, as a dict: whether the record is pulse-like and its
    pulse period ``period_s`` (Baker 2007 on one component; with ``record_h2`` the station's
    other horizontal, Shahi & Baker 2014 over every orientation), and each candidate pulse's
    measures; with ``series=True`` also the velocity, the extracted pulse and the residual
    [cm/s]. ``record`` is a file (keywords as for ``run``) or an array in g (then ``dt_s=``)."""
    if record is not None:
        if isinstance(record, (str, _os.PathLike)):
            keywords["record"] = record
        else:
            keywords["ground_accel_g"] = record
    text, notes = _pcrf.pulse(series=bool(series), **keywords)
    _warn_notes(notes)
    return _json.loads(text)


def record_spectra(paths, periods_s=None, damping=0.05):
    """What ``pcrf record spectra`` writes, as a pandas DataFrame: one row per horizontal
    component (``kind`` "component") and per pair (``kind`` "rotd50"), columns ``name``,
    ``kind``, ``file``, ``file_h2``, ``dt_s``, ``samples``, ``damping``, ``pga_g`` and
    ``sa_g_<T>s`` per period (default 30 from 0.05 s to 10 s). ``paths``: a folder (searched
    for .AT2 files) or files, or a list of them. Write it with ``DataFrame.to_csv(index=False)``
    for ``select``."""
    import io as _io

    import pandas as _pd

    if isinstance(paths, (str, _os.PathLike)):
        paths = [paths]
    periods = [] if periods_s is None else ([periods_s] if not hasattr(periods_s, "__len__") else list(periods_s))
    text, notes = _pcrf.record_spectra([_os.fspath(p) for p in paths], [float(t) for t in periods], float(damping))
    _warn_notes(notes)
    return _pd.read_csv(_io.StringIO(text), comment="#", keep_default_na=False)


def select(target, library, n, kind="rotd50", scale_min=0.25, scale_max=4.0, seed=1):
    """What ``pcrf record select --json`` prints, as a dict: ``n`` records of the spectra table
    ``library`` (a file of ``pcrf record spectra``) with scale factors, whose scaled ln Sa match
    the ``target`` file's mean and sigma (Jayaram, Lin & Baker 2011; Baker & Lee 2018): the
    records (name, kind, file, file_h2, scale, ln_sa), the set's mean and sigma of ln Sa and the
    fit (median_error_percent, sigma_error_percent, sum_of_squares)."""
    return _json.loads(_pcrf.select(_os.fspath(target), _os.fspath(library), int(n), kind, float(scale_min),
                                    float(scale_max), int(seed)))


def settings():
    """Every setting: a list of dicts (table, key, kind, unit, default, doc)."""
    return _pcrf.settings()


def vocabulary():
    """The engine's names, as ``pcrf settings --json`` prints them: ``statuses`` (name, value,
    kind: survived, collapse or no_verdict), ``history_events`` (name, flag, meaning),
    ``parameters`` (the frame's, in axis order: name, long_name, units), ``curve_states`` (an
    IDA cube's curve_state codes), and the cube's own names from its schema: ``cube_names``
    (role: name, e.g. ``IDA_INTENSITY``), ``metrics`` (name, units) and ``metric_roles``
    (``THETA_MAX``: its name); ``pcrf._names`` reads them once."""
    return _json.loads(_pcrf.vocabulary())


def check_output(path, inputs=(), overwrite=False):
    """Refuses ``path`` now as ``write_output`` would (``pcrf.OutputError``, an OSError): when
    it is, or resolves to, one of ``inputs`` (whatever ``overwrite`` says), is a folder, or
    exists and ``overwrite`` is false."""
    _pcrf.check_output(_os.fspath(path), [_os.fspath(p) for p in inputs], overwrite)


def write_output(path, content, inputs=(), overwrite=False):
    """Writes the bytes ``content`` to ``path`` by the rule of every file pcrf writes: never one
    of ``inputs``, an existing file replaced only with ``overwrite``, written beside it and
    renamed over it when complete (a failed write leaves any old file as it was), with the
    user's umask. A refusal or a failed write raises ``pcrf.OutputError`` naming the file."""
    _pcrf.write_output(_os.fspath(path), bytes(content), [_os.fspath(p) for p in inputs], overwrite)


from ._cube import open_cube  # noqa: E402
from ._reports import fragility, p695, risk, sensitivity, stats  # noqa: E402
from ._study import study  # noqa: E402

__all__ = ["run", "Frame", "record_measures", "pulse", "record_spectra", "select", "study", "open_cube", "stats", "fragility", "sensitivity", "p695", "risk",
           "settings", "vocabulary", "check_output", "write_output", "InputError", "OutputError",
           "RecordWarning"]

import atexit as _atexit  # noqa: E402

_atexit.register(_pcrf.finalize_mpi)  # MPI (started by the first pcrf.study) ends with the interpreter
