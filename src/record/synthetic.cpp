/// \file synthetic.cpp
/// \brief Synthetic ground motions: a sine pulse train and seeded Kanai–Tajimi filtered noise,
/// plus the "kind:key=value,..." text form used by the CLI and study files.
///
/// The stochastic record is reproducible: std::mt19937_64 (fully specified by the standard)
/// feeds an explicit Box–Muller transform, and the Kanai–Tajimi oscillator is advanced by its
/// exact discrete-time transition for noise held constant over each step (no adaptive steps,
/// no library distributions whose output varies between standard libraries).

#include "pcrf/record/synthetic.hpp"

#include "pcrf/user_error.hpp"

#include "pcrf/number_text.hpp"
#include "pcrf/record/pulses.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <functional>
#include <random>
#include <stdexcept>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <utility>
#include <vector>

namespace pcrf {

namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;
/// Longest record the generators make; beyond this a typo in dt_s or duration_s is likelier
/// than a real need, and the allocation would fail less helpfully.
constexpr double kMaxSamples = 1e8;


/// "period_s of sine must be …, got 1e-07": the key and the kind as a synthetic string
/// names them (`spec` is the kind: "sine", "stochastic"), the value in full.
[[noreturn]] void bad_field(const char* spec, const char* field, const std::string& requirement,
                            double value) {
  throw UserError(std::string(field) + " of " + spec + " " + requirement + ", got " +
                              number_text(value));
}

void require_positive(const char* spec, const char* field, double value) {
  if (!(value > 0.0) || !std::isfinite(value)) bad_field(spec, field, "must be positive and finite", value);
}

void require_non_negative(const char* spec, const char* field, double value) {
  if (!(value >= 0.0) || !std::isfinite(value)) bad_field(spec, field, "must be ≥ 0 and finite", value);
}

/// Number of samples at t = i·dt covering [0, duration]. A duration that is a whole number of
/// steps up to rounding (5 / 0.005 = 999.9999999999999) counts as whole, so it ends on a sample.
std::size_t sample_count(const char* spec, double duration_s, double dt_s) {
  const double steps = duration_s / dt_s;
  if (steps > kMaxSamples) {
    bad_field(spec, "duration_s", "gives more than 1e8 samples at dt_s = " + number_text(dt_s),
              duration_s);
  }
  const double nearest = std::nearbyint(steps);
  const double whole = std::abs(steps - nearest) <= 1e-9 * std::max(1.0, steps) ? nearest
                                                                                 : std::floor(steps);
  return static_cast<std::size_t>(whole) + 1;
}

// ---- sine pulse train -----------------------------------------------------------------------

void validate(const SinePulseSpec& s) {
  constexpr const char* kSpec = "sine";
  require_positive(kSpec, "amplitude_g", s.amplitude_g);
  require_positive(kSpec, "period_s", s.period_s);
  require_positive(kSpec, "dt_s", s.dt_s);
  if (s.cycles < 1) bad_field(kSpec, "cycles", "must be ≥ 1", s.cycles);
  // Fewer than 4 samples a period and the sampled train no longer looks like a sine
  // (at 2 samples a period every sample is zero).
  if (s.period_s < 4.0 * s.dt_s) {
    bad_field(kSpec, "period_s", "must be at least 4·dt_s = " + number_text(4.0 * s.dt_s), s.period_s);
  }
  const double pulses_s = s.cycles * s.period_s;
  if (!std::isfinite(s.duration_s) || s.duration_s < pulses_s * (1.0 - 1e-12)) {
    bad_field(kSpec, "duration_s", "must be at least cycles·period_s = " + number_text(pulses_s),
              s.duration_s);
  }
}

std::string sine_name(const SinePulseSpec& s) {
  return "sine:amplitude_g=" + number_text(s.amplitude_g) + ",period_s=" +
         number_text(s.period_s) + ",cycles=" + std::to_string(s.cycles) +
         ",duration_s=" + number_text(s.duration_s) + ",dt_s=" + number_text(s.dt_s);
}

// ---- stochastic record ----------------------------------------------------------------------

void validate(const StochasticSpec& s) {
  constexpr const char* kSpec = "stochastic";
  require_positive(kSpec, "pga_g", s.pga_g);
  require_positive(kSpec, "dt_s", s.dt_s);
  require_positive(kSpec, "duration_s", s.duration_s);
  // At least two samples: the first is always zero (the filter starts at rest).
  if (s.duration_s < s.dt_s) {
    bad_field(kSpec, "duration_s", "must be at least dt_s = " + number_text(s.dt_s), s.duration_s);
  }
  require_positive(kSpec, "ground_freq_hz", s.ground_freq_hz);
  if (s.ground_freq_hz >= 0.5 / s.dt_s) {
    bad_field(kSpec, "ground_freq_hz", "must be below the Nyquist frequency 0.5/dt_s = " +
                                           number_text(0.5 / s.dt_s), s.ground_freq_hz);
  }
  require_positive(kSpec, "ground_damping", s.ground_damping);
  require_non_negative(kSpec, "rise_s", s.rise_s);
  require_non_negative(kSpec, "strong_s", s.strong_s);
  require_non_negative(kSpec, "decay_per_s", s.decay_per_s);
}

std::string stochastic_name(const StochasticSpec& s) {
  return "stochastic:seed=" + std::to_string(s.seed) + ",pga_g=" + number_text(s.pga_g) +
         ",duration_s=" + number_text(s.duration_s) + ",dt_s=" + number_text(s.dt_s) +
         ",ground_freq_hz=" + number_text(s.ground_freq_hz) +
         ",ground_damping=" + number_text(s.ground_damping) + ",rise_s=" +
         number_text(s.rise_s) + ",strong_s=" + number_text(s.strong_s) +
         ",decay_per_s=" + number_text(s.decay_per_s);
}

/// Standard normal numbers from mt19937_64 by the Box–Muller transform, written out here
/// because std::normal_distribution differs between standard libraries.
class NormalSource {
 public:
  explicit NormalSource(std::uint64_t seed) : engine_(seed) {}

  double next() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = uniform_open_closed();  // (0, 1]: log(u1) is finite
    const double u2 = uniform_closed_open();  // [0, 1)
    const double radius = std::sqrt(-2.0 * std::log(u1));
    spare_ = radius * std::sin(kTwoPi * u2);
    has_spare_ = true;
    return radius * std::cos(kTwoPi * u2);
  }

 private:
  static constexpr double kTwoPowMinus53 = 1.0 / 9007199254740992.0;
  double uniform_closed_open() { return static_cast<double>(engine_() >> 11) * kTwoPowMinus53; }
  double uniform_open_closed() { return static_cast<double>((engine_() >> 11) + 1) * kTwoPowMinus53; }

  std::mt19937_64 engine_;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

/// Kanai–Tajimi filter x'' + 2ζω x' + ω² x = −w(t), output a = −(2ζω x' + ω² x) (the absolute
/// acceleration of the "soil" oscillator). Advanced by the exact transition over dt for w held
/// constant over the step: stable and exact for any dt, no integration error to tune.
class KanaiTajimiFilter {
 public:
  KanaiTajimiFilter(double freq_hz, double damping, double dt_s)
      : omega_(kTwoPi * freq_hz), zeta_(damping) {
    // e^{F dt} for F = [[0, 1], [−ω², −2ζω]] by the 2×2 formula
    // e^{M} = e^{s} (c I + h (M − s I)), s = tr M / 2, q² = s² − det M,
    // c = cos q, h = sin q / q (q² < 0, taking |q|) or cosh/sinh (q² > 0).
    const double wdt = omega_ * dt_s;
    const double s = -zeta_ * wdt;
    const double q2 = wdt * wdt * (zeta_ * zeta_ - 1.0);
    double c = 1.0;
    double h = 1.0;
    if (q2 < 0.0) {
      const double q = std::sqrt(-q2);
      c = std::cos(q);
      h = std::sin(q) / q;
    } else if (q2 > 0.0) {
      const double q = std::sqrt(q2);
      c = std::cosh(q);
      h = std::sinh(q) / q;
    }
    const double es = std::exp(s);
    phi11_ = es * (c + h * zeta_ * wdt);
    phi12_ = es * h * dt_s;
    phi21_ = -es * h * omega_ * omega_ * dt_s;
    phi22_ = es * (c - h * zeta_ * wdt);
    // Γ = F⁻¹ (Φ − I) b with b = (0, −1) and F⁻¹ = [[−2ζ/ω, −1/ω²], [1, 0]].
    gamma1_ = 2.0 * zeta_ * phi12_ / omega_ - (1.0 - phi22_) / (omega_ * omega_);
    gamma2_ = -phi12_;
  }

  /// Current output, then one step with forcing w over the next dt.
  double output_then_step(double w) {
    const double a = -(2.0 * zeta_ * omega_ * v_ + omega_ * omega_ * x_);
    const double x_next = phi11_ * x_ + phi12_ * v_ + gamma1_ * w;
    const double v_next = phi21_ * x_ + phi22_ * v_ + gamma2_ * w;
    x_ = x_next;
    v_ = v_next;
    return a;
  }

 private:
  double omega_;
  double zeta_;
  double phi11_ = 0.0, phi12_ = 0.0, phi21_ = 0.0, phi22_ = 0.0;
  double gamma1_ = 0.0, gamma2_ = 0.0;
  double x_ = 0.0;
  double v_ = 0.0;
};

/// Jennings-type envelope: (t/t_rise)² rise, plateau, then exponential decay.
double envelope(const StochasticSpec& s, double t_s) {
  if (t_s < s.rise_s) return (t_s / s.rise_s) * (t_s / s.rise_s);
  const double plateau_end_s = s.rise_s + s.strong_s;
  if (t_s <= plateau_end_s) return 1.0;
  return std::exp(-s.decay_per_s * (t_s - plateau_end_s));
}

/// Scales to the target peak and pins it: x·(P/x) can miss P by an ulp, and any sample that
/// rounding pushed past P is set to ±P, so the record's peak |a| equals P exactly.
void scale_to_peak(std::vector<double>& accel, double target_peak) {
  std::size_t peak_index = 0;
  for (std::size_t i = 1; i < accel.size(); ++i) {
    if (std::abs(accel[i]) > std::abs(accel[peak_index])) peak_index = i;
  }
  const double peak = std::abs(accel[peak_index]);
  if (!(peak > 0.0)) throw UserError("stochastic: the record is identically zero");
  const double factor = target_peak / peak;
  for (double& a : accel) {
    a *= factor;
    if (std::abs(a) > target_peak) a = std::copysign(target_peak, a);
  }
  accel[peak_index] = std::copysign(target_peak, accel[peak_index]);
}

// ---- text form --------------------------------------------------------------------------------

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

template <typename T>
bool parse_whole(std::string_view text, T& value) {
  if constexpr (std::is_floating_point_v<T>) {
    if (text.size() >= 2 && text.front() == '+') text.remove_prefix(1);
  }
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end) return false;
  if constexpr (std::is_floating_point_v<T>) return std::isfinite(value);
  return true;
}

/// One settable field of a spec: its key and how to store a value given as text.
template <typename Spec>
struct Field {
  const char* key;
  std::function<bool(Spec&, std::string_view)> set;
};

template <typename Spec, typename T>
Field<Spec> field(const char* key, T Spec::*member) {
  return {key, [member](Spec& spec, std::string_view text) {
            return parse_whole(text, spec.*member);
          }};
}

template <typename Spec>
std::string key_list(const std::vector<Field<Spec>>& fields) {
  std::string keys;
  for (const auto& f : fields) keys += (keys.empty() ? "" : ", ") + std::string(f.key);
  return keys;
}

/// Applies "key=value,key=value" to `spec`; every key known, none repeated, every value valid.
template <typename Spec>
void apply_assignments(const std::string& text, std::string_view kind, std::string_view list,
                       const std::vector<Field<Spec>>& fields, Spec& spec) {
  const auto error = [&](const std::string& problem) {
    return UserError("synthetic record '" + text + "': " + problem);
  };
  std::vector<std::string_view> seen;
  if (trim(list).empty()) return;  // "sine" or "sine:" → all defaults
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t comma = std::min(list.find(',', start), list.size());
    const std::string_view item = trim(list.substr(start, comma - start));
    start = comma + 1;
    const std::size_t eq = item.find('=');
    if (item.empty()) throw error("empty item (stray comma)");
    if (eq == std::string_view::npos) throw error("expected key=value, got '" + std::string(item) + "'");
    const std::string_view key = trim(item.substr(0, eq));
    const std::string_view value = trim(item.substr(eq + 1));
    const auto it = std::find_if(fields.begin(), fields.end(),
                                 [&](const Field<Spec>& f) { return key == f.key; });
    if (it == fields.end()) {
      throw error("unknown key '" + std::string(key) + "' for " + std::string(kind) +
                  " (known: " + key_list(fields) + ")");
    }
    if (std::find(seen.begin(), seen.end(), key) != seen.end()) {
      throw error("key '" + std::string(key) + "' given twice");
    }
    seen.push_back(key);
    if (!it->set(spec, value)) {
      throw error("bad value '" + std::string(value) + "' for key '" + std::string(key) + "'");
    }
  }
}

const std::vector<Field<SinePulseSpec>>& sine_fields() {
  static const std::vector<Field<SinePulseSpec>> fields = {
      field("amplitude_g", &SinePulseSpec::amplitude_g), field("period_s", &SinePulseSpec::period_s),
      field("cycles", &SinePulseSpec::cycles), field("duration_s", &SinePulseSpec::duration_s),
      field("dt_s", &SinePulseSpec::dt_s)};
  return fields;
}

const std::vector<Field<StochasticSpec>>& stochastic_fields() {
  static const std::vector<Field<StochasticSpec>> fields = {
      field("seed", &StochasticSpec::seed), field("pga_g", &StochasticSpec::pga_g),
      field("duration_s", &StochasticSpec::duration_s), field("dt_s", &StochasticSpec::dt_s),
      field("ground_freq_hz", &StochasticSpec::ground_freq_hz),
      field("ground_damping", &StochasticSpec::ground_damping),
      field("rise_s", &StochasticSpec::rise_s), field("strong_s", &StochasticSpec::strong_s),
      field("decay_per_s", &StochasticSpec::decay_per_s)};
  return fields;
}

/// The keys of a pulse kind: those every pulse has, and its own.
std::vector<Field<PulseSpec>> pulse_fields(PulseShape shape) {
  std::vector<Field<PulseSpec>> fields = {field("period_s", &PulseSpec::period_s),
                                          field("amplitude_g", &PulseSpec::amplitude_g),
                                          field("duration_s", &PulseSpec::duration_s), field("dt_s", &PulseSpec::dt_s)};
  if (shape == PulseShape::kCycles) fields.push_back(field("cycles", &PulseSpec::cycles));
  if (shape == PulseShape::kMavroeidis) {
    fields.push_back(field("gamma", &PulseSpec::gamma));
    fields.push_back(field("nu_deg", &PulseSpec::nu_deg));
  }
  return fields;
}

/// Same record under another name (the text the caller gave).
GroundMotion renamed(const GroundMotion& g, const std::string& name) {
  return GroundMotion(name, g.dt_s(), g.samples_m_s2());
}

}  // namespace

GroundMotion make_sine_pulse_train(const SinePulseSpec& spec) {
  validate(spec);
  const std::size_t n = sample_count("sine", spec.duration_s, spec.dt_s);
  const double amplitude_m_s2 = spec.amplitude_g * kGravity_m_s2;
  std::vector<double> accel_m_s2(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double phase = static_cast<double>(i) * spec.dt_s / spec.period_s;  // cycles elapsed
    if (phase >= spec.cycles) break;
    accel_m_s2[i] = amplitude_m_s2 * std::sin(kTwoPi * phase);
  }
  return GroundMotion(sine_name(spec), spec.dt_s, std::move(accel_m_s2));
}

GroundMotion make_stochastic(const StochasticSpec& spec) {
  validate(spec);
  const std::size_t n = sample_count("stochastic", spec.duration_s, spec.dt_s);
  NormalSource noise(spec.seed);
  KanaiTajimiFilter filter(spec.ground_freq_hz, spec.ground_damping, spec.dt_s);
  std::vector<double> accel_m_s2(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t_s = static_cast<double>(i) * spec.dt_s;
    accel_m_s2[i] = envelope(spec, t_s) * filter.output_then_step(noise.next());
  }
  scale_to_peak(accel_m_s2, spec.pga_g * kGravity_m_s2);
  return GroundMotion(stochastic_name(spec), spec.dt_s, std::move(accel_m_s2));
}

GroundMotion make_synthetic(const std::string& text) {
  const std::size_t colon = text.find(':');
  const std::string_view kind = trim(std::string_view(text).substr(0, colon));
  const std::string_view list =
      colon == std::string::npos ? std::string_view() : std::string_view(text).substr(colon + 1);
  // The generators' own checks name the field; prefix the text so the caller sees which record.
  const auto with_text = [&](auto&& make) {
    try {
      return renamed(make(), text);
    } catch (const std::invalid_argument& e) {
      throw UserError("synthetic record '" + text + "': " + e.what());
    }
  };
  if (kind == "sine") {
    SinePulseSpec spec;
    apply_assignments(text, kind, list, sine_fields(), spec);
    return with_text([&] { return make_sine_pulse_train(spec); });
  }
  if (kind == "stochastic") {
    StochasticSpec spec;
    apply_assignments(text, kind, list, stochastic_fields(), spec);
    return with_text([&] { return make_stochastic(spec); });
  }
  for (const PulseShape shape : pulse_shapes()) {
    if (kind != pulse_kind(shape)) continue;
    PulseSpec spec;
    spec.shape = shape;
    apply_assignments(text, kind, list, pulse_fields(shape), spec);
    return with_text([&] { return make_pulse(spec); });
  }
  std::string kinds = "sine, stochastic";
  for (const PulseShape shape : pulse_shapes()) kinds += ", " + pulse_kind(shape);
  throw UserError("synthetic record '" + text + "': unknown kind '" + std::string(kind) + "' (expected " +
                              kinds + ")");
}

}  // namespace pcrf
