"""`spectrum`: a rocking (collapse) spectrum of an IDA cube over pulse records ([[records]]
pulse, [axes] pulse_period_s): each curve's collapse amplitude, over the frame's uplift
threshold, against ω_p/p, one line per pulse shape, one panel per frame; recorded motions of a
study with [outputs] record_pulses are points at their identified T_p (those without a pulse
have no ω_p/p and are left out). The marker says how
the run at the collapse amplitude ended: overturned (filled circle) or tendon fracture
(cross); a curve safe up to max_intensity is a triangle at the cap (its amplitude is above),
an unbracketed one (max_runs ran out) a hollow triangle at its last safe amplitude, and an
unresolved one (a run without a verdict ended it: still rocking when its tail ended, ground in
free fall, invalid frame) a hollow square at its last safe amplitude: its collapse amplitude is
unknown, above that. Each panel's legend counts the points of each kind."""
import math

import matplotlib.pyplot as plt
from matplotlib import ticker

from .. import _names as schema
from . import engine, style
from .errors import PlotError



def minor_label(value, _position):
    """A minor tick's label, except beside a decade's (0.9 next to 1 would overlap it)."""
    decade = 10.0 ** round(math.log10(value))
    return "" if abs(value / decade - 1.0) < 0.15 else f"{value:g}"


def draw(args):
    cube = engine.Cube(args.input)
    for needed, why in ((schema.COLLAPSE_INTENSITY, "an IDA cube ([ida] table)"),
                        (schema.OMEGA_OVER_P, "pulse records ([[records]] pulse with [axes] pulse_period_s) or "
                                              "[outputs] record_pulses")):
        if cube.variable(needed) is None:
            raise PlotError(f"{args.input}: not a rocking-spectrum cube (no {needed}): it needs {why}")
    units = cube.variable(schema.COLLAPSE_INTENSITY)["units"]
    names = [schema.IDA_INTENSITY, schema.COLLAPSE_INTENSITY, schema.LAST_SAFE_INTENSITY, schema.CURVE_STATE,
             schema.OMEGA_OVER_P, schema.UPLIFT_THRESHOLD]
    rows = cube.export(names, args.where)
    censored, unresolved = engine.curve_state("censored"), engine.curve_state("unresolved")
    if not rows:
        raise PlotError(f"{args.input}: no case matches the selection")
    frame_dims = [d["name"] for d in cube.dimensions if d["name"] not in (schema.RECORD, schema.IDA_POINT) and d["size"] > 1]
    curves = {}  # (frame, shape) → {record: (ω_p/p, a_c/threshold, marker kind)}
    for r in rows:
        frame = ",".join(f"{d}={r[d]}" if d != schema.CASE else r[schema.CASE_LABEL] for d in frame_dims) or "all"
        threshold = engine.number(r[schema.UPLIFT_THRESHOLD]) if units == "g" else 1.0
        key = (frame, r[schema.PULSE_SHAPE])
        record = curves.setdefault(key, {}).setdefault(r[schema.RECORD], {"x": engine.number(r[schema.OMEGA_OVER_P])})
        collapse, state = engine.number(r[schema.COLLAPSE_INTENSITY]), engine.number(r[schema.CURVE_STATE])
        if state == censored:
            record["point"] = (engine.number(r[schema.LAST_SAFE_INTENSITY]) / threshold, "censored")
        elif state == unresolved:
            record["point"] = (engine.number(r[schema.LAST_SAFE_INTENSITY]) / threshold, "unresolved")
        elif not math.isfinite(collapse):
            record["point"] = (engine.number(r[schema.LAST_SAFE_INTENSITY]) / threshold, "unbracketed")
        elif r[schema.IDA_INTENSITY] != "" and engine.number(r[schema.IDA_INTENSITY]) == collapse:
            record["point"] = (collapse / threshold, r[schema.STATUS])
    frames = sorted({f for f, _ in curves})
    columns = min(2, len(frames))
    fig, axes = plt.subplots(math.ceil(len(frames) / columns), columns, figsize=(6.4 * columns, 4.8), squeeze=False,
                             constrained_layout=True)
    shapes = sorted({s for _, s in curves})
    markers = {"overturned": ("o", "overturned"), "tendon_fracture": ("x", "tendon fracture"),
               "censored": ("^", "safe up to max_intensity"), "unbracketed": ("^", "unbracketed: last safe"),
               "unresolved": ("s", "unresolved (no verdict above): last safe")}
    hollow = ("unbracketed", "unresolved")
    for ax, frame in zip(axes.flat, frames):
        counts = {kind: 0 for kind in markers}
        for colour, shape in zip(style.CYCLE, shapes):
            points = sorted((p["x"], *p["point"]) for p in curves.get((frame, shape), {}).values()
                            if "point" in p and math.isfinite(p["x"]))
            if not points:
                continue
            # Recorded motions ([outputs] record_pulses: no pulse_shape, T_p identified) are points
            # of different records, not a curve: markers only.
            ax.plot([p[0] for p in points], [p[1] for p in points], linestyle="-" if shape else "none", color=colour,
                    lw=1.4, marker=None if shape else "o", mfc="none", label=shape or "records (T_p identified)")
            for kind, (marker, _) in markers.items():
                chosen = [p for p in points if p[2] == kind]
                counts[kind] += len(chosen)
                if chosen:
                    ax.plot([p[0] for p in chosen], [p[1] for p in chosen], marker, color=colour,
                            ms=7 if kind == "unresolved" else 5, mfc="none" if kind in hollow else colour)
        for kind, (marker, label) in markers.items():
            if counts[kind] or kind in ("overturned", "tendon_fracture"):
                ax.plot([], [], marker, color=style.GREY, mfc="none" if kind in hollow else style.GREY,
                        label=f"{label} ({counts[kind]})")
        ax.set_xscale("log")
        ax.set_yscale("log")
        for axis, (low, high) in ((ax.xaxis, ax.get_xlim()), (ax.yaxis, ax.get_ylim())):
            # Plain numbers, not powers of ten; the minor ticks labelled too when the axis spans
            # less than a decade and a half (else a decade's only label would be its base).
            axis.set_major_formatter(ticker.FormatStrFormatter("%g"))
            short = high / low < 30
            axis.set_minor_formatter(ticker.FuncFormatter(minor_label) if short else ticker.NullFormatter())
        ylabel = "collapse amplitude / uplift threshold [–]" if units == "g" else f"collapse intensity [{units}]"
        # One frame ("all") needs no panel title: the figure's title names it.
        ax.set(xlabel="pulse frequency / frame frequency parameter ω_p / p [–]", ylabel=ylabel, title="" if frame == "all" else frame)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(loc="upper left", fontsize="small")
    for ax in axes.flat[len(frames):]:
        ax.remove()
    # A study of one scene names its model in an attribute (none: pcrf); one that mixes scenes
    # names each frame's in a coordinate, and its panels are titled by case label.
    mixed = schema.SCENE_MODEL in cube.info["auxiliary_coordinates"]
    scene = cube.info.get("attributes", {}).get(schema.SCENE_MODEL, "pcrf")
    fig.suptitle(args.title or ("Rocking spectra" if mixed else f"Rocking spectrum ({scene})"))
    return fig
