#!/usr/bin/python3
"""Work-precision diagram and summary tables from pcrf_work_precision's CSV files.

usage: plot_work_precision.py PREFIX [--png FILE] [--summary-csv FILE] [--markdown FILE]
                              [--frames basic,slender,...]

PREFIX_runs.csv and PREFIX_cases.csv come from `pcrf_work_precision --out PREFIX`.
Statistics per setting are over the cases whose reference rocks (theta_max > 0); a setting
that fails (solver failure, time limit) on a case counts as an infinite error there.
The diagram: median theta_max relative error against median wall time per case, log-log,
one line per contender (through its tolerances or fixed steps), the presets as large
markers; the right panel shows the 90th percentile of the error. The grey band is the
median conditioning of the cases (relative change of theta_max when the record is scaled by
1 + 1e-9): errors below it are not meaningful. Needs numpy and matplotlib.
"""
import argparse
import csv
import math
from collections import OrderedDict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def f(x):
    try:
        return float(x)
    except (TypeError, ValueError):
        return math.nan


def quantile(v, q):
    v = sorted(v)
    if not v:
        return math.nan
    pos = q * (len(v) - 1)
    lo = int(math.floor(pos))
    hi = min(lo + 1, len(v) - 1)
    if math.isinf(v[hi]) or math.isinf(v[lo]):
        return v[hi] if pos > lo else v[lo]
    return v[lo] + (pos - lo) * (v[hi] - v[lo])


def ill_conditioned(cases, limit=1e-6):
    """Cases whose reference is not resolved to `limit`: theta_max moves by more than that when
    the record is scaled by 1 + 1e-9, or between the reference and ERK8 one decade looser."""
    return {c["case"] for c in cases if f(c["theta_ref_rad"]) > 0
            and (f(c["cond_theta_rel"]) > limit or f(c["check_theta_rel"]) > limit)}


def summarize(runs, cases):
    ill = ill_conditioned(cases)
    by = OrderedDict()
    for r in runs:
        by.setdefault(r["setting"], []).append(r)
    out = []
    for setting, rs in by.items():
        rock = [r for r in rs if f(r["theta_ref_rad"]) > 0]
        failed = [r for r in rs if r["status"] in ("solver_failure", "time_limit")]
        err = [math.inf if r["status"] in ("solver_failure", "time_limit") else f(r["err_theta_rel"]) for r in rock]
        big = [e for e, r in zip(err, rock) if f(r["theta_ref_rad"]) >= 1e-3]
        wc = [e for e, r in zip(err, rock) if r["case"] not in ill]
        out.append(dict(
            setting=setting, family=rs[0]["family"], knob=f(rs[0]["knob"]), integrator=rs[0]["integrator"],
            rtol=f(rs[0]["rtol"]), atol_theta=f(rs[0]["atol_theta"]), atol_omega=f(rs[0]["atol_omega"]),
            stop=rs[0]["stop_at_samples"], cases=len(rs), rocking=len(rock), fails=len(failed),
            status_mismatch=sum(1 for r in rs if r["status_match"] != "1"),
            err_median=quantile(err, 0.5), err_p90=quantile(err, 0.9), err_worst=quantile(err, 1.0),
            err_worst_1mrad=quantile(big, 1.0),
            err_p90_wc=quantile(wc, 0.9), err_worst_wc=quantile(wc, 1.0),
            t_theta_err_median_s=quantile([f(r["err_t_theta_s"]) for r in rock], 0.5),
            omega_err_median=quantile([f(r["err_omega_rel"]) for r in rock], 0.5),
            uplift_err_median_s=quantile([f(r["err_uplift_s"]) for r in rock], 0.5),
            d_impacts_median=quantile([abs(f(r["d_impacts"])) for r in rock], 0.5),
            wall_median_ms=1e3 * quantile([f(r["wall_median_s"]) for r in rs], 0.5),
            wall_rock_median_ms=1e3 * quantile([f(r["wall_median_s"]) for r in rock], 0.5),
            cost_multiple_median=quantile([f(r["cost_multiple"]) for r in rs], 0.5),
            steps_median=quantile([f(r["steps"]) for r in rs], 0.5),
            rhs_median=quantile([f(r["rhs_evals"]) for r in rs], 0.5),
        ))
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("prefix")
    ap.add_argument("--png", default="work_precision.png")
    ap.add_argument("--summary-csv", default=None)
    ap.add_argument("--markdown", default=None)
    ap.add_argument("--frames", default=None, help="restrict to these frames (comma list)")
    a = ap.parse_args()

    runs = list(csv.DictReader(open(a.prefix + "_runs.csv")))
    cases = list(csv.DictReader(open(a.prefix + "_cases.csv")))
    if a.frames:
        keep = set(a.frames.split(","))
        runs = [r for r in runs if r["frame"] in keep]
        cases = [c for c in cases if c["frame"] in keep]
    s = summarize(runs, cases)
    rock_cases = [c for c in cases if f(c["theta_ref_rad"]) > 0]
    cond = [f(c["cond_theta_rel"]) for c in rock_cases]
    floor_ms = 1e3 * quantile([f(c["floor_s"]) for c in cases], 0.5)
    floor_tab_ms = 1e3 * quantile([f(c.get("floor_table_s")) for c in cases], 0.5)

    fig, axes = plt.subplots(1, 2, figsize=(14, 6), sharex=True)
    fams = OrderedDict()
    for row in s:
        fams.setdefault(row["family"], []).append(row)
    # Okabe–Ito colours (colour-blind safe); the engine's own integrator in black.
    colors = {"dopri5": "#000000", "cvode-adams": "#0072B2", "cvode-bdf": "#CC79A7", "arkode-erk5": "#009E73",
              "arkode-erk8": "#E69F00", "fixed-rk4": "#D55E00"}
    for ax, key, title in ((axes[0], "err_median", "median"), (axes[1], "err_p90", "90th percentile")):
        for fam, rows in fams.items():
            if fam in ("preset", "preset-before") or "/atol=" in fam:
                continue
            base = fam.split("/")[0]
            ls = "-" if fam.endswith("/stop") or fam == "fixed-rk4" else "--"
            x = [r["wall_median_ms"] for r in rows]
            y = [max(r[key], 1e-16) for r in rows]
            ax.loglog(x, y, ls, marker="o" if fam != "fixed-rk4" else "s", ms=3.5, color=colors.get(base, "k"),
                      label=fam.replace("/stop", " (stop at samples)").replace("/nostop", " (no stop)"))
            if fam in ("dopri5/stop", "arkode-erk5/stop") or fam == "fixed-rk4":
                for r in rows:
                    lab = f"{r['knob']:.0e}" if fam != "fixed-rk4" else f"dt/{r['knob']:g}"
                    ax.annotate(lab, (r["wall_median_ms"], max(r[key], 1e-16)), fontsize=6, xytext=(3, 3),
                                textcoords="offset points")
        pcol = {"preset:fast": "#56B4E9", "preset:balanced": "#F0E442", "preset:reference": "#D55E00"}
        for r in fams.get("preset", []):
            ax.loglog([r["wall_median_ms"]], [max(r[key], 1e-16)], "*", ms=15, mec="k",
                      color=pcol.get(r["setting"], "w"), label=r["setting"], zorder=5)
        for r in fams.get("preset-before", []):  # the same preset on ARKODE ERK5, before dopri5
            name = r["setting"].replace("preset-before:", "preset:")
            ax.loglog([r["wall_median_ms"]], [max(r[key], 1e-16)], "*", ms=13, mfc="none", mew=1.5,
                      color=pcol.get(name, "k"), label=name + " before (ARKODE ERK5)", zorder=5)
        if cond:
            c50 = quantile(cond, 0.5)
            ax.axhspan(1e-16, max(c50, 1e-16), color="0.85", zorder=0)
            ax.text(0.02, 0.02, f"conditioning: θ_max moves by {c50:.1e} (median) when the record is scaled by 1+1e-9",
                    transform=ax.transAxes, fontsize=7)
        ax.axvline(floor_ms, color="k", ls=":", lw=1)
        ax.text(floor_ms, 0.5, " floor: 1 RHS/sample", rotation=90, fontsize=7, va="top",
                transform=ax.get_xaxis_transform())
        ax.set_xlabel("median wall time per case [ms]")
        ax.set_ylabel(f"{title} of the θ_max relative error")
        ax.set_title(f"{title} over {len(rock_cases)} rocking cases", fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        ax.set_ylim(1e-13, 10)
    axes[0].legend(fontsize=7, loc="upper right", ncol=1)
    fig.suptitle(f"Work-precision, {len(cases)} cases ({len(set(c['frame'] for c in cases))} frames): "
                 f"error against ERK8 reference vs cost; 2-core box, medians of repeats", fontsize=11)
    fig.tight_layout()
    fig.savefig(a.png, dpi=110)
    print("wrote", a.png)

    if a.summary_csv:
        with open(a.summary_csv, "w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=list(s[0].keys()))
            w.writeheader()
            for row in s:
                w.writerow({k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in row.items()})
        print("wrote", a.summary_csv)
    lines = ["| setting | rocking cases | fails | status ≠ ref | median θ_max err | p90 | worst | worst (θ_ref ≥ 1 mrad) | p90 / worst, well-cond. "
             "| median \\|Δt_θmax\\| [s] | median ω_max err | median \\|Δimpacts\\| | median wall [ms] | × floor | "
             "median steps | median RHS |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in s:
        lines.append(f"| {r['setting']} | {r['rocking']} | {r['fails']} | {r['status_mismatch']} | "
                     f"{r['err_median']:.1e} | {r['err_p90']:.1e} | {r['err_worst']:.1e} | {r['err_worst_1mrad']:.1e} | "
                     f"{r['err_p90_wc']:.1e} / {r['err_worst_wc']:.1e} | "
                     f"{r['t_theta_err_median_s']:.1e} | {r['omega_err_median']:.1e} | {r['d_impacts_median']:.0f} | "
                     f"{r['wall_median_ms']:.2f} | {r['cost_multiple_median']:.1f} | {r['steps_median']:.0f} | "
                     f"{r['rhs_median']:.0f} |")
    text = "\n".join(lines)
    ill = ill_conditioned(cases)
    extra = (f"\nCases: {len(cases)}, rocking in the reference: {len(rock_cases)}, of which {len(ill)} "
             f"ill-conditioned (reference not resolved to 1e-6: {', '.join(sorted(ill))}). Floor (one RHS per record "
             f"sample), median per case: {floor_ms:.3f} ms exact EquationOfMotion, {floor_tab_ms:.3f} ms "
             f"tabulated (EomTable). Conditioning (θ_max change for a 1e-9 record scaling), median "
             f"{quantile(cond, 0.5):.1e}, 90th pct {quantile(cond, 0.9):.1e}, worst {quantile(cond, 1.0):.1e}. "
             f"Reference check: ERK8 one decade looser, median {quantile([f(c['check_theta_rel']) for c in rock_cases], 0.5):.1e}, "
             f"worst {quantile([f(c['check_theta_rel']) for c in rock_cases], 1.0):.1e}; CVODE Adams 1e-12, median "
             f"{quantile([f(c['cross_theta_rel']) for c in rock_cases], 0.5):.1e}, worst "
             f"{quantile([f(c['cross_theta_rel']) for c in rock_cases], 1.0):.1e}.\n")
    if a.markdown:
        with open(a.markdown, "w") as fh:
            fh.write(text + "\n" + extra)
        print("wrote", a.markdown)
    else:
        print(text)
        print(extra)


if __name__ == "__main__":
    main()
