/// \file attempt_kernel.hpp
/// \brief One Dormand–Prince 5(4) step attempt for every lane of a batch, over a pack type:
/// `double` (one lane) or an xsimd batch of doubles (one register of lanes). Included by one
/// translation unit per instruction set, each compiled with that set's flags and with
/// -ffp-contract=off. The attempt is dopri5_attempt.hpp's, the rigid rockers' right-hand
/// side rigid_rocker.hpp's and its sin/cos rocker_sincos.hpp's: the one-case solver's
/// arithmetic rounding for rounding, a register at a time. Only BatchOptions::trig "sleef"
/// or "xsimd" trades the sin/cos for another vector one. Private to the solver.
#pragma once

#include <cmath>
#include <cstddef>
#include <type_traits>

#ifdef PCRF_HAVE_XSIMD
#include <xsimd/xsimd.hpp>
#endif
#ifdef PCRF_HAVE_SLEEF
#include <sleef.h>
#endif

#include "../dopri5/dopri5_attempt.hpp"
#include "lane_arrays.hpp"
#include "pcrf/model/rigid_rocker.hpp"

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
  static bool none(M m) { return !m; }
  static bool lane(M m, int) { return m; }
  static P abs(P v) { return std::abs(v); }
  static P sqrt(P v) { return std::sqrt(v); }
  static void sincos(P x, P& s, P& c) { rocker_sincos<ScalarPack>(x, s, c); }
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
  static bool none(const M& m) { return xsimd::none(m); }
  static bool lane(const M& m, int j) {
    bool b[kLanes];
    m.store_unaligned(b);
    return b[j];
  }
  static P abs(const P& v) { return xsimd::abs(v); }
  static P sqrt(const P& v) { return xsimd::sqrt(v); }
  static void sincos(const P& x, P& s, P& c) { Trig::sincos(x, s, c); }
};

/// rocker_sincos over a whole register: the one-case solver's values, bit for bit.
template <class Batch>
struct RockerTrig {
  template <class M>
  static Batch select(const M& m, const Batch& a, const Batch& b) { return xsimd::select(m, a, b); }
  static void sincos(const Batch& x, Batch& s, Batch& c) { rocker_sincos<RockerTrig>(x, s, c); }
};

/// rocker_sincos lane by lane (what the vector one gains, for benchmarks).
template <class Batch>
struct LaneByLaneTrig {
  static void sincos(const Batch& x, Batch& s, Batch& c) {
    constexpr std::size_t n = Batch::size;
    double v[n], sv[n], cv[n];
    x.store_unaligned(v);
    for (std::size_t j = 0; j < n; ++j) ScalarPack::sincos(v[j], sv[j], cv[j]);
    s = Batch::load_unaligned(sv), c = Batch::load_unaligned(cv);
  }
};

/// sin and cos of xsimd.
template <class Batch>
struct XsimdTrig {
  static void sincos(const Batch& x, Batch& s, Batch& c) {
    auto sc = xsimd::sincos(x);
    s = sc.first, c = sc.second;
  }
};

/// sin and cos of SLEEF's function F for one register (its result's x and y).
template <class Batch, auto F>
struct SleefTrig {
  static void sincos(const Batch& x, Batch& s, Batch& c) {
    const auto sc = F(x);
    s = Batch(sc.x), c = Batch(sc.y);
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
    const P y0[2] = {ld(L_.theta0), ld(L_.omega0)};  // θ₁, θ̇₁
    const P k1[2] = {ld(L_.k1_theta), ld(L_.k1_omega)};
    const P atol[2] = {P(L_.atol_theta), P(L_.atol_omega)};
    P evals(0.0);
    // The derivative at a stage: (s_ω, θ̈₁(ts, s)).
    auto f = [&](const P& ts, const P* s, P* k, M& alive) {
      k[0] = s[1];
      M good;
      k[1] = acceleration(ts, s[0], s[1], good);
      evals = evals + Pack::select(alive, P(1.0), P(0.0));
      alive = alive & good;
    };
    Dopri5Stages<P> out{};
    const M ok = dopri5_attempt<Pack>(t, h, y0, k1, atol, P(L_.rtol), f, out);
    st(L_.theta1, out.y1[0]), st(L_.omega1, out.y1[1]), st(L_.k7_theta, out.k7[0]), st(L_.k7_omega, out.k7[1]);
    st(L_.err, out.err), st(L_.ok, Pack::select(ok, P(1.0), P(0.0))), st(L_.evals, evals);
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 2; ++i) st(L_.cont[j][i], out.cont[j][i]);
  }

 private:
  P ld(const std::vector<double>& v) const { return Pack::load(v.data() + o_); }
  void st(std::vector<double>& v, const P& x) const { Pack::store(v.data() + o_, x); }
  /// The ground acceleration at the stage times: each lane's record interval or the one after
  /// it (ExcitationCursor::at's arithmetic: the value at t depends on t alone), else lane by
  /// lane through the callbacks.
  void ground(const P& ts, P& ah, P& av) const {
    const M here = (ts >= ld(L_.lo)) & (ts < ld(L_.hi));
    if (Pack::all(here)) {
      interpolate(ts, ld(L_.lo), ld(L_.h0), ld(L_.dh), ld(L_.v0), ld(L_.dv), ah, av);
      return;
    }
    const M next = (ts >= ld(L_.nlo)) & (ts < ld(L_.nhi));
    if (Pack::all(next)) {  // the step's last stages, on its closing sample
      interpolate(ts, ld(L_.nlo), ld(L_.nh0), ld(L_.ndh), ld(L_.nv0), ld(L_.ndv), ah, av);
      return;
    }
    P h1, v1, h2, v2;
    interpolate(ts, ld(L_.lo), ld(L_.h0), ld(L_.dh), ld(L_.v0), ld(L_.dv), h1, v1);
    interpolate(ts, ld(L_.nlo), ld(L_.nh0), ld(L_.ndh), ld(L_.nv0), ld(L_.ndv), h2, v2);
    ah = Pack::select(here, h1, h2), av = Pack::select(here, v1, v2);
    const M known = here | next;
    if (Pack::all(known)) return;
    double t[N], a[N], b[N];
    Pack::store(t, ts), Pack::store(a, ah), Pack::store(b, av);
    for (int j = 0; j < N; ++j)
      if (!Pack::lane(known, j)) cb_.ground(o_ + j, t[j], a[j], b[j]);
    ah = Pack::load(a), av = Pack::load(b);
  }
  void interpolate(const P& ts, const P& lo, const P& h0, const P& dh, const P& v0, const P& dv, P& ah, P& av) const {
    const P frac = (ts - lo) * ld(L_.inv_dt);
    ah = h0 + frac * dh;
    av = v0 + frac * dv;
  }

  /// θ̈₁ at (ts, θ₁, θ̇₁); `good` false where the right-hand side fails.
  P acceleration(const P& ts, const P& th, const P& om, M& good) {
    if (!block_) return by_lane(ts, th, om, good);
    P ah, av;
    ground(ts, ah, av);
    const P acc = rigid_rocker_acceleration<Pack>(ld(L_.moment_over_inertia), ld(L_.alpha), ld(L_.gravity), th,
                                                  ld(L_.side) < P(0.0), ah, av);
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

/// The exact sin/cos of pack type Pack over n arguments (tests): whole registers, then the
/// rest one by one.
template <class Pack>
void sincos_all(const double* x_rad, double* sin_x, double* cos_x, std::size_t n) {
  constexpr auto w = static_cast<std::size_t>(Pack::kLanes);
  std::size_t i = 0;
  for (; i + w <= n; i += w) {
    typename Pack::P s, c;
    Pack::sincos(Pack::load(x_rad + i), s, c);
    Pack::store(sin_x + i, s), Pack::store(cos_x + i, c);
  }
  for (; i < n; ++i) ScalarPack::sincos(x_rad[i], sin_x[i], cos_x[i]);
}

#ifdef PCRF_HAVE_XSIMD
/// The kernels of the instruction set Arch (an xsimd architecture); `Sleef` the SLEEF
/// sin/cos of its registers (a SleefTrig), or void where SLEEF is not built or lacks one.
template <class Arch, class Sleef = void>
KernelSet vector_kernels(const char* name) {
  using Batch = xsimd::batch<double, Arch>;
  KernelSet k;
  k.name = name;
  k.register_lanes = static_cast<int>(Batch::size);
  k.exact_trig = &attempt_all<VectorPack<Batch, RockerTrig<Batch>>>;
  k.scalar_trig = &attempt_all<VectorPack<Batch, LaneByLaneTrig<Batch>>>;
  k.xsimd_trig = &attempt_all<VectorPack<Batch, XsimdTrig<Batch>>>;
  if constexpr (!std::is_void_v<Sleef>) k.sleef_trig = &attempt_all<VectorPack<Batch, Sleef>>;
  k.sincos = &sincos_all<VectorPack<Batch, RockerTrig<Batch>>>;
  return k;
}
#endif

}  // namespace pcrf::detail::batch
