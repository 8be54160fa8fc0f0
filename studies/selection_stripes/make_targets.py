"""Illustrative conditional-spectrum targets for selection_stripes.toml, one per return period.

    cd studies/selection_stripes && python3 make_targets.py

pcrf computes no ground-motion model: a real study takes its targets from OpenQuake's
conditional-spectrum output or EzGM (docs/commands/record.md). For this example the library's
own RotD50 spectra stand in for the model: their geometric mean mu(T) and sigma 0.6 at every
period. Each stripe's target is the conditional spectrum (Baker 2011, J. Struct. Eng. 137(3))
on Sa(T* = 1 s) = x_T, the hazard curve's intensity at 1/T:
    epsilon* = (ln x_T - mu(T*)) / 0.6
    mean_ln_sa(T)  = mu(T) + rho(T, T*) epsilon* 0.6     (= ln x_T at T*)
    sigma_ln_sa(T) = 0.6 sqrt(1 - rho(T, T*)^2)          (= 0 at T*: every record scaled to x_T)
with rho Baker & Jayaram (2008), Earthquake Spectra 24(1), over the library's periods 0.1-4 s.
Standard library only; the intensities are the hazard file's, interpolated log-log.
"""
import csv
import math

T_STAR_S = 1.0
SIGMA = 0.6
RETURN_PERIODS_YR = [475, 2475, 10000, 50000]


def bj2008(t1, t2):
    """Baker & Jayaram (2008) correlation of epsilon between periods t1 and t2 [s]."""
    tmin, tmax = min(t1, t2), max(t1, t2)
    c1 = 1 - math.cos(math.pi / 2 - 0.366 * math.log(tmax / max(tmin, 0.109)))
    c2 = 1 - 0.105 * (1 - 1 / (1 + math.exp(100 * tmax - 5))) * (tmax - tmin) / (tmax - 0.0099) if tmax < 0.2 else 0
    c3 = c2 if tmax < 0.109 else c1
    c4 = c1 + 0.5 * (math.sqrt(c3) - c3) * (1 + math.cos(math.pi * tmin / 0.109))
    if tmax < 0.109:
        return c2
    if tmin > 0.109:
        return c1
    return min(c2, c4) if tmax < 0.2 else c4


def rows(path):
    return list(csv.reader(line for line in open(path) if not line.startswith('#')))


def intensity_at(hazard, period_yr):
    """The curve's intensity at the rate 1/T, log-log between its points."""
    points = [(float(x), float(r)) for x, r in rows(hazard)[1:]]
    rate = 1.0 / period_yr
    for (x0, r0), (x1, r1) in zip(points, points[1:]):
        if r1 <= rate <= r0:
            return math.exp(math.log(x0) + math.log(rate / r0) / math.log(r1 / r0) * math.log(x1 / x0))
    raise ValueError(f'{period_yr} yr is outside {hazard}')


def main():
    table = rows('library.csv')
    header = table[0]
    columns = [i for i, h in enumerate(header) if h.startswith('sa_g_')]
    periods = [float(header[i][5:-1]) for i in columns]
    pairs = [r for r in table[1:] if r[1] == 'rotd50']
    mu = [sum(math.log(float(r[i])) for r in pairs) / len(pairs) for i in columns]
    star = periods.index(T_STAR_S)
    for period_yr in RETURN_PERIODS_YR:
        x = intensity_at('hazard_sa1_rotd50.csv', period_yr)
        epsilon = (math.log(x) - mu[star]) / SIGMA
        with open(f't{period_yr}.csv', 'w') as out:
            out.write(f'# illustrative conditional spectrum (make_targets.py): Sa RotD50({T_STAR_S:g} s) = {x:.6g} g '
                      f'at {period_yr} yr, epsilon* {epsilon:.3f}; the library\'s geometric mean, sigma {SIGMA:g}, '
                      'rho Baker & Jayaram 2008\n')
            out.write('period_s,mean_ln_sa,sigma_ln_sa\n')
            for t, m in zip(periods, mu):
                if not 0.1 <= t <= 4.0:
                    continue
                rho = 1.0 if t == T_STAR_S else bj2008(t, T_STAR_S)
                mean = math.log(x) if t == T_STAR_S else m + rho * epsilon * SIGMA
                out.write(f'{t:g},{mean:.17g},{SIGMA * math.sqrt(max(0.0, 1 - rho * rho)):.17g}\n')


if __name__ == '__main__':
    main()
