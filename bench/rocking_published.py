#!/usr/bin/python3
"""The block's overturning amplitudes against the published ones (not a test; the tests
check the same cases at fixed points: tests/solver/rocking_canon_test.cpp). Prints a markdown
table and draws the one-sine overturning spectrum of Zhang & Makris (2001)'s block with their
published points (docs/rocking_canon.md, "Published overturning amplitudes").

    /usr/bin/python3 bench/rocking_published.py --pcrf build/pcrf [--figure docs/rocking_published.png]
    cmake --build build --target rocking_published

Every engine number is found with `pcrf run`: a scan of the amplitude upward in steps of
0.5 % from the uplift threshold, each change of verdict (safe, overturned after k impacts)
refined by bisection to 1e-5. The published values are quoted from the papers' text:

  Makris & Konstantinidis (2003), EESD 32(2) 265-289, p. 271 and Fig. 4.
  Zhang & Makris (2001), J. Eng. Mech. 127(5) 473-483, pp. 478-480 and Figs. 7, 8, 10.
  Makris & Roussos (2000), Geotechnique 50(3) 243-262, pp. 251-252 and Figs. 9, 11.

The linearised formulation of those papers (their Eq. (50) in Zhang & Makris) is also
integrated here independently (scipy DOP853, rtol 1e-12), as a check of the published
linear values and of the engine in the slender limit.
"""
import argparse
import json
import math
import subprocess
import sys

G_M_S2 = 9.81  # the engine's gravity (include/pcrf/units.hpp)
STEP = 1.005  # the scan's step: a band of verdicts narrower than 0.5 % can be missed


def block(alpha, p=None, size_m=None, restitution=None):
    args = ["--model", "block", "--slenderness-rad", repr(alpha)]
    args += ["--frequency-parameter-rad-s", repr(p)] if p else ["--size-m", repr(size_m)]
    return args + (["--restitution", repr(restitution)] if restitution else [])


class Engine:
    def __init__(self, pcrf):
        self.pcrf = pcrf

    def verdict(self, scene, shape, period_s, amplitude_g):
        """(overturned, impacts before overturning or None)."""
        command = [self.pcrf, "run", *scene, "--tail-s", "30",
                   "--synthetic", f"{shape}:period_s={period_s!r},amplitude_g={amplitude_g!r},dt_s={period_s / 2000!r}"]
        out = subprocess.run(command, capture_output=True, text=True)
        if out.returncode != 0:
            sys.exit(f"rocking_published: {' '.join(command)} failed:\n{out.stderr}")
        r = json.loads(out.stdout)
        return (True, r["impacts"]) if r["status"] == "overturned" else (False, None)

    def boundaries(self, scene, shape, period_s, lo_g, hi_g, step=STEP):
        """Every amplitude [g] in (lo_g, hi_g) where the verdict changes: (amplitude, before, after)."""
        found, a, before = [], lo_g, self.verdict(scene, shape, period_s, lo_g)
        while a < hi_g:
            a_next = a * step
            after = self.verdict(scene, shape, period_s, a_next)
            if after != before:
                lo, hi = a, a_next
                while hi - lo > 1e-5 * hi:
                    mid = 0.5 * (lo + hi)
                    (lo, hi) = (mid, hi) if self.verdict(scene, shape, period_s, mid) == before else (lo, mid)
                found.append((hi, before, after))
            a, before = a_next, after
        return found


def linear_boundaries(beta_lo, beta_hi, omega_ratio, restitution, p=2.14):
    """The same boundaries [a_p/(alpha g)] for the linearised equation, one-sine pulse."""
    from scipy.integrate import solve_ivp

    def verdict(beta, alpha=0.01):
        wp = omega_ratio * p
        tp = 2 * math.pi / wp
        t, y, side, impacts = math.asin(1 / beta) / wp, [0.0, 0.0], -1, 0
        while True:
            start = t
            ground = (lambda t: beta * alpha * math.sin(wp * t)) if t < tp else (lambda t: 0.0)

            def hit(t, y):
                return y[0] if t > start + 1e-9 else side

            def fallen(t, y):
                return abs(y[0]) - 20 * alpha
            hit.terminal, hit.direction, fallen.terminal = True, -side, True
            sol = solve_ivp(lambda t, y: [y[1], -p * p * (alpha * side - y[0] + ground(t))],
                            (t, tp if t < tp else 200.0), y, method="DOP853", rtol=1e-12, atol=1e-15,
                            events=[hit, fallen])
            t, y = sol.t[-1], list(sol.y[:, -1])
            if sol.status == 1 and sol.t_events[1].size:
                return True, impacts
            if sol.status == 1:
                impacts, y, side = impacts + 1, [0.0, restitution * y[1]], -side
                if abs(y[1]) < 1e-9:
                    return False, None
            elif t >= 200.0:
                return False, None

    found, b, before = [], beta_lo, verdict(beta_lo)
    while b < beta_hi:
        after = verdict(b * STEP)
        if after != before:
            lo, hi = b, b * STEP
            while hi - lo > 1e-5 * hi:
                mid = 0.5 * (lo + hi)
                (lo, hi) = (mid, hi) if verdict(mid) == before else (lo, mid)
            found.append((hi, before, after))
        b, before = b * STEP, after
    return found


def mode(verdict):
    overturned, impacts = verdict
    return "safe" if not overturned else f"overturns after {impacts} impact{'s' if impacts != 1 else ''}"


def describe(bounds, scale, unit):
    return "; ".join(f"{scale * a:.5g}{unit} ({mode(b)} → {mode(c)})" for a, b, c in bounds)


def table(engine):
    print("| source (formulation) | block | pulse | published | engine |")
    print("| --- | --- | --- | --- | --- |")
    a15 = math.radians(15)
    b = engine.boundaries(block(a15, p=2.0), "pulse-cosine", 2.0, 0.30, 0.33)
    print(f"| Makris & Konstantinidis 2003, Fig. 4 (nonlinear) | α = 15°, p = 2.0 rad/s, r = 0.8995 (Housner) | "
          f"one-cosine, T_p = 2 s | 0.315 g safe, 0.316 g overturns | {describe(b, 1, ' g')} |")
    zm = block(0.25, p=2.14, restitution=0.9)
    period = 2 * math.pi / 15.7
    b = engine.boundaries(zm, "pulse-sine", period, 1.5, 2.5)
    print(f"| Zhang & Makris 2001, p. 480 (nonlinear) | α = 0.25, p = 2.14 rad/s, r = 0.9 | one-sine, ω_p = 15.7 rad/s "
          f"(ω_p/p = 7.34) | least overturning 2.22 g, one impact (linearised: 3.24 g, no impact) | {describe(b[:1], 1, ' g')} |")
    period5 = 2 * math.pi / (5 * 2.14)
    published5 = "3.00 safe, 3.01 overturns (one impact) … 6.32 overturns, 6.33 safe … 7.17 safe, 7.18 overturns (no impact)"
    slender = []
    for alpha in (0.25, 0.01):
        b = engine.boundaries(block(alpha, p=2.14, restitution=0.9), "pulse-sine", period5, 1.001 * alpha, 8 * alpha)
        slender = [x / alpha for x, _, _ in b]
        print(f"| Zhang & Makris 2001, Figs. 7-8 (linearised), a_p/(α g) | α = {alpha}, p = 2.14 rad/s, r = 0.9 | "
              f"one-sine, ω_p/p = 5 | {published5 if alpha == 0.25 else 'as above'} | {describe(b, 1 / alpha, '')} |")
    try:
        b = linear_boundaries(1.001, 8.0, 5.0, 0.9)
        print(f"| the same, linearised equation integrated here (DOP853) | – | one-sine, ω_p/p = 5 | as above | "
              f"{describe(b, 1, '')} |")
    except ImportError:
        print("rocking_published: scipy absent: the independent linearised check is skipped", file=sys.stderr)
    alpha, size = math.atan(1 / 3), math.sqrt(0.5 ** 2 + 1.5 ** 2)
    mr = block(alpha, size_m=size)
    b = engine.boundaries(mr, "pulse-sine", 1.0, 0.43, 0.50)
    print(f"| Makris & Roussos 2000, Fig. 9 (linearised) | 0.5 m × 1.5 m: α = 0.3218, p = 2.157 rad/s, r = 0.85 (Housner) | "
          f"one-sine, T_p = 1 s | 0.4513 g safe, 0.4514 g overturns | {describe(b[:1], 1, ' g')} |")
    b = engine.boundaries(block(0.01, size_m=size, restitution=0.85), "pulse-sine", 1.0, 1.3 * 0.01, 1.5 * 0.01)
    print(f"| the same in the slender limit, a_p/(α g) | α = 0.01, same p and r | one-sine, T_p = 1 s | "
          f"{0.4513 / alpha:.4f} safe, {0.4514 / alpha:.4f} overturns | {describe(b[:1], 100, '')} |")
    b = engine.boundaries(mr, "pulse-cosine", 1.0, 0.60, 0.65)
    print(f"| Makris & Roussos 2000, Fig. 11 (nonlinear) | as Fig. 9 | one-cosine, T_p = 1 s | 0.6245 g safe, 0.6255 g "
          f"overturns | {describe(b[:1], 1, ' g')} |")
    return slender


def figure(engine, path, slender):
    """`slender`: the engine's boundaries at omega_p/p = 5 for alpha = 0.01 [a_p/(alpha g)]."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib import ticker
    # The figures' style (pcrf.plot.style) from the module built beside the engine (build/python).
    sys.path.insert(0, str(__import__("pathlib").Path(engine.pcrf).resolve().parent / "python"))
    from pcrf.plot import style

    alpha, p, r = 0.25, 2.14, 0.9
    ratios = [1.5, 2, 2.5, 3, 3.5, 4, 4.5, 5, 5.5, 6, 6.5, 7, 7.34, 7.5, 8, 9, 10]
    lower, cape_low, cape_high = [], [], []
    for w in ratios:
        b = engine.boundaries(block(alpha, p=p, restitution=r), "pulse-sine", 2 * math.pi / (w * p), 1.001 * alpha,
                              30 * alpha, step=1.01)
        lower.append(b[0][0] / alpha if b else math.nan)
        safe_again = [x for x, before, after in b if before[0] and not after[0]]
        cape_low.append(safe_again[0] / alpha if safe_again else math.nan)
        cape_high.append(next((x / alpha for x, before, after in b if after == (True, 0)), math.nan))
    fig, ax = plt.subplots(figsize=(9.6, 4.8), constrained_layout=True)
    ax.plot(ratios, lower, "-o", color=style.BLUE, ms=4, label="engine: least overturning amplitude")
    ax.plot(ratios, cape_low, "--", color=style.ORANGE, label="engine: safe again above (upper end of mode 1)")
    ax.plot(ratios, cape_high, "-.", color=style.GREEN, label="engine: overturns without an impact (mode 2)")
    ax.plot([5, 5, 5], [3.01, 6.32, 7.18], "s", mfc="none", color=style.BLACK, ms=7,
            label="Zhang & Makris 2001, ω_p/p = 5 (linearised)")
    ax.plot([5] * len(slender), slender, "x", color=style.PURPLE, ms=7, label="engine, α = 0.01 (slender limit)")
    ax.plot([15.7 / 2.14], [2.22 / alpha], "D", color=style.VERMILLION, ms=7,
            label="Zhang & Makris 2001, 15.7 rad/s (nonlinear)")
    ax.axvline(2 * math.pi * 2.58 / p, color=style.GREY, ls=":", lw=1.2,
               label="Zhang & Makris 2001: above, only mode 2 (nonlinear)")
    ax.set(xlabel="pulse to block frequency ratio ω_p / p [–]", ylabel="pulse amplitude a_p / (α g) [–]",
           yscale="log", title="One-sine overturning of a block: α = 0.25 rad, p = 2.14 rad/s, r = 0.9")
    ax.yaxis.set_major_formatter(ticker.FormatStrFormatter("%g"))
    # Minor labels at 2, 3 and 5 only: all eight crowd each other near the top of a decade.
    ax.yaxis.set_minor_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}" if round(v / 10 ** math.floor(math.log10(v))) in (2, 3, 5) else ""))
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize="small")  # outside: no point hidden
    fig.savefig(path, dpi=110)
    print(f"\nfigure: {path}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pcrf", required=True)
    parser.add_argument("--figure", help="PNG of the one-sine spectrum of Zhang & Makris's block")
    args = parser.parse_args()
    engine = Engine(args.pcrf)
    slender = table(engine)
    if args.figure:
        figure(engine, args.figure, slender)


if __name__ == "__main__":
    main()
