// Closed-form acceleration pulses (see pulses.hpp for the formulas and references).
#include "pcrf/record/pulses.hpp"

#include "pcrf/user_error.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "pcrf/number_text.hpp"
#include "pcrf/setting.hpp"
#include "pcrf/units.hpp"

namespace pcrf {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRickerHalfWidth = 6.0;  ///< the wavelets are cut at |s| = 6 (relative size < 1e-6)
constexpr double kMaxSamples = 1e8;

/// "period_s of ricker must be …": the key and the kind as a synthetic string names them.
[[noreturn]] void bad(const PulseSpec& p, const char* field, const std::string& problem) {
  throw UserError(std::string(field) + " of " + pulse_kind(p.shape) + " " + problem);
}

void validate(const PulseSpec& p) {
  auto bad = [&p](const char* field, const std::string& problem) { pcrf::bad(p, field, problem); };
  auto positive = [&bad](const char* field, double value) {
    if (!(value > 0.0) || !std::isfinite(value)) bad(field, "must be positive and finite, got " + number_text(value));
  };
  positive("dt_s", p.dt_s);
  positive("period_s", p.period_s);
  positive("amplitude_g", p.amplitude_g);
  if (p.period_s < 4.0 * p.dt_s)
    bad("period_s", "= " + number_text(p.period_s) + " s is below 4 dt_s = " + number_text(4.0 * p.dt_s) +
                        " s: the pulse would not be resolved");
  if (p.shape == PulseShape::kCycles && p.cycles < 1) bad("cycles", "must be at least 1");
  if (p.shape == PulseShape::kMavroeidis && !(p.gamma > 1.0 && std::isfinite(p.gamma)))
    bad("gamma", "must be above 1 (the envelope holds more than one oscillation), got " + number_text(p.gamma));
  if (!std::isfinite(p.nu_deg)) bad("nu_deg", "must be finite");
  if (!(p.duration_s >= 0.0) || !std::isfinite(p.duration_s)) bad("duration_s", "must be 0 or positive");
}

/// A pulse of unit peak |acceleration| as a function of τ over its support, with the τ of
/// its peak.
struct UnitPulse {
  std::function<double(double)> accel;  ///< a(τ)/a_p
  double begin_s, end_s;                ///< support of τ
  double peak_s;                        ///< τ where |a| = a_p
  bool jumps_at_start = false;          ///< a(τ_begin) ≠ 0: start on sample 0
};

double antisymmetric_peak_s() { return std::sqrt(3.0 - std::sqrt(6.0)); }
double antisymmetric_norm() {
  const double s = antisymmetric_peak_s();
  return s * (3.0 - s * s) * std::exp(-0.5 * s * s);
}

/// The Mavroeidis–Papageorgiou velocity v/A and acceleration a/A at τ.
double mp_velocity(const PulseSpec& p, double tau) {
  const double w = 2.0 * kPi / p.period_s, nu = p.nu_deg * kPi / 180.0;
  return 0.5 * (1.0 + std::cos(w * tau / p.gamma)) * std::cos(w * tau + nu);
}
double mp_accel(const PulseSpec& p, double tau) {
  const double w = 2.0 * kPi / p.period_s, nu = p.nu_deg * kPi / 180.0;
  return -0.5 * w / p.gamma * std::sin(w * tau / p.gamma) * std::cos(w * tau + nu) -
         0.5 * w * (1.0 + std::cos(w * tau / p.gamma)) * std::sin(w * tau + nu);
}

/// Where |f| is largest on [a, b]: a dense scan, then golden-section refinement.
double argmax_abs(const std::function<double(double)>& f, double a, double b) {
  const int n = 20000;
  int best = 0;
  for (int i = 1; i <= n; ++i)
    if (std::abs(f(a + (b - a) * i / n)) > std::abs(f(a + (b - a) * best / n))) best = i;
  double lo = a + (b - a) * std::max(0, best - 1) / n, hi = a + (b - a) * std::min(n, best + 1) / n;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int k = 0; k < 100; ++k) {
    const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    (std::abs(f(x1)) > std::abs(f(x2)) ? hi : lo) = std::abs(f(x1)) > std::abs(f(x2)) ? x2 : x1;
  }
  return 0.5 * (lo + hi);
}

UnitPulse unit_pulse(const PulseSpec& p) {
  const double T = p.period_s, w = 2.0 * kPi / T;
  switch (p.shape) {
    case PulseShape::kSine: return {[w](double t) { return std::sin(w * t); }, 0.0, T, 0.25 * T};
    case PulseShape::kCosine: return {[w](double t) { return std::cos(w * t); }, 0.0, T, 0.0, true};
    case PulseShape::kCycles: {
      const double phi = cycles_pulse_phase_rad(p.cycles);
      return {[w, phi](double t) { return std::cos(w * t + phi); }, 0.0, (p.cycles + 0.5 - phi / kPi) * T,
              (kPi - phi) / w, true};
    }
    case PulseShape::kRicker: {
      const double sigma = T / (std::sqrt(2.0) * kPi);
      return {[sigma](double t) {
                const double s = t / sigma;
                return (1.0 - s * s) * std::exp(-0.5 * s * s);
              },
              -kRickerHalfWidth * sigma, kRickerHalfWidth * sigma, 0.0};
    }
    case PulseShape::kRickerAntisymmetric: {
      const double sigma = std::sqrt(3.0) * T / (2.0 * kPi), c = antisymmetric_norm();
      return {[sigma, c](double t) {
                const double s = t / sigma;
                return s * (3.0 - s * s) * std::exp(-0.5 * s * s) / c;
              },
              -kRickerHalfWidth * sigma, kRickerHalfWidth * sigma, antisymmetric_peak_s() * sigma};
    }
    case PulseShape::kMavroeidis: {
      const double half = 0.5 * p.gamma * T;
      const auto a = [p](double t) { return mp_accel(p, t); };
      const double peak = argmax_abs(a, -half, half);
      const double scale = 1.0 / std::abs(a(peak));
      return {[p, scale](double t) { return scale * mp_accel(p, t); }, -half, half, peak};
    }
  }
  throw UserError("pulse shape: unknown value");
}

}  // namespace

namespace {
constexpr std::array<EnumName<PulseShape>, 6> kPulseNames{{{PulseShape::kSine, "pulse-sine"},
                                                          {PulseShape::kCosine, "pulse-cosine"},
                                                          {PulseShape::kCycles, "pulse-cycles"},
                                                          {PulseShape::kRicker, "ricker"},
                                                          {PulseShape::kRickerAntisymmetric, "ricker-antisymmetric"},
                                                          {PulseShape::kMavroeidis, "mavroeidis"}}};
}  // namespace

std::string pulse_kind(PulseShape shape) { return name_of(kPulseNames, shape); }

std::vector<PulseShape> pulse_shapes() { return values_of(kPulseNames); }

double cycles_pulse_phase_rad(int cycles) {
  if (cycles < 1) throw UserError("cycles of pulse-cycles must be at least 1");
  // 2 cos φ − ((2n + 1)π − 2φ) sin φ falls from 2 at φ = 0 to −2nπ at φ = π/2.
  const auto residual = [cycles](double phi) {
    return 2.0 * std::cos(phi) - ((2.0 * cycles + 1.0) * kPi - 2.0 * phi) * std::sin(phi);
  };
  double lo = 0.0, hi = 0.5 * kPi;
  for (int k = 0; k < 200 && hi - lo > 0.0; ++k) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    (residual(mid) > 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double pulse_peak_velocity_m_s(const PulseSpec& p) {
  validate(p);
  const double a_p = p.amplitude_g * kGravity_m_s2, T = p.period_s;
  switch (p.shape) {
    case PulseShape::kSine: return a_p * T / kPi;
    case PulseShape::kCosine: return a_p * T / (2.0 * kPi);
    case PulseShape::kCycles: return a_p * T * (1.0 + std::sin(cycles_pulse_phase_rad(p.cycles))) / (2.0 * kPi);
    case PulseShape::kRicker: return a_p * T / (std::sqrt(2.0) * kPi) * std::exp(-0.5);
    case PulseShape::kRickerAntisymmetric: return a_p * std::sqrt(3.0) * T / (2.0 * kPi) / antisymmetric_norm();
    case PulseShape::kMavroeidis: {
      const double half = 0.5 * p.gamma * T;
      const auto a = [&p](double t) { return mp_accel(p, t); };
      const double amplitude = a_p / std::abs(a(argmax_abs(a, -half, half)));  // A
      const auto v = [&p](double t) { return mp_velocity(p, t); };
      return amplitude * std::abs(v(argmax_abs(v, -half, half)));
    }
  }
  return 0.0;
}

namespace {

/// The pulse's support and its duration in samples, checked before anything is sized by them:
/// a period of 1e308 s makes the support infinite and its sample count NaN.
void check_samples(const PulseSpec& p, const UnitPulse& unit) {
  const double support = (unit.end_s - unit.begin_s) / p.dt_s;
  if (!(support <= kMaxSamples) || !std::isfinite(unit.peak_s))
    bad(p, "period_s",
        "= " + number_text(p.period_s) + " s" +
            (p.shape == PulseShape::kMavroeidis ? " (times gamma = " + number_text(p.gamma) + ")" : std::string()) +
            " at dt_s = " + number_text(p.dt_s) + " s gives a pulse of " + number_text(support) + " samples, more than 1e8");
  if (!(p.duration_s / p.dt_s <= kMaxSamples)) bad(p, "duration_s", "gives more than 1e8 samples");
}

}  // namespace

GroundMotion make_pulse(const PulseSpec& p) {
  validate(p);
  const UnitPulse unit = unit_pulse(p);
  check_samples(p, unit);
  // The peak on sample k: a smooth pulse starts at δ = k dt − (τ_peak − τ_begin) ∈ [0, dt);
  // one that jumps at its start starts at 0 with dt shortened to (τ_peak − τ_begin)/k.
  const double to_peak = unit.peak_s - unit.begin_s;
  const double k = std::ceil(to_peak / p.dt_s);
  const double dt = unit.jumps_at_start && k > 0.0 ? to_peak / k : p.dt_s;
  const double delay = unit.jumps_at_start ? 0.0 : k * dt - to_peak;
  const double length_s = std::max(delay + (unit.end_s - unit.begin_s), p.duration_s);
  if (!(length_s / dt <= kMaxSamples)) bad(p, "duration_s", "gives more than 1e8 samples");
  const auto n = static_cast<std::size_t>(std::ceil(length_s / dt - 1e-9)) + 1;
  const double a_p = p.amplitude_g * kGravity_m_s2;
  std::vector<double> a(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double tau = static_cast<double>(i) * dt - delay + unit.begin_s;
    if (tau < unit.begin_s || tau > unit.end_s) continue;
    a[i] = std::clamp(a_p * unit.accel(tau), -a_p, a_p);
  }
  const auto peak = static_cast<std::size_t>(k);
  a[peak] = std::copysign(a_p, unit.accel(unit.peak_s));  // exactly a_p, whatever the rounding of τ
  return GroundMotion(pulse_kind(p.shape), dt, std::move(a));
}

}  // namespace pcrf
