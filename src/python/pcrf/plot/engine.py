"""The engine as a data source, in process: every number a figure shows comes through here,
from the C++ that the command line runs (``pcrf._pcrf``: the same reports, the same cube
reader, the same names), never from the text of a ``pcrf`` process."""
import csv
import json

from .. import _pcrf
from .._notices import warn
from .._reports import said as _said
from .errors import PlotError

# What a bad input raises in the engine (pcrf.InputError, a ValueError) and a
# failure no check foresaw (RuntimeError): either is the figure's one-line error.
ENGINE_ERRORS = (_pcrf.InputError, RuntimeError)


def call(function, *args, **keywords):
    """`function(*args, **keywords)` of the engine; its error becomes a PlotError with its message."""
    try:
        return function(*args, **keywords)
    except ENGINE_ERRORS as e:
        raise PlotError(str(e)) from e


def report(kind, cube, **keywords):
    """``pcrf cube KIND --json``'s object (stats, fragility, sensitivity, risk), from the same C++."""
    return call(_said, kind, cube, **keywords)[0]  # as pcrf plot always drew: the cube's notes said by Cube


_VOCABULARY = None


def vocabulary():
    """The engine's names (``pcrf.vocabulary()``, as ``pcrf settings --json``): statuses with
    their kind (survived, collapse, no_verdict), history event flags, frame parameters in axis
    order, an IDA's curve states."""
    global _VOCABULARY
    if _VOCABULARY is None:
        _VOCABULARY = json.loads(_pcrf.vocabulary())
    return _VOCABULARY


def statuses():
    return [s["name"] for s in vocabulary()["statuses"]]


def collapse_statuses():
    return {s["name"] for s in vocabulary()["statuses"] if s["kind"] == "collapse"}


def status_kind(name):
    return next((s["kind"] for s in vocabulary()["statuses"] if s["name"] == name), "no_verdict")


def curve_state(name):
    """The code of an IDA curve state ("bracketed", "censored", "unbracketed", "unresolved") in
    a cube's ``curve_state``; None when the engine has no such state."""
    return next((c["value"] for c in vocabulary().get("curve_states", []) if c["name"] == name), None)


def no_verdict_statuses():
    """Statuses that say nothing of the frame: neither safe nor collapsed (still rocking at
    the end, ground in free fall, invalid frame, failures)."""
    return {s["name"] for s in vocabulary()["statuses"] if s["kind"] == "no_verdict"}


def event_flag(name):
    """The bit of a history event ("impact", "stop")."""
    for e in vocabulary()["history_events"]:
        if e["name"] == name:
            return e["flag"]
    raise PlotError(f"the engine has no history event {name!r}")


def parameters():
    """The frame parameters' names, in the model's (axis) order."""
    return [p["name"] for p in vocabulary()["parameters"]]


def reduction(args, how=None):
    """``--reduce-over DIM [--reduce HOW]`` as given to ``pcrf plot`` (`how`: one of several
    --reduce; default the only one), as the keywords of the engine's stats and fragility
    reports, which reduce (and check the names); without --reduce each takes its worst: the
    largest response (stats) or the smallest collapse intensity (fragility)."""
    how = how or (args.reduce[0] if args.reduce else None)
    return {"reduce_over": args.reduce_over, "reduce": how}


def read_csv(path):
    """A CSV file (a ``pcrf run --history`` or the paper comparison) as a list of dicts of
    strings, empty where pcrf wrote NaN."""
    with open(path, encoding="utf-8", newline="") as f:
        return list(csv.DictReader(f))


def number(value):
    """A field or a JSON value as a float; NaN where it is missing (empty, null)."""
    return float(value) if value not in ("", None) else float("nan")


def reduced_text(report):
    """"min over incidence_deg" from a reduced report's fields; "" when it is not reduced."""
    return f"{report['reduction']} over {report['reduced_over']}" if report.get("reduced_over") else ""


class Cube:
    """A result cube, read in process by the engine's cube reader."""

    def __init__(self, path):
        self.path = str(path)
        info, notes = call(_pcrf.cube_info, self.path)
        self.info = json.loads(info)
        # A partial cube (cases never run), or one a run is writing: the figure shows the
        # cases run so far; say so (pcrf plot prints it on stderr).
        warn(notes)

    @property
    def dimensions(self):
        return self.info["dimensions"]

    def dimension(self, name):
        for d in self.dimensions:
            if d["name"] == name:
                return d
        return None

    def variable(self, name):
        """Name, units and long name of a metric or side variable, or None."""
        for v in self.info["metrics"] + self.info["side_variables"]:
            if v["name"] == name:
                return v
        return None

    def require_metric(self, name, kind):
        if self.variable(name) is None:
            names = ", ".join(m["name"] for m in self.info["metrics"])
            raise PlotError(f"{self.path}: `{kind}` needs the metric {name}, which the cube lacks (it has: {names})")

    def export(self, metrics, where):
        """The rows of ``pcrf cube export`` (dicts: coordinates, status, the metrics; each the
        text the CSV holds, "" for NaN)."""
        header, rows = call(_pcrf.cube_export, self.path, list(metrics), list(where))
        return [dict(zip(header, row)) for row in rows]

    def history(self, label):
        """The history group `label`: {column: float array}."""
        return call(_pcrf.cube_history, self.path, label)

    def stats(self, by, metric, where, reduction=None):
        """Median and 16/84 % percentiles per value of `by` (rows of ``cube stats``), the
        metric first reduced over an axis by the engine when `reduction` holds its keywords
        (engine.reduction); also the axes pooled over besides the records, and reduced_text()."""
        r = report("stats", self.path, by=by, metric=metric, where=list(where), **(reduction or {}))
        pooled = [w.removeprefix("also pooled over ") for w in r["warnings"] if w.startswith("also pooled over ")]
        return r["groups"], pooled, reduced_text(r)

    def fragility(self, where, reduction=None):
        """``cube fragility``'s report: the fitted lognormal of each frame (`frames`), the fitted
        data (`points`) and the intensity's units (`intensity_units`); with `reduction`, of each
        record's collapse intensity reduced over an axis by the engine (`reduced_over`, `reduction`)."""
        return report("fragility", self.path, where=list(where), **(reduction or {}))

    def sensitivity(self, metric, where):
        """The rows of ``cube sensitivity``'s indices."""
        return report("sensitivity", self.path, metric=metric, where=list(where))["indices"]
