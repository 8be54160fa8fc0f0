"""`risk`: a cube's collapse risk at a site, from `pcrf cube risk --json`, on one figure with
intensity across: the hazard curve λ(im) with the risk-targeted and the 2 %-in-50-years
intensities; each frame's fragility (the fitted lognormal, the empirical steps); and the
deaggregation of λ_c over intensity (the lognormal's as bars, the empirical's as steps)."""
import math

import matplotlib.pyplot as plt
import numpy as np

from .. import _names as schema
from . import engine, style
from .errors import PlotError
from .fragility import lognormal_cdf


def report(args):
    return engine.report("risk", args.input, hazard=args.hazard, tail=args.tail, years=args.years, where=args.where)


def draw_hazard(ax, r, units):
    num = engine.number
    x = [num(p[schema.INTENSITY]) for p in r["hazard"]]
    y = [num(p["annual_rate_per_yr"]) for p in r["hazard"]]
    ax.loglog(x, y, "o-", color=style.BLACK, ms=4, lw=1.6, label=f"hazard curve ({r['hazard_file']})")
    if r["tail"] == "power-law" and len(x) > 1:
        k = -math.log(y[-1] / y[-2]) / math.log(x[-1] / x[-2])
        xt = np.geomspace(x[-1], x[-1] * 4, 20)
        ax.loglog(xt, y[-1] * (xt / x[-1]) ** -k, ":", color=style.BLACK, lw=1.4, label="power-law extension")
    # Solid and dashed: the two often nearly coincide (a risk coefficient near 1).
    for field, colour, line, label in (("risk_targeted_intensity", style.VERMILLION, "-", "risk-targeted"),
                                       ("uniform_hazard_intensity_2pct_50yr", style.GREEN, "--", "2 % in 50 years")):
        value = num(r.get(field))
        if math.isfinite(value):
            ax.axvline(value, color=colour, ls=line, lw=1.4, label=f"{label}: {value:.3g} {units}")
    ax.set_ylabel("annual rate of exceedance λ [1/yr]")
    ax.legend(loc="lower left")


def draw_fragility(ax, r, x):
    num = engine.number
    for colour, frame in zip(style.CYCLE, r["frames"]):
        median, beta = num(frame["median"]), num(frame["beta"])
        lam = num(frame["lambda_collapse_per_yr"])
        if math.isfinite(median) and math.isfinite(beta):
            ax.semilogx(x, lognormal_cdf(x, median, beta), "-", color=colour, lw=1.8,
                        label=f"{frame['frame']}: λ_c {lam:.3g} /yr (lognormal)")
        steps = [p for p in r["empirical"] if p["frame"] == frame["frame"]]
        if steps:
            sx = [num(p[schema.INTENSITY]) for p in steps]
            sy = [num(p["probability"]) for p in steps]
            emp = num(frame["lambda_collapse_empirical_per_yr"])
            ax.step([x[0]] + sx + [x[-1]], [0.0] + sy + [sy[-1]], where="post", color=colour, lw=1.2, ls="--",
                    label=f"{frame['frame']}: λ_c {emp:.3g} /yr (empirical)")
    ax.set_ylabel("P(collapse | im) [–]")
    ax.set_ylim(-0.02, 1.05)
    ax.legend(loc="upper left")


def draw_deaggregation(ax, r, units):
    num = engine.number
    frames = [f["frame"] for f in r["frames"]]
    width = 0.8 / max(len(frames), 1)
    for i, (colour, frame) in enumerate(zip(style.CYCLE, frames)):
        rows = [b for b in r["deaggregation"] if b["frame"] == frame]
        low = np.array([num(b["im_low"]) for b in rows])
        high = np.array([num(b["im_high"]) for b in rows])
        share = np.array([num(b["share_lognormal"]) for b in rows])
        emp = np.array([num(b["share_empirical"]) for b in rows])
        # Bars side by side within each log bin.
        left = low * (high / low) ** (0.1 + i * width)
        right = low * (high / low) ** (0.1 + (i + 1) * width)
        ax.bar(left, np.nan_to_num(share), width=right - left, align="edge", color=colour, alpha=0.75,
               label=f"{frame}: lognormal")
        if np.isfinite(emp).any():
            ax.step(np.append(low, high[-1:]), np.append(np.nan_to_num(emp), 0.0), where="post", color=colour,
                    lw=1.3, ls="--", label=f"{frame}: empirical")
    ax.set_xscale("log")
    ax.set_ylabel("share of λ_c per bin [–]")
    ax.set_xlabel(f"intensity ({r['measure']}) [{style.pretty_units(units)}]")
    ax.legend(loc="upper left")


def draw(args):
    if not args.hazard:
        raise PlotError("risk needs --hazard FILE (the site's hazard curve CSV)")
    r = report(args)
    if not r["frames"]:
        raise PlotError(f"{args.input}: no frame among the selected cases")
    units = r["measure"].rsplit("_", 1)[-1] if r["measure"] != "pgv_m_s" else "m/s"
    num = engine.number
    edges = [num(b["im_low"]) for b in r["deaggregation"]] + [num(b["im_high"]) for b in r["deaggregation"]]
    hazard_x = [num(p[schema.INTENSITY]) for p in r["hazard"]]
    x = np.geomspace(min(edges + hazard_x), max(edges + hazard_x), 400)
    fig, axes = plt.subplots(3, 1, figsize=(7.5, 9.5), sharex=True, constrained_layout=True)
    draw_hazard(axes[0], r, units)
    draw_fragility(axes[1], r, x)
    draw_deaggregation(axes[2], r, units)
    axes[0].set_xlim(x[0], x[-1])
    axes[0].set_title(args.title or f"Collapse risk at the site (hazard beyond its last point: {r['tail']})")
    return fig
