"""The pcrf executable as a data source: every number a figure shows comes through here."""
import csv
import io
import json
import os
import subprocess
import sys
import tempfile

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


def where_args(where):
    return [arg for w in where for arg in ("-w", w)]


def table(text):
    """CSV text as a list of dicts (strings; empty where pcrf wrote NaN)."""
    return list(csv.DictReader(io.StringIO(text)))


def number(text):
    return float(text) if text not in ("", None) else float("nan")


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

    def stats(self, by, metric, where):
        """Median and 16/84 % percentiles per value of `by`; also what was pooled."""
        out, err = run("cube", "stats", self.path, "--by", by, "-m", metric, *where_args(where))
        pooled = [line.split("also pooled over ", 1)[1] for line in err.splitlines() if "also pooled over" in line]
        return table(out), pooled

    def fragility(self, where):
        """The fitted lognormal of each frame (table) and the fitted data (points)."""
        with tempfile.TemporaryDirectory(prefix="pcrf_plot_") as folder:
            fit, points = os.path.join(folder, "fit.csv"), os.path.join(folder, "points.csv")
            run("cube", "fragility", self.path, *where_args(where), "--csv", fit, "--points", points)
            with open(fit, encoding="utf-8") as f:
                fits = table(f.read())
            with open(points, encoding="utf-8") as f:
                data = table(f.read())
        return fits, data

    def sensitivity(self, metric, where):
        out, _ = run("cube", "sensitivity", self.path, "-m", metric, *where_args(where), "--csv", "-")
        # The aligned table goes to stdout first, then the CSV copy: keep the CSV part.
        lines = out.splitlines()
        start = max(i for i, line in enumerate(lines) if line.startswith("record,"))
        return table("\n".join(lines[start:]) + "\n")

