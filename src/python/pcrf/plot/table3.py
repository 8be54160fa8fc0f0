"""`table3`: the paper comparison that bench/paper_comparison.py writes
(docs/paper_comparison.csv): (a) t_RI, engine against paper; (b) θ_max of the paper and of
its non-physical fixed-step procedure at three steps; (c) the scale at which each record
first lifts the consistent model; (d) the paper's rows against θ̇² = 2a₀θ + ω²θ²."""
import matplotlib.pyplot as plt
import matplotlib.ticker as ticker
import numpy as np

from . import engine, style
from .errors import PlotError

STEPS = (("5", style.ORANGE, "s"), ("2.5", style.SKY_BLUE, "^"), ("1", style.BLUE, "v"))
NEEDED = ("record", "paper_t_RI_s", "engine_t_RI_s", "paper_theta_max_rad", "paper_omega_max_rad_s",
          "scale1_status", "first_lift_scale", "paper_fit_a0_rad_s2", "paper_fit_w2_s2", "model_a0_rad_s2",
          "model_w2_s2") + tuple(f"proc{step}ms_theta_max_rad" for step, _, _ in STEPS)


def read(path):
    rows = engine.read_csv(path)
    missing = [c for c in NEEDED if not rows or c not in rows[0]]
    if missing:
        raise PlotError(f"{path}: not a paper comparison table (no column {', '.join(missing)}; "
                        "write one with python3 bench/paper_comparison.py)")
    return rows


def draw(args):
    rows = read(args.input)
    computed = [r for r in rows if r["engine_t_RI_s"] not in ("", None)]
    if not computed:
        raise PlotError(f"{args.input}: no record was computed")
    names = [r["record"] for r in computed]
    x = np.arange(len(names))
    num = engine.number
    fig, axes = plt.subplots(2, 2, figsize=(12, 8.5), constrained_layout=True)
    (a_tri, a_theta), (a_lift, a_fit) = axes

    paper_t = np.array([num(r["paper_t_RI_s"]) for r in computed])
    engine_t = np.array([num(r["engine_t_RI_s"]) for r in computed])
    top = max(paper_t.max(), engine_t.max()) * 1.05
    a_tri.plot([0, top], [0, top], "-", color=style.GREY, lw=1, label="equal")
    a_tri.plot(paper_t, engine_t, "o", color=style.BLUE, label=f"{len(computed)} records")
    exact = int(np.sum(np.abs(paper_t - engine_t) < 1e-9))
    a_tri.set(xlabel=r"paper's $t_{RI}$ [s]", ylabel=r"engine's $t_{RI}$ (t_trigger_paper_s) [s]",
              title=f"(a) trigger time $t_{{RI}}$: equal for {exact} of {len(computed)}", xlim=(0, top),
              ylim=(0, top))
    a_tri.legend(loc="upper left")

    a_theta.plot(x, [num(r["paper_theta_max_rad"]) for r in computed], "D", color=style.BLACK, ms=7,
                 label="paper, Table 3")
    for step, colour, marker in STEPS:
        a_theta.plot(x, [num(r[f"proc{step}ms_theta_max_rad"]) for r in computed], marker, color=colour, ms=6,
                     label=f"paper's procedure, h = {step} ms")
    at_rest = sum(1 for r in computed if r["scale1_status"] == "at_rest")
    a_theta.set_yscale("log")
    a_theta.yaxis.set_minor_formatter(ticker.LogFormatter(labelOnlyBase=False, minor_thresholds=(2, 0.4)))
    a_theta.set_xticks(x, names, rotation=45)
    a_theta.set(ylabel=r"peak $|\theta_1|$ [rad]", title="(b) peak rotation at scale 1")
    a_theta.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncols=2, fontsize=8,
                   title=f"consistent model: at rest, θ_max = 0, for {at_rest} of {len(computed)}",
                   title_fontsize=9)

    a_lift.bar(x, [num(r["first_lift_scale"]) for r in computed], color=style.GREEN, width=0.6)
    a_lift.axhline(1.0, color=style.BLACK, lw=1, ls="--", label="the paper's scale (1)")
    a_lift.set_xticks(x, names, rotation=45)
    a_lift.set(ylabel="scale factor at first lift [–]",
               title="(c) scale at which each record first lifts the frame")
    a_lift.legend(loc="upper right")

    theta = np.array([num(r["paper_theta_max_rad"]) for r in rows])
    omega = np.array([num(r["paper_omega_max_rad_s"]) for r in rows])
    grid = np.linspace(0, theta.max() * 1.1, 200)
    for prefix, colour, line, label in (("paper_fit", style.BLUE, "-", "fit to the paper's rows"),
                                        ("model", style.VERMILLION, "--", "consistent model, free flight")):
        a0, w2 = num(rows[0][f"{prefix}_a0_rad_s2"]), num(rows[0][f"{prefix}_w2_s2"])
        a_fit.plot(grid, 2 * a0 * grid + w2 * grid ** 2, line, color=colour, lw=1.8,
                   label=rf"{label}: $a_0$ = {a0:.3g} rad/s², $\omega^2$ = {w2:.0f} s⁻²")
    a_fit.plot(theta, omega ** 2, "o", color=style.BLACK, ms=5, mfc="none", label=f"paper, {len(rows)} rows")
    a_fit.set(xlabel=r"paper's $\theta_{1,\max}$ [rad]", ylabel=r"paper's $\dot\theta_{1,\max}^2$ [rad²/s²]",
              title=r"(d) $\dot\theta^2_{\max} = 2a_0\theta_{\max} + \omega^2\theta^2_{\max}$")
    a_fit.legend(loc="upper left", fontsize=8)
    fig.suptitle(args.title or "Zhao & Su (2021) Table 3 and the engine (basic model)")
    return fig
