"""`sensitivity`: first-order (S1) and total (ST) Sobol' indices of each parameter, bars with
the 90 % bootstrap intervals that `pcrf cube sensitivity` estimates."""
import matplotlib.pyplot as plt
import numpy as np

from .. import _names as schema
from . import engine, style
from .errors import PlotError


def draw(args):
    cube = engine.Cube(args.input)
    metric = args.metric or schema.THETA_MAX
    if metric != "collapse":
        cube.require_metric(metric, "sensitivity")
    rows = [r for r in cube.sensitivity(metric, args.where) if r[schema.RECORD] == "all"]
    if not rows:
        raise PlotError(f"{args.input}: no indices for the selection")
    names = [r["parameter"] for r in rows]
    x = np.arange(len(names))
    fig, ax = plt.subplots(figsize=(max(6.0, 0.9 * len(names) + 2), 4.2), constrained_layout=True)
    for offset, (index, colour, label) in zip((-0.2, 0.2), (("S1", style.BLUE, "first order $S_1$"),
                                                             ("ST", style.ORANGE, "total $S_T$"))):
        value = np.array([engine.number(r[index]) for r in rows])
        low = np.array([engine.number(r[index + "_5%"]) for r in rows])
        high = np.array([engine.number(r[index + "_95%"]) for r in rows])
        ax.bar(x + offset, value, width=0.4, color=colour, label=label)
        ax.errorbar(x + offset, value, yerr=[value - low, high - value], fmt="none", ecolor=style.BLACK, capsize=3,
                    lw=1)
    ax.axhline(0.0, color=style.BLACK, lw=0.8)
    ax.set_xticks(x, [style.PARAMETER_SYMBOLS.get(n, n) for n in names])
    what = "collapse (tendon fracture or overturned)" if metric == "collapse" else \
        style.metric_label(metric, cube.variable(metric))
    ax.set(ylabel="Sobol' index [–]", xlabel="parameter",
           title=args.title or f"Sensitivity of {what}, {rows[0]['samples']} base samples")
    ax.legend(title="error bars: 90 % bootstrap interval")
    return fig
