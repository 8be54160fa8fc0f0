"""`sweep`: one panel per varied parameter, the median of a metric across records and its
16–84 % band against the parameter's value; collapsed cases are counted apart (numbers
above the panel's points), as `pcrf cube stats` does."""
import math

import matplotlib.pyplot as plt
import numpy as np

from .. import _names as schema
from . import engine, style
from .errors import PlotError

def varied_parameters(cube, metric, where):
    """The parameters the cube varies (one-at-a-time: its varied_parameter values; a grid:
    the parameter axes with several values), in the model's order."""
    rows = cube.export([metric], where)
    if not rows:
        raise PlotError(f"{cube.path}: no case matches the selection")
    if schema.VARIED_PARAMETER in rows[0]:
        named = {r[schema.VARIED_PARAMETER] for r in rows} - {"none"}
        return [p for p in engine.parameters() if p in named]
    return [p for p in engine.parameters() if p in rows[0] and len({r[p] for r in rows}) > 1]


def draw(args):
    cube = engine.Cube(args.input)
    metric = args.metric or schema.THETA_MAX
    cube.require_metric(metric, "sweep")
    parameters = varied_parameters(cube, metric, args.where)
    if not parameters:
        raise PlotError(f"{args.input}: no parameter varies among the selected cases (a sweep needs a "
                        "one-at-a-time plan or a grid axis with several values)")
    columns = min(4, len(parameters))
    rows = math.ceil(len(parameters) / columns)
    fig, axes = plt.subplots(rows, columns, figsize=(3.6 * columns, 3.2 * rows), squeeze=False,
                             sharey=True, constrained_layout=True)
    pooled_over, reduced = set(), ""
    for ax, parameter in zip(axes.flat, parameters):
        stats, pooled, reduced = cube.stats(parameter, metric, args.where, engine.reduction(args))
        pooled_over.update(pooled)
        x = np.array([engine.number(r[parameter]) for r in stats])
        median = np.array([engine.number(r["median"]) for r in stats])
        low = np.array([engine.number(r["p16"]) for r in stats])
        high = np.array([engine.number(r["p84"]) for r in stats])
        collapses = [r["collapses"] for r in stats]
        ax.fill_between(x, low, high, color=style.SKY_BLUE, alpha=0.4, lw=0, label="16–84 %")
        ax.plot(x, median, "o-", color=style.BLUE, ms=4, label="median")
        for xi, c in zip(x, collapses):
            if c:
                ax.annotate(f"{c}✕", (xi, 1.0), xycoords=("data", "axes fraction"), ha="center", va="bottom",
                            color=style.VERMILLION, fontsize=9)
        ax.set_xlabel(style.parameter_label(parameter))
    for ax in axes.flat[len(parameters):]:
        ax.remove()
    for ax in axes[:, 0]:
        ax.set_ylabel(style.metric_label(metric, cube.variable(metric)))
    axes.flat[0].legend(loc="upper left")
    note = "collapsed cases (tendon fracture, overturned) counted apart: n✕ above the panel"
    if reduced:
        note = (f"each record's {reduced} (pcrf cube stats --reduce-over); a reduction that is a collapse is "
                "counted apart: n✕ above the panel")
    if pooled_over:
        note += "; pooled over " + ", ".join(sorted(pooled_over)) + " (select with -w)"
    fig.suptitle(args.title or f"Parameter sweeps across {len(cube.dimension(schema.RECORD)['values'])} records")
    fig.text(0.5, -0.02, note, ha="center", va="top", fontsize=9)
    return fig
