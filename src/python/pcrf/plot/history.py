"""`history`: θ₁, θ̇₁ and ü_g against time, and the phase portrait θ̇₁(θ₁).

An impact is one row with the velocity arriving (omega1_rad_s) and leaving
(omega1_after_rad_s): both are drawn, so the jump is a vertical step, never a smear.
"""
import os

import matplotlib.pyplot as plt
import matplotlib.ticker as ticker
import numpy as np

from . import engine, style
from .errors import PlotError

COLUMNS = ("t_s", "theta1_rad", "omega1_rad_s", "omega1_after_rad_s", "ground_accel_g", "event")


def read(args):
    """The history's columns as arrays, and a title."""
    if os.path.splitext(args.input)[1].lower() in (".csv", ".txt"):
        rows = engine.read_csv(args.input)
        columns = {c: [engine.number(r[c]) for r in rows] for c in COLUMNS if rows and c in rows[0]}
        name = os.path.basename(args.input)
    else:
        cube = engine.Cube(args.input)
        groups = cube.info["histories"]
        if not groups:
            raise PlotError(f"{args.input}: the cube holds no history (add [[outputs.histories]] to the study)")
        label = args.group or (groups[0] if len(groups) == 1 else None)
        if label is None:
            raise PlotError(f"{args.input}: several histories ({', '.join(groups)}): choose one with --group")
        columns = cube.history(label)
        rows = next(iter(columns.values()), [])
        name = f"{os.path.basename(args.input)}: {label}"
    if not len(rows):
        raise PlotError(f"{args.input}: the history is empty")
    missing = [c for c in COLUMNS if c not in columns]
    if missing:
        raise PlotError(f"{args.input}: not a pcrf history (no column {', '.join(missing)}); "
                        "write one with pcrf run --history")
    return {c: np.asarray(columns[c], dtype=float) for c in COLUMNS}, name


def with_jumps(t, before, after):
    """Each row as (t, before) then (t, after): velocity jumps become vertical steps."""
    return np.repeat(t, 2), np.column_stack([before, after]).ravel()


def draw(args):
    h, name = read(args)
    t, theta = h["t_s"], h["theta1_rad"]
    events = h["event"].astype(np.int64)
    t2, omega2 = with_jumps(t, h["omega1_rad_s"], h["omega1_after_rad_s"])
    fig, axes = plt.subplots(2, 2, figsize=(11, 7), constrained_layout=True)
    (a_theta, a_phase), (a_omega, a_ground) = axes

    a_theta.plot(t, theta, color=style.BLUE, lw=1)
    # The largest |θ₁| of the history is the result's θ_max: every extremum is a row.
    if np.any(theta):
        k = int(np.argmax(np.abs(theta)))
        a_theta.plot(t[k], theta[k], "o", color=style.VERMILLION, ms=6,
                     label=rf"peak $|\theta_1|$ = {abs(theta[k]):.4g} rad at {t[k]:.3f} s")
    if events[-1] & engine.event_flag("stop"):
        a_theta.plot(t[-1], theta[-1], "X", color=style.BLACK, ms=8, label=f"fracture or overturning at {t[-1]:.3f} s")
    if a_theta.get_legend_handles_labels()[0]:
        a_theta.legend(loc="best")
    a_theta.set(xlabel="time t [s]", ylabel=r"rotation $\theta_1$ [rad]", title="(a) rotation")

    a_omega.plot(t2, omega2, color=style.GREEN, lw=1)
    a_omega.set(xlabel="time t [s]", ylabel=r"angular velocity $\dot\theta_1$ [rad/s]", title="(c) angular velocity")

    a_ground.plot(t, h["ground_accel_g"], color=style.BLACK, lw=0.8)
    a_ground.set(xlabel="time t [s]", ylabel=r"ground acceleration $\ddot u_g$ [g]", title="(d) ground motion")

    theta2 = np.repeat(theta, 2)
    a_phase.plot(theta2, omega2, color=style.PURPLE, lw=0.8)
    a_phase.set(xlabel=r"rotation $\theta_1$ [rad]", ylabel=r"angular velocity $\dot\theta_1$ [rad/s]",
                title="(b) phase portrait")
    for ax in (a_theta, a_phase, a_omega, a_ground):
        ax.xaxis.set_major_locator(ticker.MaxNLocator(6))
        ax.ticklabel_format(axis="both", style="sci", scilimits=(-3, 4))
    impacts = int(np.count_nonzero(events & engine.event_flag("impact")))
    if not np.any(theta):
        a_theta.text(0.5, 0.5, "at rest throughout", transform=a_theta.transAxes, ha="center")
    fig.suptitle(args.title or f"Time history, {name} ({impacts} impacts)")
    return fig
