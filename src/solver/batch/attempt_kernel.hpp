/// \file attempt_kernel.hpp
/// \brief One Dormand–Prince 5(4) step attempt for every lane of a batch, written once over
/// a pack type: `double` (one lane, the C library's sin and cos) or an xsimd batch of
/// doubles (one register of lanes). Included by one translation unit per instruction set,
/// each compiled with that set's flags and with -ffp-contract=off: every lane does the
/// arithmetic of DormandPrinceIntegrator::try_step in the same order, rounding for
/// rounding; only a vectorised sin/cos may differ from the C library's (in the last bit).
/// Private to the solver.
#pragma once

#include <cmath>
#include <cstddef>

#ifdef PCRF_HAVE_XSIMD
#include <xsimd/xsimd.hpp>
#endif

#include "dopri5_tableau.hpp"
#include "lane_arrays.hpp"

namespace pcrf::detail::batch {

/// The pack operations the kernel needs, for the one-lane pack `double`.
struct ScalarPack {
  using P = double;
  using M = bool;
  static constexpr int kLanes = 1;
  static P load(const double* p) { return *p; }
  static void store(double* p, P v) { *p = v; }
  static P select(M m, P a, P b) { return m ? a : b; }
  static M finite(P v) { return std::isfinite(v); }
  static bool all(M m) { return m; }
  static bool lane(M m, int) { return m; }
  static P abs(P v) { return std::abs(v); }
  static P sqrt(P v) { return std::sqrt(v); }
  static void sincos(P x, P& s, P& c) { s = std::sin(x), c = std::cos(x); }
};

#ifdef PCRF_HAVE_XSIMD
/// The same over an xsimd batch; `Trig` gives sin and cos of a whole register.
template <class Batch, class Trig>
struct VectorPack {
  using P = Batch;
  using M = typename Batch::batch_bool_type;
  static constexpr int kLanes = static_cast<int>(Batch::size);
  static P load(const double* p) { return P::load_unaligned(p); }
  static void store(double* p, const P& v) { v.store_unaligned(p); }
  static P select(const M& m, const P& a, const P& b) { return xsimd::select(m, a, b); }
  static M finite(const P& v) { return xsimd::isfinite(v); }
  static bool all(const M& m) { return xsimd::all(m); }
  static bool lane(const M& m, int j) {
    bool b[kLanes];
    m.store_unaligned(b);
    return b[j];
  }
  static P abs(const P& v) { return xsimd::abs(v); }
  static P sqrt(const P& v) { return xsimd::sqrt(v); }
  static void sincos(const P& x, P& s, P& c) { Trig::sincos(x, s, c); }
};

/// sin and cos lane by lane from the C library: the one-case solver's values, bit for bit.
template <class Batch>
struct LibmTrig {
  static void sincos(const Batch& x, Batch& s, Batch& c) {
    constexpr std::size_t n = Batch::size;
    double v[n], sv[n], cv[n];
    x.store_unaligned(v);
    for (std::size_t j = 0; j < n; ++j) sv[j] = std::sin(v[j]), cv[j] = std::cos(v[j]);
    s = Batch::load_unaligned(sv), c = Batch::load_unaligned(cv);
  }
};

#endif  // PCRF_HAVE_XSIMD

/// Lanes o … o + kLanes − 1 of the batch.
template <class Pack>
class Attempt {
  using P = typename Pack::P;
  using M = typename Pack::M;
  static constexpr int N = Pack::kLanes;

 public:
  Attempt(LaneArrays& lanes, LaneCallbacks& callbacks, bool block, int offset)
      : L_(lanes), cb_(callbacks), block_(block), o_(offset) {}

  void run() {
    const P t = ld(L_.t0), h = ld(L_.h);
    const P y0 = ld(L_.theta0), w0 = ld(L_.omega0);  // θ₁, θ̇₁
    const P k1y = ld(L_.k1_theta), k1w = ld(L_.k1_omega);
    M alive(true);
    P evals(0.0);
    // Each stage: the state s, its derivative k = (s_ω, θ̈₁(t + c h, s)).
    auto stage = [&](double c, const P& sy, const P& sw, P& ky, P& kw) {
      ky = sw;
      M good;
      kw = acceleration(t + c * h, sy, sw, good);
      evals = evals + Pack::select(alive, P(1.0), P(0.0));
      alive = alive & good;
    };
    P k2y, k2w, k3y, k3w, k4y, k4w, k5y, k5w, k6y, k6w, k7y, k7w;
    stage(c2, y0 + h * a21 * k1y, w0 + h * a21 * k1w, k2y, k2w);
    stage(c3, y0 + h * (a31 * k1y + a32 * k2y), w0 + h * (a31 * k1w + a32 * k2w), k3y, k3w);
    stage(c4, y0 + h * (a41 * k1y + a42 * k2y + a43 * k3y), w0 + h * (a41 * k1w + a42 * k2w + a43 * k3w), k4y, k4w);
    stage(c5, y0 + h * (a51 * k1y + a52 * k2y + a53 * k3y + a54 * k4y),
          w0 + h * (a51 * k1w + a52 * k2w + a53 * k3w + a54 * k4w), k5y, k5w);
    stage(1.0, y0 + h * (a61 * k1y + a62 * k2y + a63 * k3y + a64 * k4y + a65 * k5y),
          w0 + h * (a61 * k1w + a62 * k2w + a63 * k3w + a64 * k4w + a65 * k5w), k6y, k6w);
    const P y1 = y0 + h * (a71 * k1y + a73 * k3y + a74 * k4y + a75 * k5y + a76 * k6y);
    const P w1 = w0 + h * (a71 * k1w + a73 * k3w + a74 * k4w + a75 * k5w + a76 * k6w);
    stage(1.0, y1, w1, k7y, k7w);
    // The error norm: weighted RMS of the 5th-order minus the embedded 4th-order solution.
    const P ey = h * (e1 * k1y + e3 * k3y + e4 * k4y + e5 * k5y + e6 * k6y + e7 * k7y);
    const P ew = h * (e1 * k1w + e3 * k3w + e4 * k4w + e5 * k5w + e6 * k6w + e7 * k7w);
    const P sy = L_.atol_theta + L_.rtol * larger(Pack::abs(y0), Pack::abs(y1));
    const P sw = L_.atol_omega + L_.rtol * larger(Pack::abs(w0), Pack::abs(w1));
    P sum(0.0);
    sum = sum + (ey / sy) * (ey / sy);
    sum = sum + (ew / sw) * (ew / sw);
    const P err = Pack::sqrt(sum / 2.0);
    const M ok = alive & Pack::finite(err) & Pack::finite(y1) & Pack::finite(w1);
    st(L_.theta1, y1), st(L_.omega1, w1), st(L_.k7_theta, k7y), st(L_.k7_omega, k7w);
    st(L_.err, err), st(L_.ok, Pack::select(ok, P(1.0), P(0.0))), st(L_.evals, evals);
    // The continuous extension (DOPRI5's CONTD5), as DormandPrinceIntegrator::step.
    continuous(0, y0, y1, k1y, k3y, k4y, k5y, k6y, k7y, h);
    continuous(1, w0, w1, k1w, k3w, k4w, k5w, k6w, k7w, h);
  }

 private:
  P ld(const std::vector<double>& v) const { return Pack::load(v.data() + o_); }
  void st(std::vector<double>& v, const P& x) const { Pack::store(v.data() + o_, x); }
  /// std::max(a, b): b when a < b, else a.
  static P larger(const P& a, const P& b) { return Pack::select(a < b, b, a); }

  void continuous(int i, const P& y0, const P& y1, const P& k1, const P& k3, const P& k4, const P& k5, const P& k6,
                  const P& k7, const P& h) {
    const P ydiff = y1 - y0, bspl = h * k1 - ydiff;
    st(L_.cont[0][i], y0);
    st(L_.cont[1][i], ydiff);
    st(L_.cont[2][i], bspl);
    st(L_.cont[3][i], ydiff - h * k7 - bspl);
    st(L_.cont[4][i], h * (d1 * k1 + d3 * k3 + d4 * k4 + d5 * k5 + d6 * k6 + d7 * k7));
  }

  /// The ground acceleration at the stage times: the lanes' record intervals, or lane by
  /// lane through the callbacks when a time falls outside its lane's interval.
  void ground(const P& ts, P& ah, P& av) const {
    const P lo = ld(L_.lo), hi = ld(L_.hi);
    if (Pack::all((ts >= lo) & (ts < hi))) {
      const P frac = (ts - lo) * ld(L_.inv_dt);
      ah = ld(L_.h0) + frac * ld(L_.dh);
      av = ld(L_.v0) + frac * ld(L_.dv);
      return;
    }
    double t[N], a[N], b[N];
    Pack::store(t, ts);
    for (int j = 0; j < N; ++j) cb_.ground(o_ + j, t[j], a[j], b[j]);
    ah = Pack::load(a), av = Pack::load(b);
  }

  /// θ̈₁ at (ts, θ₁, θ̇₁); `good` false where the right-hand side fails.
  P acceleration(const P& ts, const P& th, const P& om, M& good) {
    if (!block_) return by_lane(ts, th, om, good);
    P ah, av;
    ground(ts, ah, av);
    // RigidRocker::acceleration: φ = θ₁ on side −1, −θ₁ on side +1, σ = ∓1 with the side;
    // θ̈₁ = ((1 + 2γ) R / I) (σ sin(α + φ) (g + ü_v) − cos(α + φ) ü_h).
    const P side = ld(L_.side);
    const M left = side < P(0.0);
    const P phi = Pack::select(left, th, -th);
    P sn, cs;
    Pack::sincos(ld(L_.alpha) + phi, sn, cs);
    const P sigma = Pack::select(left, P(1.0), P(-1.0));
    const P acc = ld(L_.moment_over_inertia) * (sigma * sn * (ld(L_.gravity) + av) - cs * ah);
    good = Pack::finite(acc);
    return acc;
  }

  P by_lane(const P& ts, const P& th, const P& om, M& good) {
    double t[N], y[N], w[N], a[N], g[N];
    Pack::store(t, ts), Pack::store(y, th), Pack::store(w, om);
    for (int j = 0; j < N; ++j) g[j] = cb_.acceleration(o_ + j, t[j], y[j], w[j], a[j]) ? 1.0 : 0.0;
    const P gp = Pack::load(g);
    good = gp > P(0.5);
    return Pack::load(a);
  }

  LaneArrays& L_;
  LaneCallbacks& cb_;
  bool block_;
  int o_;
};

/// Every register of the batch.
template <class Pack>
void attempt_all(LaneArrays& lanes, LaneCallbacks& callbacks, bool block) {
  for (int o = 0; o < lanes.capacity(); o += Pack::kLanes) Attempt<Pack>(lanes, callbacks, block, o).run();
}

}  // namespace pcrf::detail::batch
