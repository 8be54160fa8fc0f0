/// \file intensity.hpp
/// \brief Intensity measures of a ground-motion record, computed from the record alone.
///
/// The record is taken as the engine integrates it: samples at t = i·dt, linear between
/// them, zero after the last one. No filtering or baseline correction is applied.
///
///   PGA      max |a_i|, and the first time it occurs.
///   PGV/PGD  peaks of v = ∫a dt and d = ∫v dt by the trapezoidal rule from v = d = 0.
///   Arias    I_A = π/(2g) ∫ a² dt, the integral of the linear interpolant done exactly
///            (dt/3 · (a_i² + a_i a_{i+1} + a_{i+1}²) per interval).
///   D5–95    time between 5 % and 95 % of I_A (cumulative I_A interpolated linearly
///            between samples).
///   Sa(T, ζ) pseudo-spectral acceleration ω² max |u| of the linear oscillator
///            ü + 2ζω u̇ + ω² u = −a(t), from rest. Nigam & Jennings (1969): the response to
///            a piecewise-linear excitation is exact from sample to sample; the peak is
///            taken at the record's samples and over one natural period of free vibration
///            after the record ends (the sample spacing continued).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pcrf/record/ground_motion.hpp"
#include "pcrf/record/record_readers.hpp"
#include "pcrf/setting.hpp"

namespace pcrf {

struct PeakAcceleration {
  double pga_g = 0.0;   ///< peak |a| [g]
  double t_pga_s = 0.0; ///< first time of the peak [s]
};
PeakAcceleration peak_acceleration(const GroundMotion& record);

/// Peak |v| [m/s] of the trapezoidal integral of the record.
double peak_velocity_m_s(const GroundMotion& record);
/// Peak |d| [m] of the trapezoidal double integral of the record.
double peak_displacement_m(const GroundMotion& record);
/// Arias intensity [m/s].
double arias_intensity_m_s(const GroundMotion& record);
/// 5–95 % significant duration [s] (0 for a record without motion).
double significant_duration_s(const GroundMotion& record);

/// 5 %-damped (or `damping`) pseudo-spectral acceleration at `period_s` [g].
/// \throws UserError when period_s ≤ 0 or damping is not in [0, 1).
double spectral_acceleration_g(const GroundMotion& record, double period_s, double damping = 0.05);

/// A measure a study can scale records to: "pga_g", "pgv_m_s" or "sa_g" of one component,
/// or RotD50 / RotD100 (rotd.hpp) of a station's horizontal pair: "pga_rotd50_g",
/// "pga_rotd100_g", "pgv_rotd50_m_s", "pgv_rotd100_m_s", "sa_rotd50_g", "sa_rotd100_g".
enum class IntensityMeasure { kPga, kPgv, kSa, kPgaRotD50, kPgaRotD100, kPgvRotD50, kPgvRotD100, kSaRotD50, kSaRotD100 };
/// The measure of one component behind a RotD measure (kPga for kPgaRotD50); itself otherwise.
IntensityMeasure component_measure(IntensityMeasure measure);
/// 50 or 100 for a RotD measure, 0 for a measure of one component.
int rotd_percentile(IntensityMeasure measure);
IntensityMeasure parse_intensity_measure(const std::string& text);  ///< \throws UserError
std::string to_string(IntensityMeasure measure);
/// UDUNITS of a measure's values: "g" ("9.81 m s-2" is spelled out in cube attributes), "m/s".
std::string_view intensity_units(IntensityMeasure measure);
/// "peak ground acceleration", "spectral acceleration Sa(T = 1 s, 5 % damping)", …
std::string intensity_long_name(IntensityMeasure measure, double period_s, double damping);

/// How a study's records are brought to a common intensity.
enum class SetNormalisation {
  kNone,  ///< each record is scaled to the intensity by its own measure
  /// FEMA P-695 Appendix A: each record (both components of a station) is first multiplied by
  /// NM = median over stations of PGV_pair / its station's PGV_pair, PGV_pair the geometric
  /// mean of the two horizontals' PGV; the normalised set is then scaled as a whole, its
  /// intensity being the median of the normalised components' measures.
  kP695,
};
SetNormalisation parse_set_normalisation(const std::string& text);  ///< "none" | "p695"
std::string to_string(SetNormalisation normalisation);

/// Which measure, and for Sa the oscillator.
struct IntensitySpec {
  IntensityMeasure measure = IntensityMeasure::kPga;
  double period_s = 0.0;   ///< Sa only
  double damping = 0.05;   ///< Sa only
  SetNormalisation normalise = SetNormalisation::kNone;  ///< studies only (the record set)
};
/// The record's value of the measure, in its units.
/// \throws UserError for a RotD measure (it needs a pair: station_intensity()).
double intensity_of(const GroundMotion& record, const IntensitySpec& spec);
/// The factor that brings a record whose measure is `record_intensity` to `target_intensity`:
/// every measure here is linear in the accelerations, so the ratio (infinite or NaN when
/// the record's measure is 0: callers check that first).
double intensity_scale_factor(double target_intensity, double record_intensity);

/// The series whose largest absolute value is the measure, in its units: the acceleration
/// [g] at the samples, the trapezoidal velocity [m/s], or ω² u [g] of the Sa oscillator at
/// the samples and over one period of free vibration after them. The series of a linear
/// combination of records is the same combination of their series (what RotD relies on).
std::vector<double> intensity_series(const GroundMotion& record, const IntensitySpec& spec);

/// The [intensity] table of a study (and the `pcrf run` flags --measure, --period-s,
/// --damping). Whether period_s is needed depends on the measure: intensity_spec_problem().
const SettingTable<IntensitySpec>& intensity_settings();
/// Why a spec cannot be used (a problem of period_s: sa_g without a usable period, or a
/// period given to a measure that has no oscillator); empty when it can.
std::string intensity_spec_problem(const IntensitySpec& spec);

/// Longest oscillator period accepted [s]: beyond any design spectrum, and the free-vibration
/// tail of the Sa computation grows with it.
inline constexpr double kMaxSaPeriod_s = 100.0;
/// Why Sa at `period_s` cannot be computed for a record sampled every `dt_s` (not a positive
/// finite period up to kMaxSaPeriod_s, or below 2·dt, where the oscillator is not resolved);
/// empty when it can. `dt_s` ≤ 0: the record is not known yet.
std::string sa_period_problem(double period_s, double dt_s);

/// A record read as `read_as` whose measures no earthquake record has: an unscaled PGA above
/// kMaxPlausiblePga_g or below kMinPlausiblePga_g (a file in other units than it was read
/// in), or a ratio PGV/PGA outside [kMinPgvPgaRatio_s, kMaxPgvPgaRatio_s] (a wrong time
/// step). Empty `problem` when it looks like a record.
struct RecordPlausibility {
  std::string problem;                ///< "PGA 501 g is above 3 g", …
  std::optional<AccelUnit> likely_unit;  ///< the unit that gives a plausible PGA, when one does
  std::string hint;                   ///< "is this file in cm/s²?", or what else to check
};
RecordPlausibility record_plausibility(const GroundMotion& record, AccelUnit read_as);
inline constexpr double kMaxPlausiblePga_g = 3.0;
inline constexpr double kMinPlausiblePga_g = 0.01;
/// PGV [m/s] over PGA [m/s²]: 0.023–0.73 s over the 192 files of ../shared/records (a
/// vertical of Imperial Valley to Chi-Chi TCU068-N, a fling record); the bounds leave a
/// factor of about 3 either side, so only a time step off by more than that is flagged.
inline constexpr double kMinPgvPgaRatio_s = 0.007;
inline constexpr double kMaxPgvPgaRatio_s = 2.0;

/// Why a record's values cannot be measured (they overflow the measures: Arias intensity or
/// the integrated velocity and displacement are not finite); empty when they can.
std::string measures_problem(const GroundMotion& record);

}  // namespace pcrf
