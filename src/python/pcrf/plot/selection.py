"""`selection`: records selected to a target spectrum: the target median and median·exp(±σ),
each selected record's scaled spectrum and the set's median and median·exp(±σ), from the JSON
that ``pcrf record select … --json > selection.json`` writes."""

import matplotlib.pyplot as plt
import numpy as np

from . import style
from .errors import read_command_json

NEEDED = ("periods_s", "target_mean_ln_sa", "target_sigma_ln_sa", "mean_ln_sa", "sigma_ln_sa", "records")


def read(path):
    return read_command_json(path, "pcrf record select --json", NEEDED)


def draw(args):
    data = read(args.input)
    t = np.asarray(data["periods_s"], dtype=float)
    mu, sig = np.asarray(data["target_mean_ln_sa"], float), np.asarray(data["target_sigma_ln_sa"], float)
    m, s = np.asarray(data["mean_ln_sa"], float), np.asarray(data["sigma_ln_sa"], float)
    fig, (ax, ax_s) = plt.subplots(1, 2, figsize=(12, 5.5), constrained_layout=True,
                                   gridspec_kw={"width_ratios": [3, 2]})
    for i, rec in enumerate(data["records"]):
        ax.plot(t, np.exp(rec["ln_sa"]), color=style.GREY, lw=0.7, label="selected, scaled" if i == 0 else None)
    ax.plot(t, np.exp(mu), color=style.BLACK, lw=2.2, label="target median")
    ax.plot(t, np.exp(mu + sig), "--", color=style.BLACK, lw=1.4, label=r"target median $\cdot e^{\pm\sigma}$")
    ax.plot(t, np.exp(mu - sig), "--", color=style.BLACK, lw=1.4)
    ax.plot(t, np.exp(m), color=style.VERMILLION, lw=2.0, label="selected median")
    ax.plot(t, np.exp(m + s), ":", color=style.VERMILLION, lw=1.6, label=r"selected median $\cdot e^{\pm\hat\sigma}$")
    ax.plot(t, np.exp(m - s), ":", color=style.VERMILLION, lw=1.6)
    ax.set(xscale="log", yscale="log", xlabel="period T [s]", ylabel="spectral acceleration Sa [g]",
           title=f"{args.title or ''}{' — ' if args.title else ''}{len(data['records'])} records: "
                 f"median within {data.get('median_error_percent', float('nan')):.1f} %, "
                 f"σ within {data.get('sigma_error_percent', float('nan')):.1f} %")
    ax.legend(loc="lower left", fontsize=9)
    ax_s.plot(t, sig, color=style.BLACK, lw=2.0, label="target")
    ax_s.plot(t, s, color=style.VERMILLION, lw=2.0, label="selected")
    ax_s.set(xscale="log", xlabel="period T [s]", ylabel=r"standard deviation of ln Sa $\sigma$ [-]",
             title=f"sum of squared errors {data.get('sum_of_squares', float('nan')):.3g}")
    ax_s.set_ylim(bottom=0)
    ax_s.legend()
    return fig
