#!/usr/bin/env python3
"""Record selection checked against a target and against a reference implementation.

    build/pcrf record spectra ../shared/records -o /tmp/lib.csv
    python3 bench/selection_check.py --library /tmp/lib.csv --target TARGET.csv [--make-target \
        [--t-star 1 --epsilon 1]] [--ezgm PATH/TO/EzGM/selection.py] -n 10 20 30 --kind component --seeds 1 2

For each N and seed it runs `pcrf record select --json` three ways: Baker & Lee's algorithm as
they run it (`--starts 1 --loops 2`: one simulated set, two greedy passes), pcrf's default (the
greedy from each of the 20 simulated sets, passes until none replaces an entry, each scale
optimised continuously within the limits), and the same on the objective weighted by the
tolerances (`--relative-sigma --w-mean 4 --w-sigma 1`: Σ (Δm/0.05)² + Σ ((Δσ/σ)/0.10)², up to a
factor). It prints the largest error over the target's periods of the selected set's median
(exp of the mean ln Sa) and of its sigma ln Sa, whether both are within 5 % and 10 %, and the
sum of squared errors that Baker & Lee (2018) minimise (w_mean 1, w_sigma 2), their figure of
merit, for every row whatever it optimised. With --ezgm it
runs EzGM's conditional_spectrum.select (Ozsarac, github.com/volkanozsarac/EzGM, fetched
separately, never copied here) on the same library and target: its imports of OpenQuake,
selenium and numba are stubbed (the selection uses none of them; njit becomes a no-op), and the
target is set directly, so no ground-motion model runs. EzGM's own error measures are printed
beside pcrf's.

--make-target writes a conditional-spectrum-shaped target for the check alone: the library's
geometric-mean spectrum as the median, sigma 0.6, epsilon --epsilon (1) at T* = --t-star (1 s),
Baker & Jayaram (2008) correlation, periods 0.1 s to 4 s of the library's grid. Real targets come from OpenQuake's
conditional-spectrum output or EzGM (docs/commands/record.md).
"""
import argparse
import csv
import importlib.util
import json
import math
import subprocess
import sys
import types
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent


def read_library(path, kind):
    lines = [l for l in open(path) if not l.startswith('#')]
    rows = list(csv.reader(lines))
    header, cols = rows[0], [i for i, h in enumerate(rows[0]) if h.startswith('sa_g_')]
    periods = np.array([float(header[i][5:-1]) for i in cols])
    entries = [r for r in rows[1:] if r[1] == kind]
    sa = np.array([[float(r[i]) for i in cols] for r in entries])
    return periods, sa, entries


def bj2008(t1, t2):
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


def make_target(library, kind, path, t_star=1.0, eps=1.0, sigma=0.6):
    periods, sa, _ = read_library(library, kind)
    keep = (periods >= 0.1) & (periods <= 4.0)
    t = periods[keep]
    mu = np.log(sa).mean(axis=0)[keep]
    rho = np.array([bj2008(x, t_star) for x in t])
    with open(path, 'w') as f:
        f.write('# check target: library geometric mean (%s), sigma %g, eps %g at T* = %g s, rho Baker & Jayaram 2008\n'
                % (kind, sigma, eps, t_star))
        f.write('period_s,mean_ln_sa,sigma_ln_sa\n')
        for ti, m, r in zip(t, mu + rho * eps * sigma, sigma * np.sqrt(1 - rho ** 2)):
            f.write('%.10g,%.6f,%.6f\n' % (ti, m, r))


def read_target(path):
    rows = list(csv.DictReader(l for l in open(path) if not l.startswith('#')))
    return (np.array([float(r['period_s']) for r in rows]), np.array([float(r['mean_ln_sa']) for r in rows]),
            np.array([float(r['sigma_ln_sa']) for r in rows]))


def errors(ln_sa, mean, sigma):
    m, s = ln_sa.mean(axis=0), ln_sa.std(axis=0)
    median = np.max(np.abs(np.exp(m - mean) - 1)) * 100
    positive = sigma > 0
    sig = np.max(np.abs(s[positive] - sigma[positive]) / sigma[positive]) * 100
    sse = np.sum((m - mean) ** 2) + 2 * np.sum((s - sigma) ** 2)
    return median, sig, sse


PCRF_WAYS = [('pcrf as Baker & Lee', ['--starts', '1', '--loops', '2']),
             ('pcrf', []),
             ('pcrf, tolerance weights', ['--relative-sigma', '--w-mean', '4', '--w-sigma', '1'])]


def run_pcrf(args, n, seed, extra):
    out = subprocess.run([str(ROOT / 'build/pcrf'), 'record', 'select', '--target', args.target, '--library', args.library,
                          '-n', str(n), '--kind', args.kind, '--seed', str(seed), '--scale-min', str(args.scale_min),
                          '--scale-max', str(args.scale_max), '--json'] + extra, capture_output=True, text=True, check=True)
    j = json.loads(out.stdout)
    return np.array([r['ln_sa'] for r in j['records']]), [r['scale'] for r in j['records']]


def load_ezgm(path):
    """EzGM's selection.py (and the utility.py beside it, which it imports relatively) as the
    package EzGM, with the modules it imports for other tasks stubbed."""
    for name in ['selenium', 'webdriverdownloader', 'numba', 'openquake', 'openquake.hazardlib', 'openquake.baselib',
                 'openquake.baselib.node', 'requests']:
        sys.modules.setdefault(name, types.ModuleType(name))
    sys.modules['selenium'].webdriver = None
    sys.modules['webdriverdownloader'].ChromeDriverDownloader = sys.modules['webdriverdownloader'].GeckoDriverDownloader = None
    sys.modules['numba'].njit = lambda f: f
    for attr in ['gsim', 'imt', 'const', 'nrml']:
        setattr(sys.modules['openquake.hazardlib'], attr, None)
    sys.modules['openquake.baselib.node'].Node = None
    folder = Path(path).resolve().parent
    package = types.ModuleType('EzGM')
    package.__path__ = [str(folder)]
    sys.modules['EzGM'] = package
    sys.modules['EzGM.webdriverdownloader'] = sys.modules['webdriverdownloader']
    for name in ['utility', 'selection']:
        if not (folder / (name + '.py')).exists():
            continue
        spec = importlib.util.spec_from_file_location('EzGM.' + name, folder / (name + '.py'))
        module = importlib.util.module_from_spec(spec)
        sys.modules['EzGM.' + name] = module
        spec.loader.exec_module(module)
    return sys.modules['EzGM.selection']


def run_ezgm(module, args, n, seed):
    periods, sa, entries = read_library(args.library, args.kind)
    t, mean, sigma = read_target(args.target)
    # The library's Sa at the target's periods, linear in (ln T, ln Sa) as pcrf interpolates.
    lib = np.exp(np.array([np.interp(np.log(t), np.log(periods), np.log(row)) for row in sa]))
    cs = module.conditional_spectrum.__new__(module.conditional_spectrum)
    cs.T, cs.mu_ln, cs.sigma_ln, cs.cond = t, mean, sigma, 0
    rho = np.array([[bj2008(a, b) for b in t] for a in t])
    cs.cov = np.outer(sigma, sigma) * rho
    count = len(entries)
    cs.database = {'Name': 'NGA_W2', 'NGA_num': np.arange(count), 'Periods': t, 'Sa_RotD50': lib, 'Sa_1': lib, 'Sa_2': lib,
                   'soil_Vs30': np.full(count, 500.0), 'magnitude': np.full(count, 7.0), 'Rjb': np.full(count, 10.0),
                   'mechanism': np.zeros(count), 'EQID': np.arange(count),
                   'Filename_1': np.array([e[2] for e in entries]), 'Filename_2': np.array([e[3] for e in entries])}
    # EzGM's single-component mode doubles the list with Sa_2 (its two components); our
    # library rows are already one per entry, so its two-component (RotD50) mode reads them as they are.
    cs.selection, cs.Sa_def = 2, 'RotD50'
    import inspect
    if 'selection' in inspect.signature(cs.select).parameters:  # EzGM versions differ in where these go
        cs.select(nGM=n, selection=2, Sa_def='RotD50', isScaled=1, maxScale=args.scale_max, nTrials=20,
                  weights=[1, 2, 0.3], seedValue=seed, nLoop=2, tol=10)
    else:
        cs.select(nGM=n, isScaled=1, maxScale=args.scale_max, nTrials=20, weights=[1, 2, 0.3], seedValue=seed, nLoop=2,
                  tol=10)
    return cs.rec_spec, list(cs.rec_scale)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('--library', required=True)
    p.add_argument('--target', required=True)
    p.add_argument('--make-target', action='store_true')
    p.add_argument('--t-star', type=float, default=1.0, help='--make-target: the conditioning period [s]')
    p.add_argument('--epsilon', type=float, default=1.0, help='--make-target: epsilon at T*')
    p.add_argument('--kind', default='component')
    p.add_argument('-n', type=int, nargs='+', default=[10, 20])
    p.add_argument('--seeds', type=int, nargs='+', default=[1, 2, 3])
    p.add_argument('--scale-min', type=float, default=0.25)
    p.add_argument('--scale-max', type=float, default=4.0)
    p.add_argument('--ezgm')
    args = p.parse_args()
    if args.make_target:
        make_target(args.library, args.kind, args.target, t_star=args.t_star, eps=args.epsilon)
    ezgm = load_ezgm(args.ezgm) if args.ezgm else None
    _, mean, sigma = read_target(args.target)
    print('| tool | N | seed | max median error [%] | max sigma error [%] | within 5 % / 10 % | SSE (Baker & Lee) | scale range |')
    print('| --- | --- | --- | --- | --- | --- | --- | --- |')
    for n in args.n:
        for seed in args.seeds:
            runs = [(name, run_pcrf(args, n, seed, extra)) for name, extra in PCRF_WAYS]
            if ezgm:
                import contextlib, io
                with contextlib.redirect_stdout(io.StringIO()):
                    runs.append(('EzGM', run_ezgm(ezgm, args, n, seed)))
            for tool, (ln_sa, scales) in runs:
                m, s, sse = errors(np.asarray(ln_sa), mean, sigma)
                meets = 'yes' if m <= 5.0 and s <= 10.0 else 'no'
                print('| %s | %d | %d | %.1f | %.1f | %s | %.4f | %.2f–%.2f |' % (tool, n, seed, m, s, meets, sse, min(scales),
                                                                      max(scales)), flush=True)


if __name__ == '__main__':
    main()
