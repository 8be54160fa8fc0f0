/// \file frame_properties.hpp
/// \brief What a frame is, before any ground motion: the numbers `pcrf frame` prints.
///
/// The uplift coefficient and threshold, the coefficient of restitution, the frequency
/// parameter p and the equivalent rigid block (docs/frequency_parameter.md), the angles where
/// a case stops (a tendon's fracture, the overturning angle, the linkage's closing limit) and
/// the static pushover curve: the horizontal ground acceleration that holds the frame still at
/// a rotation θ₁, from Eq. (31) with θ̇₁ = θ̈₁ = 0,
///
///     a(θ₁) = (G(θ₁) g + K(θ₁)) / S(θ₁)      (θ₁ ≤ 0; the mirror image for θ₁ ≥ 0),
///
/// which starts at the uplift threshold at θ₁ = 0 and whose peak is the frame's static
/// capacity. A frame with tendons stiff enough keeps rising until a tendon fractures; one
/// without falls from the start, as a rigid block's does.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "pcrf/model/scene.hpp"

namespace pcrf {

struct PushoverPoint {
  double theta_rad;  ///< |θ₁| [rad]
  double accel_g;    ///< ground acceleration holding the frame there [g]
};

struct FrameProperties {
  double lambda_g;                 ///< G(0)/S(0), the paper's uplift coefficient [-]
  double uplift_threshold_g;       ///< prestress included [g]
  double restitution;              ///< r [-]
  double frequency_parameter_rad_s;///< p = √(g √(G(0)² + S(0)²) / I(0)) [rad/s]
  double equivalent_block_size_m;  ///< R̂ = 3g/(4p²) [m]
  double equivalent_block_slenderness_rad;  ///< α̂ = atan(λ_g) [rad]
  double fracture_angle_rad;       ///< +∞ when no tendon fractures before the closing limit
  std::string fracture_tendon;     ///< "column" or "beam"; empty without fracture
  double overturn_angle_rad;       ///< where a case ends as overturned [rad]
  double closing_limit_rad;        ///< where the linkage stops closing [rad]
  std::vector<PushoverPoint> pushover;  ///< from 0 to the first stop angle, evenly spaced
  double capacity_g;               ///< the pushover curve's peak [g]
  double capacity_theta_rad;       ///< where it peaks [rad]
};

/// One number of FrameProperties: its key (JSON, Python), a label for people, its unit.
struct FramePropertyInfo {
  std::string_view key;
  std::string_view label;
  std::string_view units;  ///< "rad", "g", "m", "rad/s" or "1"
  double FrameProperties::*member;
};
/// Every number of FrameProperties, in the order `pcrf frame` prints them.
const std::vector<FramePropertyInfo>& frame_property_table();

/// The properties of `frame` whose tendons fracture at `fracture_strain`, the pushover curve
/// sampled at `points` rotations (≥ 2) and its peak located to 1e-10 rad.
FrameProperties frame_properties(const Scene& eom, double fracture_strain, int points = 101);

/// The pushover curve's ground acceleration at |θ₁| = theta_rad [g]; NaN past the closing limit.
double pushover_accel_g(const Scene& eom, double theta_rad);

}  // namespace pcrf
