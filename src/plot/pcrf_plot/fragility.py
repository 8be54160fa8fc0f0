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


def column(fit, prefix):
    """The fit table's column that starts with `prefix` (its name carries the units)."""
    for key, value in fit.items():
        if key == prefix or key.startswith(prefix + " ["):
            return engine.number(value)
    return float("nan")


def draw(args):
    cube = engine.Cube(args.input)
    fits, points = cube.fragility(args.where)
    if not fits:
        raise PlotError(f"{args.input}: no frame to fit among the selected cases")
    units = next((k.split("[", 1)[1].rstrip("]") for k in fits[0] if k.startswith("median [")), "")
    fig, ax = plt.subplots(figsize=(7, 4.6), constrained_layout=True)
    top = max([engine.number(p["intensity"]) for p in points] + [column(f, "median_95%") for f in fits
                                                                  if math.isfinite(column(f, "median_95%"))])
    x = np.linspace(top * 1e-3, top * 1.25, 400)
    for colour, fit in zip(style.CYCLE, fits):
        frame = fit["frame"]
        mine = [p for p in points if p["frame"] == frame]
        stripes = [p for p in mine if p["kind"] == "stripe" and engine.number(p["trials"]) > 0]
        collapses = sorted(engine.number(p["intensity"]) for p in mine if p["kind"] == "collapse")
        censored = [engine.number(p["intensity"]) for p in mine if p["kind"] == "censored"]
        if stripes:
            ax.plot([engine.number(p["intensity"]) for p in stripes],
                    [engine.number(p["collapses"]) / engine.number(p["trials"]) for p in stripes],
                    "o", color=colour, ms=5, mfc="none")
        if collapses:
            n = len(collapses) + len(censored)
            ax.plot(collapses, np.arange(1, len(collapses) + 1) / n, "o", color=colour, ms=4, mfc="none")
        if censored:
            ax.plot(censored, np.ones(len(censored)), "v", color=colour, ms=5)
        median, beta = column(fit, "median"), column(fit, "beta")
        if math.isfinite(median) and math.isfinite(beta):
            label = f"{frame}: median {median:.3g} {units}, β = {beta:.2f}"
            ax.plot(x, lognormal_cdf(x, median, beta), "-", color=colour, lw=1.8, label=label)
            low, high = column(fit, "median_5%"), column(fit, "median_95%")
            if math.isfinite(low) and math.isfinite(high):
                ax.fill_between(x, lognormal_cdf(x, high, beta), lognormal_cdf(x, low, beta), color=colour,
                                alpha=0.18, lw=0)
        else:
            ax.plot([], [], "o", color=colour, mfc="none", label=f"{frame}: no fit (too few collapses)")
    kind = "collapse fraction per stripe" if any(p["kind"] == "stripe" for p in points) else \
        "IDA collapse intensities (empirical; ▼ censored)"
    ax.set(xlabel=style.intensity_label(cube, units), ylabel="probability of collapse [–]", ylim=(-0.02, 1.05),
           xlim=(0, x[-1]), title=args.title or f"Collapse fragility: {kind}")
    ax.legend(loc="lower right", title="lognormal fit (band: 90 % interval of the median)")
    return fig
