"""`ida`: incremental dynamic analysis curves, one panel per frame. Each record's runs
(intensity against a response metric) are joined in order of intensity; its collapse
intensity is a flat line to the panel's edge (the usual IDA flatline);
runs above it that did not collapse (the curve "resurrects") are open circles. Horizontal lines: the
median and 16/84 % collapse intensities of the lognormal that `pcrf cube fragility` fits."""
import math

import matplotlib.pyplot as plt
import numpy as np

from pcrf_plot import engine, style
from pcrf_plot.errors import PlotError


def frames_of(cube, metric, where, fits):
    """Each frame's rows, in the engine's order: the frames `pcrf cube fragility` names,
    each exported with its own selection (the frame's -w selectors) added to the user's."""
    frames = {}
    for fit in fits:
        own = [w for w in (fit.get("selection") or "").split(",") if w]
        rows = cube.export([metric, "ida_intensity", "collapse_intensity"], list(where) + own)
        if rows:
            frames[fit["frame"]] = rows
    return frames


def edge_of(metric, rows):
    """The panel's right edge: beyond every safe run's response, or (every run collapsed)
    beyond every run's."""
    safe = [engine.number(r[metric]) for r in rows if r["status"] not in engine.collapse_statuses()]
    values = [v for v in safe if math.isfinite(v)] or \
             [v for v in (engine.number(r[metric]) for r in rows) if math.isfinite(v)] or [1.0]
    return max(max(values), 1e-12) * 1.15


def draw(args):
    cube = engine.Cube(args.input)
    if cube.variable("collapse_intensity") is None or cube.variable("ida_intensity") is None:
        raise PlotError(f"{args.input}: not an IDA cube (no collapse_intensity): run a study with an [ida] table")
    metric = args.metric or "theta_max_rad"
    cube.require_metric(metric, "ida")
    fits = {f["frame"]: f for f in cube.fragility(args.where)["frames"]}
    frames = frames_of(cube, metric, args.where, fits.values())
    if not frames:
        raise PlotError(f"{args.input}: no case matches the selection")
    units = cube.variable("ida_intensity")["units"]
    columns = min(3, len(frames))
    fig, axes = plt.subplots(math.ceil(len(frames) / columns), columns, figsize=(4.4 * columns, 4.2), squeeze=False,
                             sharey=True, constrained_layout=True)
    for ax, (frame, frame_rows) in zip(axes.flat, frames.items()):
        records, resurrected = {}, False
        for r in frame_rows:
            records.setdefault(r["record"], []).append(r)
        edge = edge_of(metric, frame_rows)
        for record_rows in records.values():
            safe = sorted((engine.number(r["ida_intensity"]), engine.number(r[metric])) for r in record_rows
                          if r["status"] not in engine.collapse_statuses() and r["ida_intensity"] != ""
                          and r[metric] != "")
            collapse = engine.number(record_rows[0]["collapse_intensity"])
            below = [p for p in safe if not p[0] > collapse]  # NaN (censored): every run
            above = [p for p in safe if p[0] > collapse]
            if below:
                im, edp = zip(*below)
                ax.plot(edp, im, "-", color=style.GREY, lw=0.8, alpha=0.8)
            if above:
                resurrected = True
                ax.plot([p[1] for p in above], [p[0] for p in above], "o", mfc="none", color=style.ORANGE, ms=4)
            if math.isfinite(collapse):
                start = below[-1][1] if below else 0.0
                ax.plot([start, edge], [collapse, collapse], "-", color=style.GREY, lw=0.8, alpha=0.8)
                ax.plot(edge, collapse, "x", color=style.VERMILLION, ms=5)
        fit = fits.get(frame)
        median, beta = (engine.number(fit["median"]), engine.number(fit["beta"])) if fit else (math.nan, math.nan)
        if math.isfinite(median) and math.isfinite(beta):
            for value, line, label in ((median, "-", "median collapse intensity"),
                                       (median * math.exp(-beta), "--", "16 % / 84 %"),
                                       (median * math.exp(beta), "--", None)):
                ax.axhline(value, color=style.BLUE, ls=line, lw=1.5, label=label)
        if not any(r["status"] not in engine.collapse_statuses() for r in frame_rows):
            ax.text(0.5, 0.6, "every run collapsed:\nstart the search lower", transform=ax.transAxes, ha="center",
                    color=style.VERMILLION)
        ax.plot([], [], "x", color=style.VERMILLION, label="collapse")
        if resurrected:
            ax.plot([], [], "o", mfc="none", color=style.ORANGE, ms=4, label="safe above its collapse intensity")
        ax.set(xlim=(0, edge * 1.03), title=f"{frame} ({len(records)} records)",
               xlabel=style.metric_label(metric, cube.variable(metric)))
    for ax in axes.flat[len(frames):]:
        ax.remove()
    for ax in axes[:, 0]:
        ax.set_ylabel(style.intensity_label(cube, units))
    legend = {}
    for ax in axes.flat[:len(frames)]:
        for handle, label in zip(*ax.get_legend_handles_labels()):
            legend.setdefault(label, handle)
    axes.flat[0].legend(legend.values(), legend.keys(), loc="lower right")
    fig.suptitle(args.title or "Incremental dynamic analysis")
    return fig
