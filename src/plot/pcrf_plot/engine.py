"""The pcrf executable as a data source: every number a figure shows comes through here."""
import csv
import io
import json
import os
import subprocess
import sys

from pcrf_plot.errors import PlotError


def executable():
    """The pcrf binary that started this plot (``pcrf plot`` sets PCRF_EXECUTABLE)."""
    path = os.environ.get("PCRF_EXECUTABLE", "pcrf")
    return path


def run(*args, stdin=None):
    """Runs ``pcrf ARGS`` (with the bytes `stdin` as its input) and returns (stdout, stderr);
    a failure becomes a PlotError carrying pcrf's own one-line message."""
    try:
        done = subprocess.run([executable(), *args], capture_output=True, input=stdin)
    except OSError as e:
        raise PlotError(f"cannot run {executable()}: {e.strerror}") from e
    stdout, stderr = done.stdout.decode(errors="replace"), done.stderr.decode(errors="replace")
    if done.returncode != 0:
        lines = [line for line in stderr.splitlines() if line.strip()]
        message = lines[-1] if lines else f"pcrf {' '.join(args)} failed with exit code {done.returncode}"
        raise PlotError(message.removeprefix("pcrf: error: ").removeprefix("pcrf: "))
    return stdout, stderr


def run_json(*args):
    """Runs ``pcrf ARGS`` that prints one JSON object; returns it."""
    out, _ = run(*args)
    try:
        return json.loads(out)
    except json.JSONDecodeError as e:
        raise PlotError(f"pcrf {' '.join(args)}: not JSON ({e.msg})") from e


_VOCABULARY = None


def vocabulary():
    """The engine's names (``pcrf settings --json``): statuses with their kind (survived,
    collapse, no_verdict), history event flags, frame parameters in axis order."""
    global _VOCABULARY
    if _VOCABULARY is None:
        _VOCABULARY = run_json("settings", "--json")
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


def where_args(where):
    return [arg for w in where for arg in ("-w", w)]


def reduction_args(args, how=None):
    """``--reduce-over DIM [--reduce HOW]`` as given to ``pcrf plot`` (`how`: one of several
    --reduce; default the only one), for the engine's cube stats and cube fragility, which
    reduce (and check the names); without --reduce each takes its worst: the largest response
    (stats) or the smallest collapse intensity (fragility)."""
    how = how or (args.reduce[0] if args.reduce else None)
    flags = ["--reduce-over", args.reduce_over] if args.reduce_over else []
    return flags + (["--reduce", how] if how else [])


def table(text):
    """CSV text as a list of dicts (strings; empty where pcrf wrote NaN)."""
    return list(csv.DictReader(io.StringIO(text)))


def number(value):
    """A CSV text or a JSON value as a float; NaN where it is missing (empty, null)."""
    return float(value) if value not in ("", None) else float("nan")


def reduced_text(report):
    """"min over incidence_deg" from a reduced report's fields; "" when it is not reduced."""
    return f"{report['reduction']} over {report['reduced_over']}" if report.get("reduced_over") else ""


class Cube:
    """A result cube, read through pcrf."""

    def __init__(self, path):
        self.path = str(path)
        out, err = run("cube", "info", "--json", self.path)
        self.info = json.loads(out)
        # A partial cube (cases never run), or one a run is writing: the figure shows the
        # cases run so far; say so.
        for line in err.splitlines():
            if "not run (a partial cube)" in line or "a run holds it" in line:
                print("pcrf plot:" + line.split(":", 1)[1], file=sys.stderr)

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
        args = ["cube", "export", self.path, *where_args(where)]
        for m in metrics:
            args += ["-m", m]
        out, _ = run(*args)
        return table(out)

    def history(self, label):
        out, _ = run("cube", "export", self.path, "--history", label)
        return table(out)

    def stats(self, by, metric, where, reduction=()):
        """Median and 16/84 % percentiles per value of `by` (rows of ``cube stats --json``),
        the metric first reduced over an axis by the engine when `reduction` holds its flags
        (reduction_args); also the axes pooled over besides the records, and reduced_text()."""
        report = run_json("cube", "stats", self.path, "--by", by, "-m", metric, *where_args(where), *reduction, "--json")
        pooled = [w.removeprefix("also pooled over ") for w in report["warnings"] if w.startswith("also pooled over ")]
        return report["groups"], pooled, reduced_text(report)

    def fragility(self, where, reduction=()):
        """``cube fragility --json``: the fitted lognormal of each frame (`frames`), the fitted
        data (`points`) and the intensity's units (`intensity_units`); with `reduction`, of each
        record's collapse intensity reduced over an axis by the engine (`reduced_over`, `reduction`)."""
        return run_json("cube", "fragility", self.path, *where_args(where), *reduction, "--json")

    def sensitivity(self, metric, where):
        """The rows of ``cube sensitivity --json``."""
        return run_json("cube", "sensitivity", self.path, "-m", metric, *where_args(where), "--json")["indices"]
