"""`ida`: incremental dynamic analysis curves, one panel per frame. Each record's runs
(intensity against a response metric) are joined in order of intensity; its collapse
intensity is a flat line to the panel's edge (the usual IDA flatline);
runs above it that did not collapse (the curve "resurrects") are open circles. Horizontal lines: the
median and 16/84 % collapse intensities of the lognormal that `pcrf cube fragility` fits.
A curve whose runs ran out before it was bracketed (``curve_state`` unbracketed) gets no
flatline: a triangle at its last safe run says only that it survived there; nor does an
unresolved one (a run without a verdict ended it), marked by a hollow square at its last safe
run. Runs without a verdict (still rocking at their end, ground in free fall, invalid frame, a
failure) are never drawn as safe points: each is a small hollow square at its response, and
the legend and the panel title count them. With --reduce-over
(e.g. incidence_deg), a panel holds every orientation's curve, its flatline unmarked, and the
crosses and the fitted lines are each record's reduced collapse intensity, as the engine's
`cube fragility --reduce-over` computes it."""
import math

import matplotlib.pyplot as plt
import numpy as np

from .. import _names as schema
from . import engine, style
from .errors import PlotError



NO_VERDICT_RUNS = "run without a verdict"
UNBRACKETED_CURVES = "unbracketed: last safe run"
UNRESOLVED_CURVES = "unresolved: last safe run"


def is_safe(row):
    """A run the frame survived: neither a collapse nor without a verdict."""
    return engine.status_kind(row[schema.STATUS]) == "survived"


def curves_of(rows, reduced_over):
    """A frame's rows by curve: by record, and (reduced) by the reduced axis's value too."""
    curves = {}
    for r in rows:
        curves.setdefault((r[schema.RECORD], r[reduced_over] if reduced_over else ""), []).append(r)
    return curves


def frames_of(cube, metric, where, fits, extra):
    """Each frame's rows, in the engine's order: the frames `pcrf cube fragility` names,
    each exported with its own selection (the frame's -w selectors) added to the user's."""
    frames = {}
    for fit in fits:
        own = [w for w in (fit.get("selection") or "").split(",") if w]
        rows = cube.export([metric, schema.IDA_INTENSITY, schema.COLLAPSE_INTENSITY] + extra, list(where) + own)
        if rows:
            frames[fit["frame"]] = rows
    return frames


def edge_of(metric, rows):
    """The panel's right edge: beyond every safe run's response, or (every run collapsed)
    beyond every run's."""
    safe = [engine.number(r[metric]) for r in rows if is_safe(r)]
    values = [v for v in safe if math.isfinite(v)] or \
             [v for v in (engine.number(r[metric]) for r in rows) if math.isfinite(v)] or [1.0]
    return max(max(values), 1e-12) * 1.15


def draw(args):
    cube = engine.Cube(args.input)
    if cube.variable(schema.COLLAPSE_INTENSITY) is None or cube.variable(schema.IDA_INTENSITY) is None:
        raise PlotError(f"{args.input}: not an IDA cube (no collapse_intensity): run a study with an [ida] table")
    metric = args.metric or schema.THETA_MAX
    cube.require_metric(metric, "ida")
    report = cube.fragility(args.where, engine.reduction(args))
    fits = {f["frame"]: f for f in report["frames"]}
    reduced_over, reduced = report.get("reduced_over"), engine.reduced_text(report)
    has_states = cube.variable(schema.CURVE_STATE) is not None  # cubes from before it have none
    frames = frames_of(cube, metric, args.where, fits.values(), [schema.CURVE_STATE] if has_states else [])
    if not frames:
        raise PlotError(f"{args.input}: no case matches the selection")
    units = cube.variable(schema.IDA_INTENSITY)["units"]
    columns = min(3, len(frames))
    fig, axes = plt.subplots(math.ceil(len(frames) / columns), columns, figsize=(4.4 * columns, 4.2), squeeze=False,
                             sharey=True, constrained_layout=True)
    unbracketed_code, unresolved_code = engine.curve_state("unbracketed"), engine.curve_state("unresolved")
    totals = {}  # legend label → how many points of that kind the figure holds
    for ax, (frame, frame_rows) in zip(axes.flat, frames.items()):
        resurrected, unbracketed, unresolved = False, 0, 0
        no_verdict = [(engine.number(r[schema.IDA_INTENSITY]), engine.number(r[metric])) for r in frame_rows
                      if r[schema.IDA_INTENSITY] != "" and engine.status_kind(r[schema.STATUS]) == "no_verdict"]
        records = curves_of(frame_rows, reduced_over)
        edge = edge_of(metric, frame_rows)
        for record_rows in records.values():
            safe = sorted((engine.number(r[schema.IDA_INTENSITY]), engine.number(r[metric])) for r in record_rows
                          if is_safe(r) and r[schema.IDA_INTENSITY] != "" and r[metric] != "")
            state = engine.number(record_rows[0][schema.CURVE_STATE]) if has_states else math.nan
            if state in (unbracketed_code, unresolved_code):
                unbracketed += state == unbracketed_code
                unresolved += state == unresolved_code
                if safe:
                    im, edp = zip(*safe)
                    ax.plot(edp, im, "--", color=style.GREY, lw=0.8, alpha=0.8)
                    if state == unbracketed_code:
                        ax.plot(safe[-1][1], safe[-1][0], "^", color=style.PURPLE, ms=6)
                    else:
                        ax.plot(safe[-1][1], safe[-1][0], "s", mfc="none", color=style.BLACK, ms=7, mew=1.4)
                continue
            collapse = engine.number(record_rows[0][schema.COLLAPSE_INTENSITY])
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
                if not reduced:
                    ax.plot(edge, collapse, "x", color=style.VERMILLION, ms=5)
        if reduced:  # the values fitted: each record's reduction, from the engine's fragility points
            mine = [engine.number(p[schema.INTENSITY]) for p in report["points"] if p["frame"] == frame and p["kind"] == "collapse"]
            ax.plot([edge] * len(mine), mine, "x", color=style.VERMILLION, ms=7, mew=1.8)
        fit = fits.get(frame)
        median, beta = (engine.number(fit["median"]), engine.number(fit["beta"])) if fit else (math.nan, math.nan)
        if math.isfinite(median) and math.isfinite(beta):
            for value, line, label in ((median, "-", "median collapse intensity"),
                                       (median * math.exp(-beta), "--", "16 % / 84 %"),
                                       (median * math.exp(beta), "--", None)):
                ax.axhline(value, color=style.BLUE, ls=line, lw=1.5, label=label)
        drawn = [(im, edp if math.isfinite(edp) else edge) for im, edp in no_verdict]
        if drawn:
            ax.plot([p[1] for p in drawn], [p[0] for p in drawn], "s", mfc="none", color=style.SKY_BLUE, ms=4)
            ax.plot([], [], "s", mfc="none", color=style.SKY_BLUE, ms=4,
                    label=NO_VERDICT_RUNS)
            totals[NO_VERDICT_RUNS] = totals.get(NO_VERDICT_RUNS, 0) + len(drawn)
        if not any(is_safe(r) for r in frame_rows):
            ax.text(0.5, 0.6, "every run collapsed:\nstart the search lower", transform=ax.transAxes, ha="center",
                    color=style.VERMILLION)
        ax.plot([], [], "x", color=style.VERMILLION, label=f"collapse: each record's {reduced}" if reduced else "collapse")
        if resurrected:
            ax.plot([], [], "o", mfc="none", color=style.ORANGE, ms=4, label="safe above its collapse intensity")
        if unbracketed:
            ax.plot([], [], "^", color=style.PURPLE, ms=6, label=UNBRACKETED_CURVES)
            totals[UNBRACKETED_CURVES] = totals.get(UNBRACKETED_CURVES, 0) + unbracketed
        if unresolved:
            ax.plot([], [], "s", mfc="none", color=style.BLACK, ms=7, mew=1.4, label=UNRESOLVED_CURVES)
            totals[UNRESOLVED_CURVES] = totals.get(UNRESOLVED_CURVES, 0) + unresolved
        counted = f"{len(records)} " + ("curves" if reduced else "records") + \
            (f", {unbracketed} unbracketed" if unbracketed else "") + \
            (f", {unresolved} unresolved" if unresolved else "")
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
    labels = [f"{label} ({totals[label]})" if label in totals else label for label in legend]
    axes.flat[0].legend(legend.values(), labels, loc="lower right", fontsize="small")
    fig.suptitle(args.title or "Incremental dynamic analysis")
    return fig
