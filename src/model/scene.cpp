// What every scene shares: the decisions derived from its terms at rest (see scene.hpp).
#include "pcrf/model/scene.hpp"

#include "pcrf/user_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace pcrf {

double TendonState::strain_column_max() const { return std::max(strain_column_left, strain_column_right); }

double Scene::fracture_angle_rad(double) const { return std::numeric_limits<double>::infinity(); }

bool Scene::broken_at_rest(double) const { return false; }

TendonState Scene::tendons(double, int) const { return {}; }

TendonState Scene::peak_tendon_strains(double) const { return {}; }

bool Scene::configuration(double, int, double& theta2, double& theta3) const {
  theta2 = theta3 = std::numeric_limits<double>::quiet_NaN();
  return true;
}

void Scene::settle_rest() {
  if (!terms(0.0, -1, rest_)) throw UserError("impossible frame: the linkage does not close at rest");
  lambda_g_ = rest_.G / rest_.S;
  uplift_threshold_m_s2_ = uplift_threshold_m_s2(0.0);
}

double Scene::uplift_threshold_m_s2(double vertical_m_s2) const {
  return (rest_.G * (gravity_m_s2() + vertical_m_s2) + rest_.K) / rest_.S;
}

bool Scene::holds_closed(GroundAcceleration ground) const {
  // rest_acceleration(ground, −1) < 0 opens into θ₁ < 0, rest_acceleration(ground, +1) > 0
  // into θ₁ > 0; with S(0) < 0 both reduce to |ü_h| reaching the threshold at ü_v.
  return std::abs(ground.horizontal_m_s2) < uplift_threshold_m_s2(ground.vertical_m_s2);
}

bool Scene::acceleration(double theta1, double omega1, GroundAcceleration ground, int side,
                         double& theta1_ddot) const {
  EomTerms t;
  if (!terms(theta1, side, t)) return false;
  theta1_ddot = (t.S * ground.horizontal_m_s2 - t.J * omega1 * omega1 -
                 t.G * (gravity_m_s2() + ground.vertical_m_s2) - t.K) /
                t.I;
  return true;
}

double Scene::rest_acceleration(GroundAcceleration ground, int side) const {
  const double s = side < 0 ? -1.0 : 1.0;
  // On side +1, G and K change sign and S does not (odd dynamics).
  return (rest_.S * ground.horizontal_m_s2 + s * (rest_.G * (gravity_m_s2() + ground.vertical_m_s2) + rest_.K)) /
         rest_.I;
}

}  // namespace pcrf
