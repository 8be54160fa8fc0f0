#!/usr/bin/python3
"""Figure and table of the numerics audit (docs/numerics_audit.md).

usage: plot_numerics_audit.py PREFIX [--png FILE] [--records ER1x2.5,ER8x2.5] [--table FILE.md]

PREFIX_summary.csv and PREFIX_envelope.csv come from pcrf_numerics_audit. The figure has
  (top)    the envelope of |theta_1| (peak per 0.1 s) against time for two records, one line
           per method, log scale, with t95 and the end of the record marked;
  (bottom) RMS |theta_1| in the free-vibration tail against the fixed step h for every record
           that rocks, with the exact solution (identically zero: at rest) noted.
Needs numpy and matplotlib (Debian: python3-numpy, python3-matplotlib).
"""
import argparse
import csv
import math
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("prefix")
    ap.add_argument("--png", default="numerics_audit.png")
    ap.add_argument("--records", default="ER1x2.5,ER8x2.5")
    ap.add_argument("--table", default=None, help="write a markdown table here")
    a = ap.parse_args()

    summary = list(csv.DictReader(open(a.prefix + "_summary.csv")))
    env = defaultdict(lambda: ([], []))
    for r in csv.DictReader(open(a.prefix + "_envelope.csv")):
        t, v = env[(r["record"], r["method"])]
        t.append(float(r["t_s"]))
        v.append(float(r["peak_abs_theta_rad"]))
    methods = []
    for r in summary:
        if r["method"] not in methods:
            methods.append(r["method"])
    colors = {m: c for m, c in zip(methods, ["k", "tab:gray", "tab:red", "tab:orange", "tab:blue", "tab:green"])}
    styles = {m: ("-" if m.startswith("exact-erk8") else "--" if m.startswith("exact") else "-") for m in methods}

    shown = [x for x in a.records.split(",") if any(r["record"] == x for r in summary)]
    fig, axes = plt.subplots(len(shown) + 1, 1, figsize=(9, 3.2 * (len(shown) + 1)))
    axes = np.atleast_1d(axes)
    floor = 1e-9
    for ax, rec in zip(axes, shown):
        info = next(r for r in summary if r["record"] == rec)
        for m in methods:
            if (rec, m) not in env:
                continue
            t, v = env[(rec, m)]
            v = np.maximum(np.array(v), floor)
            ax.semilogy(t, v, styles[m], color=colors[m], lw=1.0 if m.startswith("fixed") else 1.6, label=m)
        ax.axvline(float(info["t95_s"]), color="0.5", ls=":", lw=1)
        ax.axvline(float(info["duration_s"]), color="0.5", ls="-.", lw=1)
        ax.set_ylim(floor * 0.8, 0.2)
        ax.set_ylabel("peak |θ₁| per 0.1 s [rad]")
        ax.set_title(f"basic frame, {rec} (PGA {float(info['pga_g']):.2f} g, dt {info['dt_s']} s): "
                     f"t95 (dotted), end of record (dash-dot), then {info['tail_s']} s free vibration", fontsize=9)
        ax.text(0.01, 0.03, f"values ≤ {floor:g} rad drawn at {floor:g} (exact: at rest, θ₁ = 0)",
                transform=ax.transAxes, fontsize=8, color="0.3")
    axes[0].legend(fontsize=8, loc="upper right", ncol=2)
    axes[-2].set_xlabel("t [s]")

    ax = axes[-1]
    by_rec = defaultdict(list)
    for r in summary:
        if r["method"].startswith("fixed") and r["status"] != "tendon_fracture" and float(r["theta_max_rad"]) > 0:
            by_rec[r["record"]].append((float(r["step_s"]), float(r["rms_tail_rad"])))
    for rec, pts in sorted(by_rec.items()):
        pts.sort()
        h = [p[0] for p in pts]
        v = [max(p[1], floor) for p in pts]
        ax.loglog(h, v, "o-", ms=4, lw=0.8, label=rec)
    hh = np.array([5e-5, 1e-2])
    ax.loglog(hh, 7e-6 * (hh / 1e-4) ** 2, "k:", lw=1, label="∝ h²")
    ax.set_xlabel("fixed step h [s]")
    ax.set_ylabel("RMS θ₁ in the tail [rad]")
    ax.set_title("fixed-step RK4 sign-change scheme: RMS θ₁ in the 10 s free-vibration tail\n"
                 "(exact event location: 0, at rest, for every record)", fontsize=9)
    ax.legend(fontsize=7, ncol=4)
    fig.tight_layout()
    fig.savefig(a.png, dpi=110)
    print("wrote", a.png)

    if a.table:
        with open(a.table, "w") as f:
            f.write("| record | method | status | θ_max [rad] | impacts after t95 | impacts in tail | "
                    "RMS θ after t95 [rad] | RMS θ in tail [rad] |\n|---|---|---|---|---|---|---|---|\n")
            for r in summary:
                f.write(f"| {r['record']} | {r['method']} | {r['status']} | {float(r['theta_max_rad']):.4g} | "
                        f"{r['impacts_after_t95']} | {r['impacts_tail']} | {float(r['rms_after_t95_rad']):.3g} | "
                        f"{float(r['rms_tail_rad']):.3g} |\n")
        print("wrote", a.table)


if __name__ == "__main__":
    main()
