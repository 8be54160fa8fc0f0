"""`pulse`: a record's velocity, the velocity pulse extracted from it and the residual
(Baker 2007; Shahi & Baker 2014 for a pair, along the pulse's orientation), from the JSON that
``pcrf record pulse FILE [--h2 FILE2] --series > pulse.json`` writes."""

import matplotlib.pyplot as plt
import numpy as np

from . import style
from .errors import read_command_json

NEEDED = ("method", "pulse_like", "dt_s", "candidates", "velocity_cm_s", "pulse_cm_s", "residual_cm_s")


def read(path):
    return read_command_json(path, "pcrf record pulse --series", NEEDED)


def draw(args):
    data = read(args.input)
    dt = float(data["dt_s"])
    v, p, r = (np.asarray(data[k], dtype=float) for k in ("velocity_cm_s", "pulse_cm_s", "residual_cm_s"))
    t = np.arange(len(v)) * dt
    c = data["candidates"][int(data.get("decided_by", 0))]
    fig, axes = plt.subplots(3, 1, figsize=(10, 7.5), sharex=True, sharey=True, constrained_layout=True)
    orientation = f", azimuth {c['azimuth_deg']:.0f}°" if "azimuth_deg" in c else ""
    verdict = (f"pulse-like, $T_p$ = {c['period_s']:.2f} s" if data["pulse_like"]
               else f"not pulse-like (strongest candidate $T_p$ = {c['period_s']:.2f} s"
                    + (", late" if c.get("late") else "") + ")")
    for ax, series, colour, label in ((axes[0], v, style.BLACK, "ground"), (axes[1], p, style.VERMILLION, "extracted pulse"),
                                      (axes[2], r, style.BLUE, "residual")):
        ax.plot(t, series, color=colour, lw=1.0)
        ax.axhline(0.0, color=style.GREY, lw=0.5)
        ax.set_ylabel(f"{label}\nvelocity [cm/s]")
    axes[1].plot(t, v, color=style.GREY, lw=0.6, zorder=0, label="ground velocity")
    axes[1].legend(loc="upper right")
    axes[-1].set_xlabel("time t [s]")
    method = {"baker-2007": "Baker (2007)", "shahi-baker-2014": "Shahi & Baker (2014)"}.get(data["method"], data["method"])
    axes[0].set_title(f"{args.title or ''}{' — ' if args.title else ''}{verdict}{orientation}; {method}: "
                      f"PGV ratio {c['pgv_ratio']:.2f}, energy ratio {c['energy_ratio']:.2f}, PGV {c['pgv_cm_s']:.0f} cm/s")
    return fig
