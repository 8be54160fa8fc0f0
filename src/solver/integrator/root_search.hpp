/// \file root_search.hpp
/// \brief The root search of the event-locating integrators (dopri5's Runge–Kutta steps and
/// the Taylor steps): which root function crosses first within a step, located on the step's
/// dense output. Private to the solver.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>

#include "pcrf/host_device.hpp"

namespace pcrf::detail {

/// Time tolerance of a located root, as SUNDIALS' (100 ulp of the time and step).
PCRF_HD inline double root_tolerance(double t, double h) {
  return 100.0 * std::numeric_limits<double>::epsilon() * (std::abs(t) + std::abs(h));
}

/// The step δ to the root of the local model v + slope·δ + ½·curvature·δ² (the root nearest
/// δ = 0, in the form that cancels nothing); Newton's −v/slope when the curvature is 0 or the
/// model has no real root. With the curvature, the step of Euler and Chebyshev: cubic
/// convergence, and near a double root (a flight starting where θ̈ ≈ 0, the ground at the
/// uplift threshold) the model's root where Newton's steps only halve the distance.
PCRF_HD inline double model_step(double v, double slope, double curvature) {
  if (curvature != 0.0) {
    const double disc = slope * slope - 2.0 * v * curvature;
    if (disc >= 0.0) {
      const double q = slope + std::copysign(std::sqrt(disc), slope);
      if (q != 0.0) return -2.0 * v / q;
    }
  }
  return -v / slope;  // ±inf or NaN for a zero slope: bisection in the caller
}

/// Narrows [lo, hi] (values glo, ghi of opposite signs) around the root of a function whose
/// value, slope and curvature at t `value_slope(t, v, slope, curvature)` gives (curvature 0
/// where unknown), to ttol: steps of the local model (model_step; Newton's without the
/// curvature) kept inside the bracket, bisection where one would leave it; once its steps
/// fall below the tolerance, one probe just across the root closes the bracket. Two to four
/// probes where the Illinois method takes eight. The first probe is at `t_first` when it is
/// inside the bracket, else at the secant's root. The bracket's far end `hi` is the root
/// reported (as SUNDIALS does).
///
/// With the curvature the model's root is good to the cube of the step: each model step aims
/// a quarter of the tolerance past it (towards hi, the crossed side), and a probe that lands
/// past the root with a step back below half the tolerance ends the search (hi within ttol of
/// the root; lo not narrowed): one probe fewer than closing the bracket from both sides.
template <class ValueSlope>
PCRF_HD void newton_in_bracket(ValueSlope&& value_slope, double& lo, double& glo, double& hi, double& ghi, double ttol,
                       double t_first = std::numeric_limits<double>::quiet_NaN()) {
  double t = t_first > lo && t_first < hi ? t_first : hi - ghi * (hi - lo) / (ghi - glo);
  for (int it = 0; it < 100 && hi - lo > ttol && ghi != 0.0; ++it) {
    t = std::clamp(t, lo + 0.25 * ttol, hi - 0.25 * ttol);
    double v = 0.0, slope = 0.0, curvature = 0.0;
    value_slope(t, v, slope, curvature);
    if (v == 0.0) {
      hi = t, ghi = 0.0;
      break;
    }
    const bool below = (v > 0.0) == (glo > 0.0);
    if (below) {
      lo = t, glo = v;
    } else {
      hi = t, ghi = v;
    }
    const double newton = t + model_step(v, slope, curvature);
    if (std::abs(newton - t) < 0.5 * ttol) {
      if (!below && curvature != 0.0) break;
      t = below ? t + 0.5 * ttol : t - 0.5 * ttol;
    } else if (newton > lo && newton < hi) {
      t = curvature != 0.0 ? newton + 0.25 * ttol : newton;  // past the root: hi's side
    } else {
      t = 0.5 * (lo + hi);
    }
  }
}

/// Narrows the bracket [lo, hi] of root function i (values glo, ghi) to ttol by the Illinois
/// method: regula falsi that halves the stale end's value when an end repeats. For a root that
/// is no state component (newton_in_bracket takes those). `roots_at(t, g)` sets the kMax (or
/// fewer) functions at t; false when the problem failed there, which this returns.
template <std::size_t kMax, class RootsAt>
PCRF_HD bool illinois_in_bracket(RootsAt&& roots_at, int i, double& lo, double& glo, double& hi, double& ghi,
                                 double ttol) {
  double g[kMax];  // NOLINT: filled by roots_at before use
  int last = 0;
  for (int it = 0; it < 200 && hi - lo > ttol && ghi != 0.0; ++it) {
    double t = hi - ghi * (hi - lo) / (ghi - glo);
    const double margin = 0.5 * ttol;
    t = std::clamp(t, lo + margin, hi - margin);
    if (!roots_at(t, g)) return false;
    const double gt = g[i];
    if (gt == 0.0) {
      hi = t;
      ghi = 0.0;
    } else if ((gt > 0.0) == (glo > 0.0)) {
      lo = t, glo = gt;
      if (last == -1) ghi *= 0.5;
      last = -1;
    } else {
      hi = t, ghi = gt;
      if (last == 1) glo *= 0.5;
      last = 1;
    }
  }
  return true;
}

/// Whether root function i may cross, in its direction, from g_a to g_b.
PCRF_HD inline bool crosses(double g_a, double g_b, int dir) {
  return g_a != 0.0 && g_a * g_b <= 0.0 && !(dir != 0 && dir * g_a > 0.0);
}

/// The earliest crossing in (a, b] of the n root functions (values g_a at a, g_b at b,
/// directions `dirs`) within one step. One crossing is located first — the `preferred`
/// function's if it crosses (θ̇: in a step that holds a peak and the next impact, the peak
/// comes first, by Rolle, and the impact then needs no search in this step) — and the others
/// are checked at it: a function whose sign there differs from its sign at a crossed before
/// it (perhaps crossing back before b: the stop angle exceeded at a peak within the step) and
/// is located, and the check is made again at the new earliest.
///  - roots_at(t, g): the functions at t within the step; false when the problem failed;
///  - locate(i, lo, glo, hi, ghi, ttol): narrows the bracket around function i's root.
/// Returns false when nothing crosses; else the root's time, the functions found there (within
/// ttol of it) and their values at it (zeros when the problem failed there).
template <std::size_t kMax, class RootsAt, class Locate>
PCRF_HD bool earliest_crossing(int n, const std::array<int, kMax>& dirs, int preferred, double a, const double* g_a, double b,
                       const double* g_b, double ttol, RootsAt&& roots_at, Locate&& locate, double& root_time,
                       std::array<int, kMax>& found, std::array<double, kMax>& g_root) {
  int first = -1;
  for (int i = 0; i < n; ++i)
    if (crosses(g_a[i], g_b[i], dirs[static_cast<std::size_t>(i)]) && (first < 0 || i == preferred)) first = i;
  if (first < 0) return false;
  std::array<double, kMax> when;  // NOLINT: set below for every function
  for (double& w : when) w = std::numeric_limits<double>::infinity();  // no fill(): not constexpr before C++20 (device code)
  double earliest = 0.0;
  {
    double lo = a, glo = g_a[first], hi = b, ghi = g_b[first];
    locate(first, lo, glo, hi, ghi, ttol);
    when[static_cast<std::size_t>(first)] = earliest = hi;
  }
  std::array<double, kMax> g;  // NOLINT: filled by roots_at before use
  bool current = false;        // g holds the functions at `earliest`
  for (int pass = 0; pass < n; ++pass) {
    if (!roots_at(earliest, g.data())) break;
    current = true;
    bool moved = false;
    for (int i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const double ga = g_a[i], gm = g[k];
      if (when[k] <= earliest || !crosses(ga, gm, dirs[k])) continue;
      if (gm == 0.0) {  // a root at the earliest itself
        when[k] = earliest;
        continue;
      }
      double lo = a, glo = ga, hi = earliest, ghi = gm;
      locate(i, lo, glo, hi, ghi, ttol);
      when[k] = hi;
      if (hi < earliest) earliest = hi, moved = true, current = false;
    }
    if (!moved) break;
  }
  // The functions at the root, for the search that resumes there.
  if (current) {
    g_root = g;
  } else if (!roots_at(earliest, g_root.data())) {
    for (double& v : g_root) v = 0.0;
  }
  for (int& f : found) f = 0;
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (when[k] <= earliest + ttol) found[k] = 1;
  }
  root_time = earliest;
  return true;
}

}  // namespace pcrf::detail
