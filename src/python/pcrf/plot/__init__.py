"""Figures of pcrf results, drawn with matplotlib: ``pcrf plot KIND INPUT -o FILE`` runs
``python3 -m pcrf.plot``, and ``pcrf.plot.figure(KIND, INPUT, ...)`` returns the figure.

Everything is read in process through the module (``pcrf._pcrf``): the cube's axes and
variables (as ``cube info --json``), its rows (``cube export``), the reports (``cube stats``,
``fragility``, ``sensitivity``, ``risk``) and the names (``pcrf.vocabulary()``: statuses,
history event flags, parameters), so every estimator, selection (``-w NAME=VALUE``) and label is
the engine's; this package only draws. The file is written by the engine's output rule
(``pcrf.write_output``). No ``pcrf`` process is started.
"""


def figure(kind, input, **options):
    """The matplotlib figure that ``pcrf plot KIND INPUT`` draws, not written: ``options`` are
    the command's flags as keywords (``where=["kappa=1.2"]``, ``metric=``, ``reduce_over=``,
    ``reduce=[...]``, ``compare_where=[...]``, ``group=``, ``x=``, ``y=``, ``hazard=``,
    ``title=``, ...). A bad input raises ``pcrf.plot.PlotError`` with the command's message."""
    import importlib

    import matplotlib

    from . import style
    from .cli import check_reduction, parser
    from .errors import PlotError

    args = parser().parse_args([kind, str(input), "-o", ""])
    for name, value in options.items():
        if name in ("output", "overwrite") or not hasattr(args, name):
            raise PlotError(f"figure() takes no option {name!r}")
        repeatable = isinstance(getattr(args, name), list) or name == "reduce"
        setattr(args, name, [value] if repeatable and isinstance(value, str) else value)
    check_reduction(args)
    matplotlib.use("Agg")
    style.apply()
    return importlib.import_module(f".{kind}", __package__).draw(args)


def main(argv=None):
    """``pcrf plot ARGV``: draws and writes the figure; returns the exit code (0, or 2 after one line on stderr)."""
    import sys

    from .cli import main as run

    return run(sys.argv[1:] if argv is None else list(argv))


from .errors import PlotError  # noqa: E402

__all__ = ["figure", "main", "PlotError"]
