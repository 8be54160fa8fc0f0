/// \file dopri5_attempt.hpp
/// \brief One step attempt of Dormand–Prince 5(4): its stages, the embedded error norm and
/// the coefficients of the continuous extension, written once over a number type — `double`
/// for DormandPrinceIntegrator (one case), a SIMD pack whose lanes are cases for the batch
/// kernels (src/solver/lanes/attempt_kernel.hpp). Both do the same arithmetic in the same
/// order, rounding for rounding. Private to the solver.
#pragma once

#include "dopri5_tableau.hpp"
#include "pcrf/host_device.hpp"

namespace pcrf::detail {

/// What an attempt computes, for a number type P.
template <class P>
struct Dopri5Stages {
  P y1[2];       ///< the 5th-order solution at t + h
  P k7[2];       ///< f(t + h, y1): the next step's first stage (first same as last)
  P err;         ///< the error estimate in the weighted RMS norm (accept when ≤ 1)
  P cont[5][2];  ///< the continuous extension's coefficients (see dense_component)
};

/// One attempt from (t, y0) with k1 = f(t, y0) and step h. `f(ts, s, k, alive)` sets
/// k = f(ts, s) and clears `alive` where that fails (it need not evaluate where `alive` is
/// already clear). Weights atol_i + rtol·max(|y0_i|, |y1_i|). Returns the mask of lanes
/// whose every stage succeeded and whose error and solution are finite; when no lane is
/// left alive after a stage, at once (`out` then partly unset).
///
/// `Ops` gives the number type's operations: P (the number), M (its mask), select(m, a, b),
/// finite(p), abs(p), sqrt(p), none(m). Always inlined: it is the body of the integrator's
/// inner loop, and a call would keep the stages' numbers in memory.
template <class Ops, class F>
[[gnu::always_inline]] PCRF_HD inline typename Ops::M dopri5_attempt(const typename Ops::P& t, const typename Ops::P& h, const typename Ops::P (&y0)[2],
                               const typename Ops::P (&k1)[2], const typename Ops::P (&atol)[2],
                               const typename Ops::P& rtol, F&& f, Dopri5Stages<typename Ops::P>& out) {
  using P = typename Ops::P;
  typename Ops::M alive(true);
  P s[2], k2[2], k3[2], k4[2], k5[2], k6[2];
  for (int i = 0; i < 2; ++i) s[i] = y0[i] + h * a21 * k1[i];
  f(t + c2 * h, s, k2, alive);
  if (Ops::none(alive)) return alive;
  for (int i = 0; i < 2; ++i) s[i] = y0[i] + h * (a31 * k1[i] + a32 * k2[i]);
  f(t + c3 * h, s, k3, alive);
  if (Ops::none(alive)) return alive;
  for (int i = 0; i < 2; ++i) s[i] = y0[i] + h * (a41 * k1[i] + a42 * k2[i] + a43 * k3[i]);
  f(t + c4 * h, s, k4, alive);
  if (Ops::none(alive)) return alive;
  for (int i = 0; i < 2; ++i) s[i] = y0[i] + h * (a51 * k1[i] + a52 * k2[i] + a53 * k3[i] + a54 * k4[i]);
  f(t + c5 * h, s, k5, alive);
  if (Ops::none(alive)) return alive;
  for (int i = 0; i < 2; ++i)
    s[i] = y0[i] + h * (a61 * k1[i] + a62 * k2[i] + a63 * k3[i] + a64 * k4[i] + a65 * k5[i]);
  f(t + 1.0 * h, s, k6, alive);
  if (Ops::none(alive)) return alive;
  for (int i = 0; i < 2; ++i)
    out.y1[i] = y0[i] + h * (a71 * k1[i] + a73 * k3[i] + a74 * k4[i] + a75 * k5[i] + a76 * k6[i]);
  f(t + 1.0 * h, out.y1, out.k7, alive);
  if (Ops::none(alive)) return alive;
  const P* k7 = out.k7;
  P sum(0.0);
  for (int i = 0; i < 2; ++i) {
    const P e = h * (e1 * k1[i] + e3 * k3[i] + e4 * k4[i] + e5 * k5[i] + e6 * k6[i] + e7 * k7[i]);
    const P a = Ops::abs(y0[i]), b = Ops::abs(out.y1[i]);
    const P sk = atol[i] + rtol * Ops::select(a < b, b, a);  // std::max(a, b)
    sum = sum + (e / sk) * (e / sk);
  }
  out.err = Ops::sqrt(sum / 2.0);
  // Shampine's continuous extension (DOPRI5's CONTD5).
  for (int i = 0; i < 2; ++i) {
    const P ydiff = out.y1[i] - y0[i], bspl = h * k1[i] - ydiff;
    out.cont[0][i] = y0[i];
    out.cont[1][i] = ydiff;
    out.cont[2][i] = bspl;
    out.cont[3][i] = ydiff - h * k7[i] - bspl;
    out.cont[4][i] = h * (d1 * k1[i] + d3 * k3[i] + d4 * k4[i] + d5 * k5[i] + d6 * k6[i] + d7 * k7[i]);
  }
  return alive & Ops::finite(out.err) & Ops::finite(out.y1[0]) & Ops::finite(out.y1[1]);
}

}  // namespace pcrf::detail
