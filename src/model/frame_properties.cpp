// A frame's properties and its static pushover curve (see frame_properties.hpp).
#include "pcrf/model/frame_properties.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>


#include "pcrf/units.hpp"

namespace pcrf {

const std::vector<FramePropertyInfo>& frame_property_table() {
  using P = FrameProperties;
  static const std::vector<FramePropertyInfo> table = {
      {"lambda_g", "uplift coefficient lambda_g = G/S", "1", &P::lambda_g},
      {"uplift_threshold_g", "uplift threshold (prestress included)", "g", &P::uplift_threshold_g},
      {"restitution", "coefficient of restitution r", "1", &P::restitution},
      {"frequency_parameter_rad_s", "frequency parameter p", "rad/s", &P::frequency_parameter_rad_s},
      {"equivalent_block_size_m", "equivalent block: size R", "m", &P::equivalent_block_size_m},
      {"equivalent_block_slenderness_rad", "equivalent block: slenderness alpha", "rad",
       &P::equivalent_block_slenderness_rad},
      {"fracture_angle_rad", "fracture angle", "rad", &P::fracture_angle_rad},
      {"overturn_angle_rad", "overturning angle", "rad", &P::overturn_angle_rad},
      {"closing_limit_rad", "closing limit of the mechanism", "rad", &P::closing_limit_rad},
      {"capacity_g", "static capacity (pushover peak)", "g", &P::capacity_g},
      {"capacity_theta_rad", "  at rotation", "rad", &P::capacity_theta_rad},
  };
  return table;
}

double pushover_accel_g(const Scene& eom, double theta_rad) {
  EomTerms t;
  if (!eom.terms(-theta_rad, -1, t)) return std::numeric_limits<double>::quiet_NaN();
  return (t.G * eom.gravity_m_s2() + t.K) / t.S / kGravity_m_s2;
}

namespace {

/// The pushover curve's peak in [lo, hi], by golden-section search.
PushoverPoint refine_peak(const Scene& eom, double lo, double hi) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  while (hi - lo > 1e-10) {
    const double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
    if (pushover_accel_g(eom, a) > pushover_accel_g(eom, b)) {
      hi = b;
    } else {
      lo = a;
    }
  }
  const double theta = 0.5 * (lo + hi);
  return {theta, pushover_accel_g(eom, theta)};
}

}  // namespace

FrameProperties frame_properties(const Scene& eom, double fracture_strain, int points) {
  FrameProperties p{};
  EomTerms rest;
  eom.terms(0.0, -1, rest);
  const double g = eom.gravity_m_s2();
  p.lambda_g = eom.lambda_g();
  p.uplift_threshold_g = eom.uplift_threshold_m_s2() / kGravity_m_s2;
  p.restitution = eom.restitution();
  const double p2 = g * std::hypot(rest.G, rest.S) / rest.I;
  p.frequency_parameter_rad_s = std::sqrt(p2);
  p.equivalent_block_size_m = 3.0 * g / (4.0 * p2);
  p.equivalent_block_slenderness_rad = std::atan(p.lambda_g);
  p.fracture_angle_rad = eom.fracture_angle_rad(fracture_strain);
  if (std::isfinite(p.fracture_angle_rad)) {
    const TendonState at = eom.tendons(-p.fracture_angle_rad, -1);
    p.fracture_tendon = at.strain_beam > at.strain_column_max() ? "beam" : "column";
  }
  p.overturn_angle_rad = eom.overturn_angle_rad();
  p.closing_limit_rad = eom.closing_limit_rad();
  const double end = std::min(p.fracture_angle_rad, p.overturn_angle_rad);
  const int n = std::max(points, 2);
  int best = 0;
  for (int i = 0; i < n; ++i) {
    const double theta = end * i / (n - 1);
    p.pushover.push_back({theta, pushover_accel_g(eom, theta)});
    if (p.pushover.back().accel_g > p.pushover[static_cast<std::size_t>(best)].accel_g) best = i;
  }
  const double lo = end * std::max(0, best - 1) / (n - 1), hi = end * std::min(n - 1, best + 1) / (n - 1);
  // At an end of the range (a falling curve, or one rising to the fracture) the sample is the peak.
  const bool at_end = best == 0 || best == n - 1;
  const PushoverPoint peak = at_end ? p.pushover[static_cast<std::size_t>(best)] : refine_peak(eom, lo, hi);
  p.capacity_g = peak.accel_g;
  p.capacity_theta_rad = peak.theta_rad;
  return p;
}

P695Ductility p695_ductility(const FrameProperties& p, double half_column_height_m, double period_s) {
  // δ_u: 80 % of the peak after it, interpolated between the curve's points, else its end.
  double theta_u = p.pushover.back().theta_rad;
  const double floor_g = 0.8 * p.capacity_g;
  for (std::size_t i = 1; i < p.pushover.size(); ++i) {
    const PushoverPoint &a = p.pushover[i - 1], &b = p.pushover[i];
    if (b.theta_rad <= p.capacity_theta_rad || !(b.accel_g <= floor_g)) continue;
    theta_u = a.accel_g <= floor_g ? a.theta_rad
                                   : a.theta_rad + (a.accel_g - floor_g) / (a.accel_g - b.accel_g) * (b.theta_rad - a.theta_rad);
    break;
  }
  P695Ductility d{};
  d.ultimate_rotation_rad = theta_u;
  d.ultimate_displacement_m = 2.0 * half_column_height_m * std::sin(theta_u);
  const double spectral_m_per_g = kGravity_m_s2 * period_s * period_s / (4.0 * std::numbers::pi * std::numbers::pi);
  d.yield_displacement_capacity_m = p.capacity_g * spectral_m_per_g;
  d.yield_displacement_uplift_m = p.uplift_threshold_g * spectral_m_per_g;
  d.mu_t_capacity = d.ultimate_displacement_m / d.yield_displacement_capacity_m;
  d.mu_t_uplift = d.ultimate_displacement_m / d.yield_displacement_uplift_m;
  return d;
}

}  // namespace pcrf
