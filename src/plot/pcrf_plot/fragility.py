"""`fragility`: the probability of collapse against intensity. Stripes (a grid cube with an
intensity axis): the fraction of records that collapsed at each intensity. IDA: the empirical
distribution of the curves' collapse intensities (censored curves marked at the top). With
each frame's lognormal fitted by `pcrf cube fragility` and the band between the fits at the
ends of its median's 90 % bootstrap interval."""
import math

import matplotlib.pyplot as plt
import numpy as np

from pcrf_plot import engine, style
from pcrf_plot.errors import PlotError


def lognormal_cdf(x, median, beta):
    return 0.5 * (1.0 + np.vectorize(math.erf)(np.log(x / median) / (beta * math.sqrt(2.0))))


def draw(args):
    cube = engine.Cube(args.input)
    report = cube.fragility(args.where)
    fits, points, units = report["frames"], report["points"], report["intensity_units"]
    if not fits:
        raise PlotError(f"{args.input}: no frame to fit among the selected cases")
    num = engine.number
    fig, ax = plt.subplots(figsize=(7, 4.6), constrained_layout=True)
    top = max([num(p["intensity"]) for p in points] + [num(f["median_95%"]) for f in fits
                                                        if math.isfinite(num(f["median_95%"]))] + [1e-9])
    x = np.linspace(top * 1e-3, top * 1.25, 400)
    for colour, fit in zip(style.CYCLE, fits):
        frame = fit["frame"]
        mine = [p for p in points if p["frame"] == frame]
        stripes = [p for p in mine if p["kind"] == "stripe" and num(p["trials"]) > 0]
        collapses = sorted(num(p["intensity"]) for p in mine if p["kind"] == "collapse")
        censored = [num(p["intensity"]) for p in mine if p["kind"] == "censored"]
        if stripes:
            ax.plot([num(p["intensity"]) for p in stripes],
                    [num(p["collapses"]) / num(p["trials"]) for p in stripes],
                    "o", color=colour, ms=5, mfc="none")
        if collapses:
            n = len(collapses) + len(censored)
            ax.plot(collapses, np.arange(1, len(collapses) + 1) / n, "o", color=colour, ms=4, mfc="none")
        if censored:
            ax.plot(censored, np.ones(len(censored)), "v", color=colour, ms=5)
        median, beta = num(fit["median"]), num(fit["beta"])
        if math.isfinite(median) and math.isfinite(beta):
            label = f"{frame}: median {median:.3g} {units}, β = {beta:.2f}"
            ax.plot(x, lognormal_cdf(x, median, beta), "-", color=colour, lw=1.8, label=label)
            low, high = num(fit["median_5%"]), num(fit["median_95%"])
            if math.isfinite(low) and math.isfinite(high):
                ax.fill_between(x, lognormal_cdf(x, high, beta), lognormal_cdf(x, low, beta), color=colour,
                                alpha=0.18, lw=0)
        else:
            ax.plot([], [], "o", color=colour, mfc="none", label=f"{frame}: no fit (the data cannot fix a median and a β)")
    kind = "collapse fraction per stripe" if any(p["kind"] == "stripe" for p in points) else \
        "IDA collapse intensities (empirical; ▼ censored)"
    ax.set(xlabel=style.intensity_label(cube, units), ylabel="probability of collapse [–]", ylim=(-0.02, 1.05),
           xlim=(0, x[-1]), title=args.title or f"Collapse fragility: {kind}")
    ax.legend(loc="lower right", title="lognormal fit (band: 90 % interval of the median)")
    return fig
