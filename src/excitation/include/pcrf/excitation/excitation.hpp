/// \file excitation.hpp
/// \brief What one case is shaken by: the in-plane horizontal ground acceleration and,
/// optionally, the vertical one, as functions of time.
///
/// An Excitation is a view: it refers to records that the caller owns and keeps alive while
/// the view is used (the records a study or `pcrf run` loaded, scaled and combined). Its
/// components share one time axis, t = i·dt from 0: the same dt and the same number of
/// samples (components of different lengths are padded with zeros where they are put
/// together). After the last sample every component is zero (the free-vibration tail).
///
/// The solver evaluates it once per right-hand-side evaluation (at()) and hands the value
/// to the model; it never reads a record itself.
#pragma once

#include <optional>

#include "pcrf/ground_acceleration.hpp"
#include "pcrf/record/ground_motion.hpp"

namespace pcrf {

class Excitation {
 public:
  /// A horizontal motion alone (in the frame's plane). Implicit: every place that solved a
  /// case under one record keeps doing so.
  Excitation(const GroundMotion& horizontal)  // NOLINT: implicit by design
      : horizontal_(&horizontal) {}

  /// A horizontal and a vertical (positive up) motion; `vertical` may be null.
  /// \throws UserError when the two differ in dt or in number of samples.
  Excitation(const GroundMotion& horizontal, const GroundMotion* vertical);

  /// The ground acceleration at t [m/s²]; each component exactly as GroundMotion::accel_m_s2.
  GroundAcceleration at(double t_s) const {
    return {horizontal_->accel_m_s2(t_s), vertical_ != nullptr ? vertical_->accel_m_s2(t_s) : 0.0};
  }

  const GroundMotion& horizontal() const { return *horizontal_; }
  /// The vertical component, or null when there is none.
  const GroundMotion* vertical() const { return vertical_; }
  bool has_vertical() const { return vertical_ != nullptr; }

  /// The common sample interval [s].
  double dt_s() const { return horizontal_->dt_s(); }
  /// Time of the last sample [s].
  double duration_s() const { return horizontal_->duration_s(); }

 private:
  const GroundMotion* horizontal_;
  const GroundMotion* vertical_ = nullptr;
};

/// Evaluates an excitation at times that mostly fall in one sample interval (an
/// integrator's stages between two samples, where the record is linear): it remembers the
/// interval, so such a time costs a multiply-add. Bit for bit Excitation::at().
class ExcitationCursor {
 public:
  explicit ExcitationCursor(const Excitation& excitation) : excitation_(excitation) {}

  GroundAcceleration at(double t_s) {
    if (!hold(t_s)) return excitation_.at(t_s);
    const double frac = (t_s - i_.lo_s) * i_.inv_dt_per_s;
    return {i_.h0 + frac * i_.dh, i_.v0 + frac * i_.dv};
  }

  /// The ground from t on as a line, over the interval holding t: at(t) bit for bit, and
  /// the interval's slopes. False where at() is not one line from t on (before the record,
  /// at its last sample, components on their own time axes).
  bool line_from(double t_s, GroundLine& line) {
    if (!hold(t_s)) return false;
    const double frac = (t_s - i_.lo_s) * i_.inv_dt_per_s;
    line = {i_.h0 + frac * i_.dh, i_.h_slope_m_s3, i_.v0 + frac * i_.dv, i_.v_slope_m_s3};
    return true;
  }

  /// The record interval the cursor is in: at(t) inside it is h0 + (t − lo)/dt · dh (and v).
  struct Interval {
    double lo_s = 0.0, hi_s = 0.0;  ///< [k·dt, (k+1)·dt), or past the record; empty at first
    double inv_dt_per_s = 0.0;
    double h0 = 0.0, dh = 0.0, v0 = 0.0, dv = 0.0;  ///< samples k and their differences [m/s²]
    double h_slope_m_s3 = 0.0, v_slope_m_s3 = 0.0;  ///< dh / dt, dv / dt
  };
  const Interval& interval() const { return i_; }
  /// Moves to the sample interval after the current one (what enter() would find at its
  /// end, without the search); false, unchanged, where there is none (the record's end, the
  /// tail, or no interval yet).
  bool next_interval() {
    const GroundMotion& h = excitation_.horizontal();
    if (!sampled_ || k_ + 2 >= h.size()) return false;
    const std::size_t k = ++k_;
    i_.lo_s = i_.hi_s;  // static_cast<double>(k) * dt, as enter() computes it
    i_.hi_s = static_cast<double>(k + 1) * h.dt_s();
    load_samples(k);
    return true;
  }

 private:
  /// Whether i_ now holds t (entered if need be). Leaving the interval at its end (where a
  /// step that ended at a sample goes on): the next one, without enter()'s search (which
  /// finds the same interval there, exactly).
  bool hold(double t_s) {
    return (t_s >= i_.lo_s && t_s < i_.hi_s) || (t_s == i_.hi_s && next_interval()) || enter(t_s);
  }
  /// Samples k and k + 1 of every component into i_ (inv_dt_per_s set).
  void load_samples(std::size_t k) {
    const auto& a = excitation_.horizontal().samples_m_s2();
    i_.h0 = a[k], i_.dh = a[k + 1] - a[k];
    i_.h_slope_m_s3 = i_.dh * i_.inv_dt_per_s;
    if (const GroundMotion* v = excitation_.vertical()) {
      const auto& b = v->samples_m_s2();
      i_.v0 = b[k], i_.dv = b[k + 1] - b[k];
      i_.v_slope_m_s3 = i_.dv * i_.inv_dt_per_s;
    }
  }
  /// Remembers the interval holding t; past every component's last sample, the still
  /// ground's [end⁺, DBL_MAX) (zeros); false before the record, at its last sample, or NaN.
  bool enter(double t_s);
  bool enter_tail(double t_s);

  Excitation excitation_;
  Interval i_;
  std::size_t k_ = 0;  ///< the interval's index while i_ is a sample interval
  bool sampled_ = false;  ///< i_ is a sample interval (not empty, not the tail)
};

/// The one owner of a scaled excitation: copies of the components, every one multiplied
/// by `factor`, and the factor. What `pcrf run`, pcrf.run and a study's case shake a frame
/// with (frame_excitation(), station_record.hpp), and the verdict check's perturbed twins
/// (the whole ground motion scaled). Movable, not copyable (a copy would double the series);
/// a view() taken before a move points into the moved-from object.
class ScaledExcitation {
 public:
  /// `of`'s components scaled by `factor`.
  /// \throws UserError as GroundMotion::scaled.
  ScaledExcitation(const Excitation& of, double factor);
  ScaledExcitation(ScaledExcitation&&) = default;
  ScaledExcitation& operator=(ScaledExcitation&&) = default;

  Excitation view() const { return {horizontal_, vertical_ ? &*vertical_ : nullptr}; }
  const GroundMotion& horizontal() const { return horizontal_; }
  /// The factor every component was scaled by.
  double factor() const { return factor_; }

 private:
  GroundMotion horizontal_;
  std::optional<GroundMotion> vertical_;
  double factor_;
};

}  // namespace pcrf
