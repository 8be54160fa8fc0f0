/// \file ground_motion.hpp
/// \brief A uniformly sampled horizontal ground acceleration record.
///
/// Sample i sits at t = i·dt (first sample at t = 0). Between samples the
/// acceleration is interpolated linearly; before t = 0 and after the last
/// sample it is zero (the free-vibration tail of a case sees no ground motion).
/// Values are stored in m/s² whatever the units of the file they came from.
#pragma once

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include "pcrf/units.hpp"

namespace pcrf {

class GroundMotion {
 public:
  /// \param name     label used in results and error messages
  /// \param dt_s     sample interval [s], > 0
  /// \param accel_m_s2 samples [m/s²], at least one; all finite
  /// \throws UserError when dt ≤ 0, no samples, or a non-finite sample
  GroundMotion(std::string name, double dt_s, std::vector<double> accel_m_s2);

  const std::string& name() const { return name_; }
  double dt_s() const { return dt_s_; }
  std::size_t size() const { return accel_m_s2_.size(); }
  /// Time of the last sample, (n − 1)·dt [s].
  double duration_s() const { return static_cast<double>(size() - 1) * dt_s_; }
  const std::vector<double>& samples_m_s2() const { return accel_m_s2_; }

  /// Ground acceleration at time t [m/s²]: linear interpolation, zero outside the record.
  /// At t == static_cast<double>(i) * dt_s() it returns sample i exactly (bit for bit), for
  /// every i including the last; t < 0 or t > duration_s() gives 0; a NaN t gives NaN.
  /// No allocation, no exceptions.
  double accel_m_s2(double t_s) const;

  /// The sample interval holding t: the k with k·dt ≤ t < (k+1)·dt (the products as
  /// written), for 0 ≤ t < duration_s(). accel_m_s2 interpolates in it.
  std::size_t interval_of(double t_s) const {
    std::size_t k = static_cast<std::size_t>(t_s * inv_dt_);
    // t·(1/dt) may land one ulp on the wrong side of an integer: the guess is corrected
    // against the sample times k·dt themselves (both corrections are conditional adds).
    k -= static_cast<std::size_t>(static_cast<double>(k) * dt_s_ > t_s);
    k += static_cast<std::size_t>(static_cast<double>(k + 1) * dt_s_ <= t_s);
    return k;
  }
  /// 1/dt [1/s], the factor accel_m_s2 interpolates with.
  double inverse_dt_per_s() const { return inv_dt_; }

  /// Peak absolute acceleration [m/s²] (found once, when the record is made).
  double pga_m_s2() const { return std::max(max_m_s2_, -min_m_s2_); }
  /// Smallest and largest sample [m/s²] (found once): scans over the record (uplift, free
  /// fall, the paper's trigger) skip a record whose extremes cannot reach their level.
  double min_m_s2() const { return min_m_s2_; }
  double max_m_s2() const { return max_m_s2_; }

  /// The same record multiplied by `factor` (a negative factor mirrors it); same name and dt.
  /// \throws UserError when factor is not finite or a scaled sample overflows.
  GroundMotion scaled(double factor) const;

 private:
  std::string name_;
  double dt_s_;
  double inv_dt_;
  std::vector<double> accel_m_s2_;
  double min_m_s2_ = 0.0;
  double max_m_s2_ = 0.0;
};

/// Relative tolerance within which two sample intervals are the same: intervals computed
/// from a time column (19.9 s / 1990 steps) differ from the written 0.01 s by an ulp or two.
inline constexpr double kSameIntervalTolerance = 1e-9;

/// True when `a_s` and `b_s` differ by at most kSameIntervalTolerance relative.
bool same_sample_interval(double a_s, double b_s);

}  // namespace pcrf
