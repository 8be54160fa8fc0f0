"""`ida`: incremental dynamic analysis curves, one panel per frame. Each record's runs
(intensity against a response metric) are joined in order of intensity; its collapse
intensity is a flat line to the panel's edge (the usual IDA flatline);
runs above it that did not collapse (the curve "resurrects") are open circles. Horizontal lines: the
median and 16/84 % collapse intensities of the lognormal that `pcrf cube fragility` fits.
A curve whose runs ran out before it was bracketed (``curve_state`` unbracketed) gets no
flatline: a triangle at its last safe run says only that it survived there."""
import math

import matplotlib.pyplot as plt
import numpy as np

from pcrf_plot import engine, style
from pcrf_plot.errors import PlotError

UNBRACKETED = 2  # curve_state: max_runs ran out (plan::CurveState, the cube's long_name)


def frame_label(cube, row):
    """A case's frame, named as `pcrf cube fragility` names it: the frame axes with several
    values ("kappa=1.4", or the case label of a list plan), or "all"."""
    parts = []
    for d in cube.dimensions:
        if d["name"] in ("record", "ida_point") or d["size"] < 2:
            continue
        parts.append(row["case_label"] if d["name"] == "case" else f"{d['name']}={row[d['name']]}")
    return ",".join(parts) or "all"


def frames_of(cube, rows):
    """Frame label → its rows, in the cube's order."""
    frames = {}
    for r in rows:
        frames.setdefault(frame_label(cube, r), []).append(r)
    return frames


def draw(args):
    cube = engine.Cube(args.input)
    if cube.variable("collapse_intensity") is None or cube.variable("ida_intensity") is None:
        raise PlotError(f"{args.input}: not an IDA cube (no collapse_intensity): run a study with an [ida] table")
    metric = args.metric or "theta_max_rad"
    cube.require_metric(metric, "ida")
    has_states = cube.variable("curve_state") is not None  # cubes from before it have none
    rows = cube.export([metric, "ida_intensity", "collapse_intensity"] + (["curve_state"] if has_states else []),
                       args.where)
    if not rows:
        raise PlotError(f"{args.input}: no case matches the selection")
    fits = {f["frame"]: f for f in cube.fragility(args.where)[0]}
    units = cube.variable("ida_intensity")["units"]
    frames = frames_of(cube, rows)
    columns = min(3, len(frames))
    fig, axes = plt.subplots(math.ceil(len(frames) / columns), columns, figsize=(4.4 * columns, 4.2), squeeze=False,
                             sharey=True, constrained_layout=True)
    for ax, (frame, frame_rows) in zip(axes.flat, frames.items()):
        records, resurrected, unbracketed = {}, False, 0
        for r in frame_rows:
            records.setdefault(r["record"], []).append(r)
        edge = max(engine.number(r[metric]) for r in frame_rows if r["status"] not in style.COLLAPSE_STATUSES
                   and r[metric] != "") * 1.15
        for record_rows in records.values():
            safe = sorted((engine.number(r["ida_intensity"]), engine.number(r[metric])) for r in record_rows
                          if r["status"] not in style.COLLAPSE_STATUSES and r["ida_intensity"] != "" and r[metric] != "")
            collapse = engine.number(record_rows[0]["collapse_intensity"])
            if has_states and engine.number(record_rows[0]["curve_state"]) == UNBRACKETED:
                unbracketed += 1
                if safe:
                    im, edp = zip(*safe)
                    ax.plot(edp, im, "--", color=style.GREY, lw=0.8, alpha=0.8)
                    ax.plot(safe[-1][1], safe[-1][0], "^", color=style.PURPLE, ms=6)
                continue
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
        if fit and fit.get(f"median [{cube.variable('ida_intensity')['units']}]"):
            median = engine.number(fit[f"median [{cube.variable('ida_intensity')['units']}]"])
            beta = engine.number(fit["beta"])
            for value, line, label in ((median, "-", "median collapse intensity"),
                                       (median * math.exp(-beta), "--", "16 % / 84 %"),
                                       (median * math.exp(beta), "--", None)):
                ax.axhline(value, color=style.BLUE, ls=line, lw=1.5, label=label)
        ax.plot([], [], "x", color=style.VERMILLION, label="collapse")
        if unbracketed:
            ax.plot([], [], "^", color=style.PURPLE, ms=6, label="unbracketed (max_runs ran out): last safe run")
        if resurrected:
            ax.plot([], [], "o", mfc="none", color=style.ORANGE, ms=4, label="safe above its collapse intensity")
        counted = f"{len(records)} records" + (f", {unbracketed} unbracketed" if unbracketed else "")
        ax.set(xlim=(0, edge * 1.03), title=f"{frame} ({counted})",
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
