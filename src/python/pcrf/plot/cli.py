"""``pcrf plot KIND INPUT [-w NAME=VALUE]… [-m METRIC] -o FILE.png|.pdf|.svg``.

Every failure is one line on stderr and exit code 2, and then nothing is written; an
unexpected exception too (its kind, the figure kind and the input named). The
output is written by the rule of every pcrf output (io::OutputFile, through
``pcrf.check_output`` before drawing and ``pcrf.write_output`` with the figure's bytes: never
the input, replaced only with --overwrite, written beside it and renamed into place when
complete, no success for a failed write).
"""
import argparse
import difflib
import importlib
import io
import os
import sys

from .. import _pcrf
from .errors import PlotError

FORMATS = (".png", ".pdf", ".svg")


# The one list of kinds: name → what it draws. Each is the module pcrf.plot.<name>, whose
# draw(args) returns a matplotlib figure.
KINDS = {
    "history": "θ₁, θ̇₁ and ü_g against t, and the phase portrait (a cube's history group or a "
               "pcrf run --history CSV)",
    "sweep": "one panel per varied parameter: median and 16–84 % band across records, collapses apart",
    "ida": "IDA curves per record, one panel per frame, with the collapse intensities' median and 16/84 %",
    "spectrum": "rocking spectrum of an IDA over pulses: collapse amplitude over the uplift threshold against "
                "omega_p/p, one line per pulse shape, overturning and fracture marked apart",
    "fragility": "collapse fractions or IDA collapse points, the fitted lognormal and its 90 % interval",
    "risk": "collapse risk at a site (--hazard FILE): the hazard curve, each frame's fragility and the "
            "deaggregation of its annual collapse rate, on one figure",
    "sensitivity": "first-order and total Sobol' indices with their 90 % intervals",
    "status": "map of the status over two axes (--x, --y), the others selected with -w",
    "table3": "the paper comparison (docs/paper_comparison.csv)",
    "pulse": "a record's velocity, its extracted velocity pulse and the residual (JSON of pcrf record pulse --series)",
    "selection": "target median and ±σ, the selected scaled spectra and their median (JSON of pcrf record select --json)",
}


# The kinds that can show a metric reduced over an axis (--reduce-over): they draw what cube
# stats or cube fragility compute. status maps each case's own end (select an orientation with
# -w, or map it with --x incidence_deg); history is one case; spectrum's pulses have no
# orientation; sensitivity's saltelli samples are frames; table3 is a fixed table.
REDUCING = ("sweep", "ida", "fragility")


class Parser(argparse.ArgumentParser):
    def error(self, message):
        raise PlotError(message + self.flag_meant(message))

    def flag_meant(self, message):
        """" (did you mean --where?)" for an unknown flag, as the engine's commands say it:
        its own spelling with dashes for underscores, else the closest flag."""
        if not message.startswith("unrecognized arguments: "):
            return ""
        word = message.split(": ", 1)[1].split()[0].split("=")[0]
        known = [o for action in self._actions for o in action.option_strings]
        dashed = "--" + word.lstrip("-").replace("_", "-")
        meant = dashed if dashed in known else next(iter(difflib.get_close_matches(word, known, n=1)), None)
        return f" (did you mean {meant}?)" if meant else ""


def parser():
    p = Parser(prog="pcrf plot", description="Draw a figure of a result cube, a history or the paper comparison.",
               formatter_class=argparse.RawDescriptionHelpFormatter,
               epilog="kinds:\n" + "\n".join(f"  {k:12s} {v}" for k, v in KINDS.items()))
    p.add_argument("kind", choices=list(KINDS), metavar="KIND", help="what to draw (below)")
    p.add_argument("input", metavar="INPUT", help="result cube (.h5), history CSV, or comparison CSV")
    p.add_argument("-w", "--where", action="append", default=[], metavar="NAME=VALUE",
                   help="keep cases with this coordinate value (repeatable; as in pcrf cube export)")
    p.add_argument("-m", "--metric", help="metric to draw (sweep, ida, sensitivity; default theta_max_rad)")
    p.add_argument("-o", "--output", required=True, metavar="FILE", help="figure file: .png, .pdf or .svg")
    p.add_argument("--overwrite", action="store_true", help="replace an existing output file")
    p.add_argument("--group", help="history: the cube's history group (default: its only one)")
    p.add_argument("--x", help="status: axis across (default: the first axis with several values)")
    p.add_argument("--y", help="status: axis up (default: the second axis with several values)")
    p.add_argument("--reduce-over", metavar="DIM",
                   help="sweep, ida, fragility: reduce over this axis first, in the engine (incidence_deg: each "
                        "record's orientations; as cube stats / cube fragility --reduce-over)")
    p.add_argument("--reduce", metavar="HOW", action="append",
                   help="with --reduce-over: max, min or median (default: the worst: max of the response for "
                        "sweep, min of the collapse intensity for ida and fragility); fragility: repeat it for a "
                        "fit of each")
    p.add_argument("--compare-where", action="append", default=[], metavar="NAME=VALUE",
                   help="fragility: also the fit of the cases with this coordinate value, not reduced "
                        "(e.g. incidence_deg=0, fault-normal, beside --reduce-over incidence_deg; repeatable)")
    p.add_argument("--hazard", metavar="FILE", help="risk: the site's hazard curve CSV (as pcrf cube risk --hazard)")
    p.add_argument("--tail", default="power-law", help="risk: beyond the curve's last point, power-law or cut-off")
    p.add_argument("--years", type=float, default=50.0, help="risk: t of p_collapse_in_years (default 50)")
    p.add_argument("--title", help="figure title (default: what the figure shows)")
    return p




def check_reduction(args):
    if (args.reduce_over or args.reduce) and args.kind not in REDUCING:
        raise PlotError(f"{args.kind} does not reduce over an axis (--reduce-over goes with {', '.join(REDUCING)})")
    if args.reduce and len(args.reduce) > 1 and args.kind != "fragility":
        raise PlotError(f"{args.kind} draws one reduction: give --reduce once")
    if args.compare_where and args.kind != "fragility":
        raise PlotError("--compare-where goes with fragility")


def check_paths(args):
    if not os.path.exists(args.input):
        raise PlotError(f"{args.input}: no such file")
    ext = os.path.splitext(args.output)[1].lower()
    if ext not in FORMATS:
        raise PlotError(f"{args.output}: the output must end in .png, .pdf or .svg")
    _pcrf.check_output(args.output, [args.input], args.overwrite)


def save(figure, args):
    """The figure's bytes, written by the engine's output rule: complete or not at all."""
    image = io.BytesIO()
    figure.savefig(image, format=os.path.splitext(args.output)[1].lower()[1:], bbox_inches="tight")
    _pcrf.write_output(args.output, image.getvalue(), [args.input], args.overwrite)


def main(argv):
    args = None
    try:
        args = parser().parse_args(argv)
        check_reduction(args)
        check_paths(args)
        try:
            import matplotlib
            matplotlib.use("Agg")
            import numpy  # noqa: F401 (matplotlib needs it; named here for the message)
        except ImportError as e:
            package = "python3-numpy" if "numpy" in str(e) else "python3-matplotlib"
            raise PlotError(f"{e.name or 'matplotlib'} not found: apt-get install {package}") from e
        from . import style
        style.apply()
        figure = importlib.import_module(f".{args.kind}", __package__).draw(args)
        save(figure, args)
        panels = len(figure.axes)
        print(f"pcrf plot: wrote {args.output} ({args.kind}, {panels} panel{'' if panels == 1 else 's'})")
        return 0
    except (PlotError, _pcrf.OutputError) as e:  # an OutputError names the file and what went wrong
        print(f"pcrf plot: error: {e}", file=sys.stderr)
        return 2
    except OSError as e:
        print(f"pcrf plot: error: {e.filename or ''}: {e.strerror}", file=sys.stderr)
        return 2
    except Exception as e:  # noqa: BLE001 (a bug or an input no check foresaw: still one line)
        kind, source = (args.kind, args.input) if args else (" ".join(argv[:1]) or "?", " ".join(argv[1:2]) or "?")
        text = " ".join(str(e).split()) or "no message"
        print(f"pcrf plot: error: {kind} {source}: unexpected {type(e).__name__}: {text}", file=sys.stderr)
        return 2
