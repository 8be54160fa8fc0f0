// Projections of a horizontal pair on any azimuth (see horizontal_pair.hpp).
#include "pcrf/record/horizontal_pair.hpp"

#include "pcrf/user_error.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

#include "pcrf/number_text.hpp"

namespace pcrf {
namespace {

double radians(double deg) { return deg * std::numbers::pi / 180.0; }

/// `deg` reduced to [0, 360).
double wrapped(double deg) {
  const double w = std::fmod(deg, 360.0);
  return w < 0.0 ? w + 360.0 : w;
}

std::string upper(std::string text) {
  for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

bool ends_with(const std::string& text, const std::string& tail) {
  return text.size() >= tail.size() && text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}

}  // namespace

namespace {

/// The weights for a pair given with wrapped(az1) < wrapped(az2).
ProjectionWeights ordered_weights(double az1_deg, double az2_deg, double phi_deg) {
  const double span = std::sin(radians(az2_deg - az1_deg));
  // Measured from az₁ and reduced to [0°, 180°), with the sign of the half turn applied
  // afterwards: φ + 180° gives exactly the negated weights, φ = az₁ exactly (1, 0) and
  // φ = az₂ exactly (0, 1).
  double from_az1 = wrapped(phi_deg - az1_deg);
  double sign = 1.0;
  if (from_az1 >= 180.0) from_az1 -= 180.0, sign = -1.0;
  if (from_az1 == 0.0) return {sign, sign * 0.0};
  const double from_az2 = wrapped(phi_deg - az2_deg);
  if (from_az2 == 0.0 || from_az2 == 180.0) return {0.0, from_az2 == 0.0 ? 1.0 : -1.0};
  const double along = az1_deg + from_az1;
  return {sign * std::sin(radians(az2_deg - along)) / span, sign * std::sin(radians(along - az1_deg)) / span};
}

}  // namespace

ProjectionWeights projection_weights(double az1_deg, double az2_deg, double phi_deg) {
  if (!std::isfinite(az1_deg) || !std::isfinite(az2_deg) || !std::isfinite(phi_deg))
    throw UserError("azimuths must be finite numbers of degrees");
  if (std::abs(std::sin(radians(az2_deg - az1_deg))) < std::sin(radians(1.0))) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "components recorded along %g° and %g° are parallel: they do not give the horizontal motion",
                  az1_deg, az2_deg);
    throw UserError(text);
  }
  // The same arithmetic whichever component comes first, so that the projection (w₁ a₁ + w₂ a₂,
  // an addition that commutes exactly) does not depend on the order the pair is given in.
  if (wrapped(az1_deg) > wrapped(az2_deg)) {
    const ProjectionWeights w = ordered_weights(wrapped(az2_deg), wrapped(az1_deg), phi_deg);
    return {w.w2, w.w1};
  }
  return ordered_weights(wrapped(az1_deg), wrapped(az2_deg), phi_deg);
}

GroundMotion padded(const GroundMotion& record, std::size_t samples) {
  if (record.size() >= samples) return record;
  std::vector<double> a = record.samples_m_s2();
  a.resize(samples, 0.0);
  return GroundMotion(record.name(), record.dt_s(), std::move(a));
}

GroundMotion project(const HorizontalPair& pair, double phi_deg) {
  if (!same_sample_interval(pair.h1.dt_s(), pair.h2.dt_s()))
    throw UserError("the horizontal components '" + pair.h1.name() + "' and '" + pair.h2.name() +
                                "' are sampled at different intervals (" + number_text(pair.h1.dt_s()) + " s, " +
                                number_text(pair.h2.dt_s()) + " s)");
  const ProjectionWeights w = projection_weights(pair.az1_deg, pair.az2_deg, phi_deg);
  const std::size_t n = std::max(pair.h1.size(), pair.h2.size());
  const auto& a1 = pair.h1.samples_m_s2();
  const auto& a2 = pair.h2.samples_m_s2();
  std::vector<double> a(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double x1 = i < a1.size() ? a1[i] : 0.0, x2 = i < a2.size() ? a2[i] : 0.0;
    a[i] = w.w1 * x1 + w.w2 * x2;
  }
  char name[64];
  std::snprintf(name, sizeof name, "@%gdeg", phi_deg);
  return GroundMotion(pair.h1.name() + name, pair.h1.dt_s(), std::move(a));
}

std::string radians_problem(const std::vector<double>& values_deg) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  if (values_deg.empty()) return {};
  bool all_whole = true;
  for (const double v : values_deg) {
    if (!(std::fabs(v) <= kTwoPi)) return {};
    all_whole = all_whole && v == std::nearbyint(v);
  }
  if (all_whole) return {};
  char degrees[32];
  std::snprintf(degrees, sizeof degrees, "%.4g", values_deg.front() * 180.0 / std::numbers::pi);
  return "every value is within ±2π and not all are whole degrees: are they radians? (" + number_text(values_deg.front()) +
         " rad is " + degrees + "°); {} is in degrees";
}

bool is_vertical_component(const std::string& component) {
  const std::string c = upper(component);
  return c == "UP" || c == "V" || ends_with(c, "-UP") || ends_with(c, "-V") || ends_with(c, "DWN") ||
         ends_with(c, "VER") || ends_with(c, "UP");
}

std::optional<double> azimuth_of_component(const std::string& component) {
  const std::string c = upper(component);
  if (c.empty() || is_vertical_component(c)) return std::nullopt;
  // "CHY101-N": one compass letter after a single dash ("ABBAR--T" is a transverse channel).
  if (c.size() >= 3 && c[c.size() - 2] == '-' && c[c.size() - 3] != '-') {
    switch (c.back()) {
      case 'N': return 0.0;
      case 'E': return 90.0;
      case 'S': return 180.0;
      case 'W': return 270.0;
      default: break;
    }
  }
  // Trailing digits: the whole name ("230") or the last three ("H-E07140", "LCN345").
  std::size_t digits = 0;
  while (digits < c.size() && std::isdigit(static_cast<unsigned char>(c[c.size() - 1 - digits]))) ++digits;
  if (digits == 0) return std::nullopt;
  if (digits < c.size() && digits > 3) digits = 3;  // a station number before the angle
  if (digits == c.size() && digits > 3) return std::nullopt;
  const double azimuth = std::stod(c.substr(c.size() - digits));
  return azimuth <= 360.0 ? std::optional<double>(azimuth) : std::nullopt;  // "SYL360": north
}

}  // namespace pcrf
