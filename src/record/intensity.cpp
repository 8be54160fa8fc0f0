/// \file intensity.cpp
/// \brief Intensity measures of a record (see intensity.hpp).
///
/// Sa: over one sample interval the excitation is linear, a(t) = a_i + s (t − t_i) with
/// s = (a_{i+1} − a_i)/dt, so the state w = (u, u̇, a, s) obeys the autonomous linear system
/// ẇ = N w with
///     N = [  0    1    0  0 ]
///         [ −ω²  −2ζω  −1  0 ]
///         [  0    0    0  1 ]
///         [  0    0    0  0 ],
/// and w(t_i + dt) = exp(N dt) w(t_i) exactly. This is the Nigam–Jennings recurrence; the
/// matrix exponential (Eigen, Padé with scaling and squaring) is computed once per period
/// instead of transcribing its closed-form coefficients.
#include "pcrf/record/intensity.hpp"

#include "pcrf/user_error.hpp"

#include <unsupported/Eigen/MatrixFunctions>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace pcrf {

PeakAcceleration peak_acceleration(const GroundMotion& record) {
  const auto& a = record.samples_m_s2();
  std::size_t at = 0;
  for (std::size_t i = 1; i < a.size(); ++i)
    if (std::fabs(a[i]) > std::fabs(a[at])) at = i;
  return {std::fabs(a[at]) / kGravity_m_s2, static_cast<double>(at) * record.dt_s()};
}

namespace {

/// Trapezoidal running integral of `x` with step dt, from 0.
std::vector<double> integrate(const std::vector<double>& x, double dt_s) {
  std::vector<double> out(x.size(), 0.0);
  for (std::size_t i = 1; i < x.size(); ++i) out[i] = out[i - 1] + 0.5 * dt_s * (x[i - 1] + x[i]);
  return out;
}

double peak_abs(const std::vector<double>& x) {
  double peak = 0.0;
  for (double v : x) peak = std::max(peak, std::fabs(v));
  return peak;
}

/// Cumulative ∫ a² dt of the linear interpolant at each sample [m²/s³].
std::vector<double> cumulative_square(const GroundMotion& record) {
  const auto& a = record.samples_m_s2();
  std::vector<double> out(a.size(), 0.0);
  const double dt = record.dt_s();
  for (std::size_t i = 1; i < a.size(); ++i)
    out[i] = out[i - 1] + dt / 3.0 * (a[i - 1] * a[i - 1] + a[i - 1] * a[i] + a[i] * a[i]);
  return out;
}

/// First time the cumulative curve reaches `level` (linear between samples).
double time_of_level(const std::vector<double>& cumulative, double dt_s, double level) {
  for (std::size_t i = 1; i < cumulative.size(); ++i) {
    if (cumulative[i] >= level) {
      const double span = cumulative[i] - cumulative[i - 1];
      const double frac = span > 0.0 ? (level - cumulative[i - 1]) / span : 0.0;
      return (static_cast<double>(i - 1) + frac) * dt_s;
    }
  }
  return static_cast<double>(cumulative.size() - 1) * dt_s;
}

}  // namespace

double peak_velocity_m_s(const GroundMotion& record) {
  return peak_abs(integrate(record.samples_m_s2(), record.dt_s()));
}

double peak_displacement_m(const GroundMotion& record) {
  return peak_abs(integrate(integrate(record.samples_m_s2(), record.dt_s()), record.dt_s()));
}

double arias_intensity_m_s(const GroundMotion& record) {
  return std::numbers::pi / (2.0 * kGravity_m_s2) * cumulative_square(record).back();
}

double significant_duration_s(const GroundMotion& record) {
  const auto cumulative = cumulative_square(record);
  const double total = cumulative.back();
  if (!(total > 0.0)) return 0.0;
  return time_of_level(cumulative, record.dt_s(), 0.95 * total) - time_of_level(cumulative, record.dt_s(), 0.05 * total);
}

namespace {

/// ω = 2π/T [rad/s].
double circular_frequency(double period_s) { return 2.0 * std::numbers::pi / period_s; }

/// Displacement u [m] of the oscillator at each sample and over one period of free
/// vibration after the record (Nigam–Jennings, see the file comment), after checking the
/// period and damping.
std::vector<double> oscillator_displacement_m(const GroundMotion& record, double period_s, double damping) {
  if (!(period_s > 0.0) || !std::isfinite(period_s))
    throw UserError("spectral acceleration: the period must be positive, got " + std::to_string(period_s));
  if (!(damping >= 0.0 && damping < 1.0))
    throw UserError("spectral acceleration: the damping ratio must be in [0, 1), got " +
                                std::to_string(damping));
  const double omega = circular_frequency(period_s);
  const double dt = record.dt_s();
  Eigen::Matrix4d N = Eigen::Matrix4d::Zero();
  N(0, 1) = 1.0;
  N(1, 0) = -omega * omega;
  N(1, 1) = -2.0 * damping * omega;
  N(1, 2) = -1.0;
  N(2, 3) = 1.0;
  const Eigen::Matrix4d step = (N * dt).exp();

  const auto& a = record.samples_m_s2();
  // Free vibration after the record: the first peak comes within one period.
  const auto tail_steps = static_cast<std::size_t>(std::ceil(period_s / dt));
  std::vector<double> out;
  out.reserve(a.size() + tail_steps);
  double u = 0.0, v = 0.0;
  auto advance = [&](double a0, double a1) {
    const Eigen::Vector4d w(u, v, a0, (a1 - a0) / dt);
    const double u1 = step.row(0).dot(w);
    v = step.row(1).dot(w);
    u = u1;
    out.push_back(u);
  };
  for (std::size_t i = 0; i + 1 < a.size(); ++i) advance(a[i], a[i + 1]);
  for (std::size_t k = 0; k < tail_steps; ++k) advance(0.0, 0.0);
  return out;
}

}  // namespace

double spectral_acceleration_g(const GroundMotion& record, double period_s, double damping) {
  const double peak = peak_abs(oscillator_displacement_m(record, period_s, damping));
  const double omega = circular_frequency(period_s);
  return omega * omega * peak / kGravity_m_s2;
}

namespace {
constexpr std::array<EnumName<IntensityMeasure>, 9> kMeasureNames{{{IntensityMeasure::kPga, "pga_g"},
                                                                   {IntensityMeasure::kPgv, "pgv_m_s"},
                                                                   {IntensityMeasure::kSa, "sa_g"},
                                                                   {IntensityMeasure::kPgaRotD50, "pga_rotd50_g"},
                                                                   {IntensityMeasure::kPgaRotD100, "pga_rotd100_g"},
                                                                   {IntensityMeasure::kPgvRotD50, "pgv_rotd50_m_s"},
                                                                   {IntensityMeasure::kPgvRotD100, "pgv_rotd100_m_s"},
                                                                   {IntensityMeasure::kSaRotD50, "sa_rotd50_g"},
                                                                   {IntensityMeasure::kSaRotD100, "sa_rotd100_g"}}};
constexpr std::array<EnumName<SetNormalisation>, 2> kNormalisationNames{{{SetNormalisation::kNone, "none"},
                                                                         {SetNormalisation::kP695, "p695"}}};
}  // namespace

IntensityMeasure component_measure(IntensityMeasure measure) {
  switch (measure) {
    case IntensityMeasure::kPgaRotD50:
    case IntensityMeasure::kPgaRotD100: return IntensityMeasure::kPga;
    case IntensityMeasure::kPgvRotD50:
    case IntensityMeasure::kPgvRotD100: return IntensityMeasure::kPgv;
    case IntensityMeasure::kSaRotD50:
    case IntensityMeasure::kSaRotD100: return IntensityMeasure::kSa;
    default: return measure;
  }
}

int rotd_percentile(IntensityMeasure measure) {
  switch (measure) {
    case IntensityMeasure::kPgaRotD50:
    case IntensityMeasure::kPgvRotD50:
    case IntensityMeasure::kSaRotD50: return 50;
    case IntensityMeasure::kPgaRotD100:
    case IntensityMeasure::kPgvRotD100:
    case IntensityMeasure::kSaRotD100: return 100;
    default: return 0;
  }
}
SetNormalisation parse_set_normalisation(const std::string& text) {
  return parse_name(kNormalisationNames, text, "normalisation");
}

std::string to_string(SetNormalisation normalisation) { return name_of(kNormalisationNames, normalisation); }

IntensityMeasure parse_intensity_measure(const std::string& text) {
  return parse_name(kMeasureNames, text, "intensity measure");
}

std::string to_string(IntensityMeasure measure) { return name_of(kMeasureNames, measure); }

std::string_view intensity_units(IntensityMeasure measure) {
  return component_measure(measure) == IntensityMeasure::kPgv ? "m/s" : "g";
}

std::string intensity_long_name(IntensityMeasure measure, double period_s, double damping) {
  if (const int percentile = rotd_percentile(measure); percentile > 0)
    return "RotD" + std::to_string(percentile) + " of the " +
           intensity_long_name(component_measure(measure), period_s, damping) + " (Boore 2010)";
  switch (measure) {
    case IntensityMeasure::kPga: return "peak ground acceleration";
    case IntensityMeasure::kPgv: return "peak ground velocity";
    case IntensityMeasure::kSa: {
      char text[128];
      std::snprintf(text, sizeof text, "pseudo-spectral acceleration Sa(T = %g s, %g %% damping)", period_s,
                    100.0 * damping);
      return text;
    }
    default: break;
  }
  return "";
}

double intensity_of(const GroundMotion& record, const IntensitySpec& spec) {
  switch (spec.measure) {
    case IntensityMeasure::kPga: return peak_acceleration(record).pga_g;
    case IntensityMeasure::kPgv: return peak_velocity_m_s(record);
    case IntensityMeasure::kSa: return spectral_acceleration_g(record, spec.period_s, spec.damping);
    default: break;
  }
  throw UserError(to_string(spec.measure) + " is a measure of a horizontal pair: '" + record.name() +
                              "' needs its second horizontal component");
}

std::vector<double> intensity_series(const GroundMotion& record, const IntensitySpec& spec) {
  switch (component_measure(spec.measure)) {
    case IntensityMeasure::kPga: {
      std::vector<double> a_g = record.samples_m_s2();
      for (double& x : a_g) x /= kGravity_m_s2;
      return a_g;
    }
    case IntensityMeasure::kPgv: return integrate(record.samples_m_s2(), record.dt_s());
    case IntensityMeasure::kSa: {
      std::vector<double> u = oscillator_displacement_m(record, spec.period_s, spec.damping);
      const double omega = circular_frequency(spec.period_s);
      for (double& x : u) x = omega * omega * x / kGravity_m_s2;
      return u;
    }
    default: break;
  }
  return {};
}

double intensity_scale_factor(double target_intensity, double record_intensity) {
  return target_intensity / record_intensity;
}

const SettingTable<IntensitySpec>& intensity_settings() {
  static const SettingTable<IntensitySpec> table = [] {
    SettingTable<IntensitySpec> t{"intensity", IntensitySpec{}, {}};
    auto& s = t.settings;
    s.push_back(choice_setting("measure", &IntensitySpec::measure, values_of(kMeasureNames), &to_string,
                               &parse_intensity_measure,
                               "what records are scaled to: peak ground acceleration [g], velocity [m/s] or Sa(T) [g] of the record, or their RotD50/RotD100 over the orientations of a record's horizontal pair (h1, h2)"));
    s.push_back(number_setting("period_s", &IntensitySpec::period_s, "s", Bound::kNonNegative,
                               "oscillator period of sa_g and sa_rotd*_g (required for them, at least 2·dt of every record, at most 100 s; no other measure takes one)"));
    s.back().aliases = {"--period"};
    s.push_back(number_setting("damping", &IntensitySpec::damping, "1", Bound::kFraction,
                               "damping ratio of the sa_g (sa_rotd*_g) oscillator"));
    s.push_back(choice_setting("normalise", &IntensitySpec::normalise, values_of(kNormalisationNames), &to_string,
                               &parse_set_normalisation,
                               "studies: p695 scales the record set as FEMA P-695 does (each station by its pair's "
                               "geometric-mean PGV, the set by its median measure; studies/README.md)"));
    return t;
  }();
  return table;
}

std::string intensity_spec_problem(const IntensitySpec& spec) {
  if (component_measure(spec.measure) != IntensityMeasure::kSa)
    return spec.period_s != 0.0 ? to_string(spec.measure) + " has no oscillator: period_s belongs to sa_g" : "";
  if (!(spec.period_s > 0.0)) return "sa_g needs an oscillator period above 0 s";
  return sa_period_problem(spec.period_s, 0.0);
}

std::string sa_period_problem(double period_s, double dt_s) {
  char text[200];
  if (!(period_s > 0.0) || !std::isfinite(period_s) || period_s > kMaxSaPeriod_s) {
    std::snprintf(text, sizeof text, "the oscillator period must be above 0 s and at most %g s, got %g s", kMaxSaPeriod_s,
                  period_s);
    return text;
  }
  if (dt_s > 0.0 && period_s < 2.0 * dt_s) {
    std::snprintf(text, sizeof text, "an oscillator period of %g s is below 2·dt = %g s of the record: its Sa is not resolved",
                  period_s, 2.0 * dt_s);
    return text;
  }
  return "";
}

RecordPlausibility record_plausibility(const GroundMotion& record, AccelUnit read_as) {
  RecordPlausibility result;
  const double pga_g = peak_acceleration(record).pga_g;
  if (!(pga_g > 0.0) || !std::isfinite(pga_g)) return result;  // measures_problem's, or a motionless record
  char text[200];
  if (pga_g > kMaxPlausiblePga_g || pga_g < kMinPlausiblePga_g) {
    std::snprintf(text, sizeof text, "PGA %.3g g is %s %g g", pga_g, pga_g > kMaxPlausiblePga_g ? "above" : "below",
                  pga_g > kMaxPlausiblePga_g ? kMaxPlausiblePga_g : kMinPlausiblePga_g);
    result.problem = text;
    // The values as written, then as each other unit would read them: of the units giving a
    // plausible PGA, the one nearest (in ratio) to a typical strong motion, 0.3 g.
    const double written = pga_g * kGravity_m_s2 / to_m_s2(read_as);
    double best_distance = std::numeric_limits<double>::infinity(), best_g = 0.0;
    for (AccelUnit unit : {AccelUnit::kG, AccelUnit::kMeterPerSecond2, AccelUnit::kCentimeterPerSecond2}) {
      if (unit == read_as) continue;
      const double as_g = written * to_m_s2(unit) / kGravity_m_s2;
      const double distance = std::abs(std::log(as_g / 0.3));
      if (as_g >= kMinPlausiblePga_g && as_g <= kMaxPlausiblePga_g && distance < best_distance) {
        best_distance = distance, best_g = as_g;
        result.likely_unit = unit;
      }
    }
    if (result.likely_unit) {
      std::snprintf(text, sizeof text, "is it in %s (PGA %.3g g)?", to_string(*result.likely_unit).c_str(), best_g);
      result.hint = text;
    }
    if (!result.likely_unit) result.hint = "check its units and scale";
    return result;
  }
  const double ratio_s = peak_velocity_m_s(record) / (pga_g * kGravity_m_s2);
  if (ratio_s < kMinPgvPgaRatio_s || ratio_s > kMaxPgvPgaRatio_s) {
    std::snprintf(text, sizeof text, "PGV/PGA = %.3g s is outside %g–%g s", ratio_s, kMinPgvPgaRatio_s, kMaxPgvPgaRatio_s);
    result.problem = text;
    std::snprintf(text, sizeof text, "is its time step %g s right (PGV scales with it)?", record.dt_s());
    result.hint = text;
  }
  return result;
}

std::string measures_problem(const GroundMotion& record) {
  const double arias = arias_intensity_m_s(record), pgv = peak_velocity_m_s(record), pgd = peak_displacement_m(record);
  if (std::isfinite(arias) && std::isfinite(pgv) && std::isfinite(pgd)) return "";
  char text[160];
  std::snprintf(text, sizeof text, "its accelerations (PGA %g g) overflow the intensity measures", peak_acceleration(record).pga_g);
  return text;
}

}  // namespace pcrf
