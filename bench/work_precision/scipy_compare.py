#!/usr/bin/python3
"""SciPy comparison for the work-precision study (issue 4). Optional: skips when SciPy is absent.

The same equations of motion as the engine, solved the way a careful SciPy script would:
solve_ivp(DOP853) over each flight between impacts, with event location for the impact
(theta_1 = 0 while closing), the rotation peaks (theta_1' = 0, for an exact theta_max) and the
fracture/overturning angle; restitution theta_1'+ = r theta_1'- at each impact; at rest the
record is scanned for the first time |u_g''| exceeds the physical uplift threshold; the
engine's return-to-rest rule (remaining Zeno time below 1e-4 s, or a flight rise below
10 atol_theta) ends the impact sequence. Nothing is re-derived in Python: the coefficients
I, J, Q = G g + K and S of Eq. (31) on the theta_1 <= 0 branch, r, the uplift threshold and the
stop angle come from the engine itself (pcrf_eom_table writes them on a 300001-point grid,
step 1e-6 rad; linear interpolation there is exact to ~1e-12 relative), and so does the
scaled record (same samples, bit for bit). Side +1 is the odd mirror (I, S even; J, Q odd).

usage: scipy_compare.py --eom-table BIN [--records-dir DIR] [--records ER1,ER2,ER9] [--scale 3]
                        [--rtols 1e-5,1e-6,1e-7,1e-8] [--wp-runs WP_runs.csv] [--out PREFIX]
                        [--png FILE] [--repeats 3]

Writes PREFIX.csv (one row per record x rtol: theta_max, error against the engine's reference
when --wp-runs is given, wall time, RHS evaluations) and, with --wp-runs, a comparison with
the engine's presets on the same cases (PREFIX.md table, --png figure).
"""
import argparse
import csv
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time

try:
    import numpy as np
    from scipy.integrate import solve_ivp
except ImportError as e:  # pragma: no cover
    print(f"scipy_compare.py: skipped ({e}); install python3-scipy to run it", file=sys.stderr)
    sys.exit(0)


class Model:
    def __init__(self, table_csv, record_txt):
        meta = {}
        rows = []
        with open(table_csv) as f:
            for line in f:
                if line.startswith("#"):
                    k, v = line[1:].split("=")
                    k = k.strip()
                    meta[k] = v.strip() if k == "frame" else float(v)
                elif line.startswith("phi"):
                    continue
                else:
                    rows.append([float(x) for x in line.split(",")])
        a = np.array(rows)
        self.phi0 = a[0, 0]
        self.dphi = a[1, 0] - a[0, 0]
        self.inv_dphi = 1.0 / self.dphi
        g = meta["g"]
        # Plain Python lists: per-call indexing is faster than numpy scalars in the RHS.
        self.I = a[:, 1].tolist()
        self.J = a[:, 2].tolist()
        self.Q = (a[:, 3] * g + a[:, 4]).tolist()
        self.S = a[:, 5].tolist()
        self.n = len(self.I)
        self.r = meta["restitution"]
        self.threshold = meta["uplift_threshold_m_s2"]
        self.theta_stop = min(meta["fracture_angle_rad"], 0.999 * meta["closing_limit_rad"])
        i0 = int(round(-self.phi0 * self.inv_dphi))
        self.I0, self.Q0, self.S0 = self.I[i0], self.Q[i0], self.S[i0]
        with open(record_txt) as f:
            self.dt = float(f.readline())
            self.acc = [float(x) for x in f]
        self.inv_dt = 1.0 / self.dt
        self.t_rec = (len(self.acc) - 1) * self.dt
        self.nfev = 0

    def ground(self, t):
        if t < 0.0 or t > self.t_rec:
            return 0.0
        x = t * self.inv_dt
        i = int(x)
        if i >= len(self.acc) - 1:
            return self.acc[-1]
        f = x - i
        return self.acc[i] + f * (self.acc[i + 1] - self.acc[i])

    def terms(self, u):
        x = (u - self.phi0) * self.inv_dphi
        i = int(x)
        if i < 0:
            i = 0
        elif i >= self.n - 1:
            i = self.n - 2
        f = x - i
        I, J, Q, S = self.I, self.J, self.Q, self.S
        return (I[i] + f * (I[i + 1] - I[i]), J[i] + f * (J[i + 1] - J[i]),
                Q[i] + f * (Q[i + 1] - Q[i]), S[i] + f * (S[i + 1] - S[i]))

    def rhs(self, t, y, side):
        self.nfev += 1
        th, om = y[0], y[1]
        u = -th if side < 0 else th
        I, J, Q, S = self.terms(u)
        s = 1.0 if side < 0 else -1.0
        return [om, (S * self.ground(t) - s * J * om * om - s * Q) / I]

    def rest_acceleration(self, a, side):
        s = -1.0 if side < 0 else 1.0
        return (self.S0 * a + s * self.Q0) / self.I0

    def first_exceedance(self, t_from, t_end):
        thr = self.threshold
        if abs(self.ground(t_from)) > thr:
            return t_from
        i = max(0, int(math.floor(t_from * self.inv_dt)))
        acc = self.acc
        while i + 1 < len(acc):
            t0 = i * self.dt
            if t0 > t_end:
                return None
            a0, a1 = acc[i], acc[i + 1]
            best = None
            for level in (thr, -thr):
                up = a1 > level if level > 0 else a1 < level
                if not up:
                    continue
                s = min(max((level - a0) / (a1 - a0), 0.0), 1.0)
                tc = max(t0 + s * self.dt, t_from)
                if best is None or tc < best:
                    best = tc
            if best is not None:
                return best if best <= t_end else None
            i += 1
        return None


def solve(model, rtol, atol_theta, atol_omega, zeno_time=1e-4):
    """One case; returns dict(theta_max, t_theta_max, impacts, status, nfev)."""
    model.nfev = 0
    t, t_end = 0.0, model.t_rec
    theta_max, t_theta_max, impacts = 0.0, float("nan"), 0
    status = "at_rest"
    at_rest = True
    y = [0.0, 0.0]
    side = -1
    while t < t_end:
        if at_rest:
            t_open = model.first_exceedance(t, t_end)
            if t_open is None:
                status = "at_rest"
                break
            t = t_open
            side = -1 if model.ground(t) > 0 else 1
            y = [0.0, 0.0]
            at_rest = False
        # One flight on `side`, from (t, y) to the next impact, limit or the end.
        def impact(tt, yy, *_):
            return yy[0]
        impact.terminal = True
        impact.direction = 1 if side < 0 else -1

        def peak(tt, yy, *_):
            return yy[1]
        peak.terminal = False
        peak.direction = 1 if side < 0 else -1

        def limit(tt, yy, *_):
            return abs(yy[0]) - model.theta_stop
        limit.terminal = True
        limit.direction = 1

        first_step = None
        if y[0] == 0.0 and y[1] != 0.0:
            a = abs(model.rest_acceleration(model.ground(t), side))
            flight = 2.0 * abs(y[1]) / a if a > 0 else math.inf
            if flight < 0.01:
                first_step = flight / 16.0
        sol = solve_ivp(model.rhs, (t, t_end), y, method="DOP853", rtol=rtol, atol=[atol_theta, atol_omega],
                        events=[impact, peak, limit], args=(side,), first_step=first_step)
        if sol.status < 0:
            status = "solver_failure"
            break
        for te, ye in zip(sol.t_events[1], sol.y_events[1]):
            if abs(ye[0]) > theta_max:
                theta_max, t_theta_max = abs(ye[0]), te
        if abs(sol.y[0, -1]) > theta_max:
            theta_max, t_theta_max = abs(sol.y[0, -1]), sol.t[-1]
        if len(sol.t_events[2]):
            status = "tendon_fracture_or_overturned"
            break
        if len(sol.t_events[0]) == 0:  # reached the end of the record in flight
            t = t_end
            status = "rocking_at_end"
            break
        t = sol.t_events[0][0]
        omega_before = sol.y_events[0][0][1]
        impacts += 1
        omega_after = model.r * omega_before
        side = -side
        a = model.ground(t)
        if abs(a) < model.threshold and model.r < 1.0:
            a_min = min(abs(model.rest_acceleration(a, -1)), abs(model.rest_acceleration(a, 1)))
            v = abs(omega_after)
            if 2.0 * v / (a_min * (1.0 - model.r)) <= zeno_time or v * v / (2.0 * a_min) <= 10.0 * atol_theta:
                at_rest = True
                continue
        y = [0.0, omega_after]
    return dict(theta_max=theta_max, t_theta_max=t_theta_max, impacts=impacts, status=status, nfev=model.nfev)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--eom-table", required=True, help="path of the pcrf_eom_table executable")
    ap.add_argument("--records-dir", default=os.environ.get("PCRF_RECORDS_DIR",
                                                             os.path.join(os.path.dirname(__file__),
                                                                          "../../../shared/records")))
    ap.add_argument("--records", default="ER1,ER2,ER9")
    ap.add_argument("--scale", type=float, default=3.0)
    ap.add_argument("--rtols", default="1e-5,1e-6,1e-7,1e-8")
    ap.add_argument("--theta-scale", type=float, default=1e-2, help="atol_theta = theta_scale * rtol")
    ap.add_argument("--omega-scale", type=float, default=1e-1, help="atol_omega = omega_scale * rtol")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--wp-runs", help="OUT_runs.csv of pcrf_work_precision (basic frame, same records and scale)")
    ap.add_argument("--out", default="scipy_compare")
    ap.add_argument("--png", default=None)
    a = ap.parse_args()

    index = os.path.join(a.records_dir, "paper", "INDEX.csv")
    if not os.path.exists(index):
        print(f"scipy_compare.py: {index} not found: skipped", file=sys.stderr)
        return 0
    files = {r["er_id"]: r["file"] for r in csv.DictReader(open(index))}
    engine = {}
    if a.wp_runs:
        for r in csv.DictReader(open(a.wp_runs)):
            if r["frame"] == "basic":
                engine.setdefault(r["case"], []).append(r)

    rows = []
    tmp = tempfile.mkdtemp(prefix="pcrf_scipy_")
    for rid in a.records.split(","):
        table, rec = os.path.join(tmp, "eom.csv"), os.path.join(tmp, rid + ".txt")
        subprocess.run([a.eom_table, table, "0.3", "300001", os.path.join(a.records_dir, files[rid]), repr(a.scale),
                        rec], check=True)
        model = Model(table, rec)
        case = f"basic:{rid}x{a.scale:g}"
        ref = None
        if case in engine:
            ref = float(engine[case][0]["theta_ref_rad"])
        for rtol in [float(x) for x in a.rtols.split(",")]:
            walls, res = [], None
            for _ in range(a.repeats):
                t0 = time.perf_counter()
                res = solve(model, rtol, a.theta_scale * rtol, a.omega_scale * rtol)
                walls.append(time.perf_counter() - t0)
            err = abs(res["theta_max"] - ref) / ref if ref else float("nan")
            row = dict(case=case, duration_s=model.t_rec, rtol=rtol, theta_max_rad=res["theta_max"],
                       theta_ref_rad=ref if ref else float("nan"), err_theta_rel=err, impacts=res["impacts"],
                       status=res["status"], nfev=res["nfev"], wall_median_s=statistics.median(walls))
            rows.append(row)
            print(f"{case} DOP853 rtol={rtol:g}: theta_max={res['theta_max']:.10g} err={err:.2e} "
                  f"impacts={res['impacts']} {res['status']} nfev={res['nfev']} wall={row['wall_median_s']:.3f} s",
                  file=sys.stderr)
    with open(a.out + ".csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)

    if not engine:
        return 0
    # Engine settings on the same cases, from the work-precision run.
    want = ["preset:fast", "preset:balanced", "preset:reference"]
    lines = ["| case | solver | θ_max error | wall [ms] | SciPy / engine |", "|---|---|---|---|---|"]
    pts = {}
    for case in sorted({r["case"] for r in rows}):
        sc = {r["rtol"]: r for r in rows if r["case"] == case}
        for rt, r in sorted(sc.items(), reverse=True):
            lines.append(f"| {case} | SciPy DOP853 rtol {rt:g} | {r['err_theta_rel']:.1e} | "
                         f"{1e3 * r['wall_median_s']:.0f} | |")
            pts.setdefault(f"SciPy DOP853", []).append((case, rt, r["wall_median_s"], r["err_theta_rel"]))
        scipy_1e6 = sc.get(1e-6)
        for e in engine.get(case, []):
            if e["setting"] in want:
                wall = float(e["wall_median_s"])
                ratio = f"{scipy_1e6['wall_median_s'] / wall:.0f}x" if scipy_1e6 else ""
                lines.append(f"| {case} | engine {e['setting']} | {float(e['err_theta_rel']):.1e} | "
                             f"{1e3 * wall:.2f} | {ratio} (vs SciPy 1e-6) |")
                pts.setdefault("engine " + e["setting"], []).append((case, None, wall, float(e["err_theta_rel"])))
    with open(a.out + ".md", "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    if a.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(7, 4.5))
        markers = {"SciPy DOP853": "s", "engine preset:fast": "v", "engine preset:balanced": "o",
                   "engine preset:reference": "^"}
        for name, p in pts.items():
            ax.loglog([x[2] for x in p], [max(x[3], 1e-16) for x in p], markers.get(name, "x"), label=name, ms=6)
        for case in sorted({r["case"] for r in rows}):
            p = sorted([x for x in pts["SciPy DOP853"] if x[0] == case], key=lambda x: x[2])
            ax.loglog([x[2] for x in p], [max(x[3], 1e-16) for x in p], "-", color="0.6", lw=0.8)
        ax.set_xlabel("wall time per case [s] (median of %d)" % a.repeats)
        ax.set_ylabel("θ_max relative error")
        ax.set_title("SciPy solve_ivp(DOP853) with events vs the engine, basic frame, "
                     + ", ".join(r.split(":")[1] for r in sorted({r['case'] for r in rows})), fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(a.png, dpi=110)
        print("wrote", a.png, file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
