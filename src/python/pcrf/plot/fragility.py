"""`fragility`: the probability of collapse against intensity. Stripes (a grid cube with an
intensity axis): the fraction of records that collapsed at each intensity. IDA: the empirical
distribution of the curves' collapse intensities (censored curves marked at the top, unresolved
ones, bounded at their last safe intensity, as hollow squares at the top; the legend counts
both, and a stripe figure's title counts the cases without a verdict left out). With
each frame's lognormal fitted by `pcrf cube fragility` and the band between the fits at the
ends of its median's 90 % bootstrap interval. With --reduce-over, the engine first reduces each
record's collapse intensities over that axis (e.g. the worst orientation: min over incidence_deg)."""
import math

import matplotlib.pyplot as plt
import numpy as np

from .. import _names as schema
from . import engine, style
from .errors import PlotError


def lognormal_cdf(x, median, beta):
    return 0.5 * (1.0 + np.vectorize(math.erf)(np.log(x / median) / (beta * math.sqrt(2.0))))


def series_of(cube, args):
    """(label prefix, cube fragility report) of each fit drawn: the selection, reduced once per
    --reduce (or not), then each --compare-where selection, not reduced."""
    reductions = args.reduce or [None]
    series = [("", cube.fragility(args.where, engine.reduction(args, how))) for how in reductions]
    if len(series) > 1 or args.compare_where:
        series = [(engine.reduced_text(r) or "all", r) for _, r in series]
    series += [(w, cube.fragility(args.where + [w])) for w in args.compare_where]
    return series


def draw(args):
    cube = engine.Cube(args.input)
    series = series_of(cube, args)
    units = series[0][1]["intensity_units"]
    if not any(r["frames"] for _, r in series):
        raise PlotError(f"{args.input}: no frame to fit among the selected cases")
    num = engine.number
    fig, ax = plt.subplots(figsize=(7, 4.6), constrained_layout=True)
    top = max([num(p[schema.INTENSITY]) for _, r in series for p in r["points"]] +
              [num(f["median_95%"]) for _, r in series for f in r["frames"] if math.isfinite(num(f["median_95%"]))] +
              [1e-9])
    x = np.linspace(top * 1e-3, top * 1.25, 400)
    drawn = [(prefix, fit, r["points"]) for prefix, r in series for fit in r["frames"]]
    counts = {"censored": 0, "unresolved": 0, "no_verdict": 0}
    banded = False
    for colour, (prefix, fit, points) in zip(style.CYCLE, drawn):
        frame = fit["frame"]
        name = frame if not prefix else prefix if frame in ("all", prefix) else f"{prefix}, {frame}"
        mine = [p for p in points if p["frame"] == frame]
        stripes = [p for p in mine if p["kind"] == "stripe" and num(p["trials"]) > 0]
        collapses = sorted(num(p[schema.INTENSITY]) for p in mine if p["kind"] == "collapse")
        censored = [num(p[schema.INTENSITY]) for p in mine if p["kind"] == "censored"]
        unresolved = [num(p[schema.INTENSITY]) for p in mine if p["kind"] == "unresolved"]
        if stripes:
            ax.plot([num(p[schema.INTENSITY]) for p in stripes],
                    [num(p["collapses"]) / num(p["trials"]) for p in stripes],
                    "o", color=colour, ms=5, mfc="none")
        if collapses:
            n = len(collapses) + len(censored) + len(unresolved)
            ax.plot(collapses, np.arange(1, len(collapses) + 1) / n, "o", color=colour, ms=4, mfc="none")
        if censored:
            ax.plot(censored, np.ones(len(censored)), "v", color=colour, ms=5)
            counts["censored"] += len(censored)
        if unresolved:
            ax.plot(unresolved, np.ones(len(unresolved)), "s", color=colour, ms=7, mfc="none", mew=1.4)
            counts["unresolved"] += len(unresolved)
        all_stripes = [p for p in mine if p["kind"] == "stripe"]
        counts["no_verdict"] += round(num(fit["records"]) * len(all_stripes) - sum(num(p["trials"]) for p in all_stripes))
        median, beta = num(fit["median"]), num(fit["beta"])
        if math.isfinite(median) and math.isfinite(beta):
            label = f"{name}: median {median:.3g} {units}, β = {beta:.2f}"
            ax.plot(x, lognormal_cdf(x, median, beta), "-", color=colour, lw=1.8, label=label)
            low, high = num(fit["median_5%"]), num(fit["median_95%"])
            if math.isfinite(low) and math.isfinite(high):
                banded = True
                ax.fill_between(x, lognormal_cdf(x, high, beta), lognormal_cdf(x, low, beta), color=colour,
                                alpha=0.18, lw=0)
        else:
            ax.plot([], [], "o", color=colour, mfc="none", label=f"{name}: no fit (the data cannot fix a median and a β)")
    points = [p for _, r in series for p in r["points"]]
    kind = "collapse fraction per stripe" if any(p["kind"] == "stripe" for p in points) else \
        "IDA collapse intensities (empirical; ▼ censored)"
    if len(series) == 1 and engine.reduced_text(series[0][1]):
        kind = f"each record's {engine.reduced_text(series[0][1])} of its IDA collapse intensities (▼ censored)"
    if counts["censored"]:
        ax.plot([], [], "v", color=style.GREY, ms=5, label=f"censored: safe up to max_intensity ({counts['censored']})")
    if counts["unresolved"]:
        ax.plot([], [], "s", color=style.GREY, ms=7, mfc="none", mew=1.4,
                label=f"unresolved: no verdict above its last safe run ({counts['unresolved']})")
    if counts["no_verdict"]:
        kind += f"\n{counts['no_verdict']} cases without a verdict (or not run) left out"
    ax.set(xlabel=style.intensity_label(cube, units), ylabel="probability of collapse [–]", ylim=(-0.02, 1.05),
           xlim=(0, x[-1]), title=args.title or f"Collapse fragility: {kind}")
    ax.legend(loc="lower right", title="lognormal fit (band: 90 % interval of the median)" if banded else
              "lognormal fit (fewer than 10 curves or records: no interval)")
    return fig
