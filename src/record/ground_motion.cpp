/// \file ground_motion.cpp
/// \brief GroundMotion: validation, exact-at-sample linear interpolation, PGA and scaling.
///
/// accel_m_s2() sits in the innermost loop of the equation-of-motion right-hand side,
/// so it allocates nothing and uses only the comparisons needed to stay in bounds.

#include "pcrf/record/ground_motion.hpp"

#include "pcrf/user_error.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "pcrf/number_text.hpp"

namespace pcrf {

namespace {

/// Message prefix naming the record, so an error from deep inside a study says which one.
std::string record_label(const std::string& name) {
  return "ground motion '" + name + "': ";
}

void validate(const std::string& name, double dt_s, const std::vector<double>& accel_m_s2) {
  if (!(dt_s > 0.0) || !std::isfinite(dt_s)) {
    throw UserError(record_label(name) + "dt_s must be positive and finite, got " +
                                number_text(dt_s));
  }
  if (accel_m_s2.empty()) {
    throw UserError(record_label(name) + "no samples");
  }
  for (std::size_t i = 0; i < accel_m_s2.size(); ++i) {
    if (!std::isfinite(accel_m_s2[i])) {
      throw UserError(record_label(name) + "sample " + std::to_string(i) +
                                  " is not finite");
    }
  }
}

}  // namespace

GroundMotion::GroundMotion(std::string name, double dt_s, std::vector<double> accel_m_s2)
    : name_(std::move(name)), dt_s_(dt_s), inv_dt_(0.0), accel_m_s2_(std::move(accel_m_s2)) {
  validate(name_, dt_s_, accel_m_s2_);
  inv_dt_ = 1.0 / dt_s_;
  const auto [lo, hi] = std::minmax_element(accel_m_s2_.begin(), accel_m_s2_.end());
  min_m_s2_ = *lo;
  max_m_s2_ = *hi;
}

double GroundMotion::accel_m_s2(double t_s) const {
  // Negative times see no ground motion; a NaN time is passed on rather than hidden.
  if (!(t_s >= 0.0)) return t_s < 0.0 ? 0.0 : t_s;
  const std::size_t last = accel_m_s2_.size() - 1;
  const double t_end_s = static_cast<double>(last) * dt_s_;  // same product as duration_s()
  if (t_s >= t_end_s) return t_s == t_end_s ? accel_m_s2_[last] : 0.0;

  // Here 0 ≤ t < t_end, so last ≥ 1. The product k·dt is monotone in k, so the interval
  // satisfies k·dt ≤ t < (k+1)·dt with k ≤ last − 1 (a guess of `last` is always pulled
  // back by the first correction in interval_of).
  const std::size_t k = interval_of(t_s);

  // frac is exactly 0 at t = k·dt, so the sample is returned unchanged there.
  const double frac = (t_s - static_cast<double>(k) * dt_s_) * inv_dt_;
  const double a0 = accel_m_s2_[k];
  return a0 + frac * (accel_m_s2_[k + 1] - a0);
}

GroundMotion GroundMotion::scaled(double factor) const {
  if (!std::isfinite(factor)) {
    throw UserError(record_label(name_) + "scale factor must be finite, got " +
                                number_text(factor));
  }
  std::vector<double> out_m_s2(accel_m_s2_);
  for (double& a : out_m_s2) a *= factor;
  return GroundMotion(name_, dt_s_, std::move(out_m_s2));
}

}  // namespace pcrf

namespace pcrf {

bool same_sample_interval(double a_s, double b_s) {
  return std::abs(a_s - b_s) <= kSameIntervalTolerance * std::max(std::abs(a_s), std::abs(b_s));
}

}  // namespace pcrf
