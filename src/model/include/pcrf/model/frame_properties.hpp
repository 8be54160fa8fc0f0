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

/// FEMA P-695's period-based ductility μ_T = δ_u / δ_y,eff (Section 6.3, Eqs. 6-5 to 6-7) of a
/// one-storey frame, from its pushover curve (docs/p695_rocking_frame.md):
///  - δ_u, the roof displacement where the frame loses its capacity: the first rotation past
///    the peak at which the curve has fallen to 80 % of the peak, else the curve's end (a
///    tendon's fracture, the overturning angle); the roof moves by 2h sin θ₁ (h the half
///    column height: the column tops, rocking about the toes, neglecting b(1 − cos θ₁));
///  - δ_y,eff = C0 (V_max/W) (g/4π²) max(T, T1)², C0 = 1 (one storey), T1 = 0 (a rigid frame
///    has no elastic period), V_max/W the static capacity in g (`capacity`: the pushover
///    peak, P-695's convention) or the uplift threshold (`uplift`: the strength at which a
///    rigid frame first softens, the bilinear idealisation's yield).
struct P695Ductility {
  double ultimate_rotation_rad;    ///< θ₁ at δ_u [rad]
  double ultimate_displacement_m;  ///< δ_u [m]
  double yield_displacement_capacity_m;  ///< δ_y,eff with V_max = the pushover peak [m]
  double yield_displacement_uplift_m;    ///< δ_y,eff with V_max = the uplift threshold [m]
  double mu_t_capacity;            ///< δ_u / δ_y,eff (pushover peak): the engine's convention
  double mu_t_uplift;              ///< δ_u / δ_y,eff (uplift threshold)
};
P695Ductility p695_ductility(const FrameProperties& p, double half_column_height_m, double period_s);

/// The pushover curve's ground acceleration at |θ₁| = theta_rad [g]; NaN past the closing limit.
double pushover_accel_g(const Scene& eom, double theta_rad);

}  // namespace pcrf
