// Equation of motion (31) from the exact four-bar kinematics; energy and tendons.
#include "pcrf/model/equation_of_motion.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

#include <boost/math/tools/toms748_solve.hpp>

#include "pcrf/model/impact.hpp"
#include "pcrf/units.hpp"

namespace pcrf {
namespace {

double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }

// Added elongations on the θ₁ ≤ 0 branch (MODEL.md, erratum 1: 2b|sin(θ/2)|) and their
// θ₁-derivatives.
struct Elongations {
  double cL, cR, b;     // [m]
  double dcL, dcR, db;  // [m/rad]
};

Elongations elongations(const Frame& f, const Configuration& c) {
  const double t1 = c.theta1, t2 = c.theta2, t3 = c.theta3;
  Elongations e{};
  e.cL = -2.0 * f.b * std::sin(0.5 * t1);
  e.cR = -2.0 * f.b * std::sin(0.5 * t3);
  e.b = 2.0 * f.h_b * (std::sin(0.5 * (t2 - t1)) + std::sin(0.5 * (t2 - t3)));
  e.dcL = -f.b * std::cos(0.5 * t1);
  e.dcR = -f.b * std::cos(0.5 * t3) * c.d_theta3;
  e.db = f.h_b * (std::cos(0.5 * (t2 - t1)) * (c.d_theta2 - 1.0) +
                  std::cos(0.5 * (t2 - t3)) * (c.d_theta2 - c.d_theta3));
  return e;
}

}  // namespace

EquationOfMotion::EquationOfMotion(const Frame& frame) : frame_(frame), four_bar_(frame) {
  settle_rest();
  restitution_ = restitution_momentum(*this);
}

bool EquationOfMotion::negative_branch_terms(double phi, EomTerms& out, Configuration& c) const {
  if (!four_bar_.solve(phi, c)) return false;
  const Frame& f = frame_;
  double I = 0, dI = 0, G = 0, S = 0;
  auto add = [&](const BodyMotion& m, double mass, double inertia_G) {
    I += mass * dot(m.dp, m.dp) + inertia_G * m.dphi * m.dphi;
    dI += 2.0 * (mass * dot(m.dp, m.ddp) + inertia_G * m.dphi * m.ddphi);
    G += mass * m.dp.y;
    S -= mass * m.dp.x;
  };
  add(c.left, f.m_c, f.I_c_G);
  add(c.beam, f.m_b, f.I_b_G);
  add(c.right, f.m_c, f.I_c_G);
  const Elongations e = elongations(f, c);
  out.I = I;
  out.J = 0.5 * dI;
  out.G = G;
  out.S = S;
  // k (e + e₀) written as k e + P₀ (k e₀ = P₀): also right for a tendon of no stiffness
  // that carries a force (the constant-force limit), where e₀ is undefined.
  out.K = (f.k_b * e.b + f.P_b0) * e.db + (f.k_c * e.cL + f.P_c0) * e.dcL + (f.k_c * e.cR + f.P_c0) * e.dcR;
  return true;
}

bool EquationOfMotion::terms(double theta1, int side, EomTerms& out) const {
  Configuration c;
  if (side < 0) return negative_branch_terms(theta1, out, c);
  if (!negative_branch_terms(-theta1, out, c)) return false;
  out.J = -out.J;
  out.G = -out.G;
  out.K = -out.K;
  return true;
}

double EquationOfMotion::energy(double theta1, double omega1, int side) const {
  Configuration c;
  const double phi = side < 0 ? theta1 : -theta1;
  if (!four_bar_.solve(phi, c)) return std::numeric_limits<double>::quiet_NaN();
  const Frame& f = frame_;
  double I = 0;
  auto inertia = [&](const BodyMotion& m, double mass, double inertia_G) {
    I += mass * dot(m.dp, m.dp) + inertia_G * m.dphi * m.dphi;
  };
  inertia(c.left, f.m_c, f.I_c_G);
  inertia(c.beam, f.m_b, f.I_b_G);
  inertia(c.right, f.m_c, f.I_c_G);
  const double V_F = f.gravity_m_s2 * (f.m_c * c.left.p.y + f.m_b * c.beam.p.y + f.m_c * c.right.p.y);
  const Elongations e = elongations(f, c);
  // ½ k (e + e₀)² = ½ k e² + P₀ e + ½ P₀ e₀: the same form as K.
  auto tendon = [](double k, double P0, double e0, double ext) { return 0.5 * k * ext * ext + P0 * ext + 0.5 * P0 * e0; };
  const double V_T = tendon(f.k_b, f.P_b0, f.e_b0, e.b) + tendon(f.k_c, f.P_c0, f.e_c0, e.cL) +
                     tendon(f.k_c, f.P_c0, f.e_c0, e.cR);
  return 0.5 * I * omega1 * omega1 + V_F + V_T;
}

TendonState EquationOfMotion::tendons(double theta1, int side) const {
  Configuration c;
  const double phi = side < 0 ? theta1 : -theta1;
  TendonState s;
  if (!four_bar_.solve(phi, c)) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    s.strain_column_left = s.strain_column_right = s.strain_beam = nan;
    s.e_column_left_m = s.e_column_right_m = s.e_beam_m = nan;
    return s;
  }
  const Elongations e = elongations(frame_, c);
  // On side +1 the reference column (the one θ₁ follows) is the physical right one.
  s.e_column_left_m = side < 0 ? e.cL : e.cR;
  s.e_column_right_m = side < 0 ? e.cR : e.cL;
  s.e_beam_m = e.b;
  const Frame& f = frame_;
  s.strain_column_left = (s.e_column_left_m + f.e_c0) / f.len_c;
  s.strain_column_right = (s.e_column_right_m + f.e_c0) / f.len_c;
  s.strain_beam = (s.e_beam_m + f.e_b0) / f.len_b;
  return s;
}

bool EquationOfMotion::configuration(double theta1, int side, double& theta2, double& theta3) const {
  Configuration c;
  const double phi = side < 0 ? theta1 : -theta1;
  if (!four_bar_.solve(phi, c)) return false;
  theta2 = side < 0 ? c.theta2 : -c.theta2;
  theta3 = side < 0 ? c.theta3 : -c.theta3;
  return true;
}

TendonState EquationOfMotion::peak_tendon_strains(double abs_theta_rad) const {
  // Elongations grow with |θ₁| in practice; where they do not (far beyond any fracture
  // strain) a scan of the visited range, refined by golden-section search around the
  // best sample, finds each tendon's own maximum.
  const int n = 64;
  // One scan serves the three tendons: the state at each sample, and the last at the end.
  std::array<TendonState, n + 1> scan;
  for (int i = 0; i < n; ++i) scan[static_cast<std::size_t>(i)] = tendons(-(abs_theta_rad * i / n), -1);
  scan[n] = tendons(-abs_theta_rad, -1);
  auto peak_of = [&](double TendonState::*member) {
    auto f = [&](double a) { return tendons(-a, -1).*member; };
    int best = n;
    double best_value = scan[n].*member;
    for (int i = 0; i < n; ++i) {
      const double v = scan[static_cast<std::size_t>(i)].*member;
      if (v > best_value) best_value = v, best = i;
    }
    if (best == n) return best_value;  // monotone case: the end of the range
    double lo = abs_theta_rad * std::max(0, best - 1) / n, hi = abs_theta_rad * (best + 1) / n;
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    for (int k = 0; k < 60; ++k) {
      const double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
      (f(a) > f(b) ? hi : lo) = (f(a) > f(b) ? b : a);
    }
    return std::max(best_value, f(0.5 * (lo + hi)));
  };
  TendonState peak = scan[n];
  peak.strain_column_left = peak_of(&TendonState::strain_column_left);
  peak.strain_column_right = peak_of(&TendonState::strain_column_right);
  peak.strain_beam = peak_of(&TendonState::strain_beam);
  return peak;
}

double EquationOfMotion::strain_excess(double theta_abs_rad, double fracture_strain) const {
  // A tendon with no stiffness is no tendon: it cannot fracture.
  const double none = -std::numeric_limits<double>::infinity();
  const bool has_column = frame_.EA_c > 0.0, has_beam = frame_.EA_b > 0.0;
  // At rest θ₁ = +0, whose configuration the linkage keeps (−0 gives the same strains).
  const TendonState t = tendons(theta_abs_rad == 0.0 ? 0.0 : -theta_abs_rad, -1);
  return std::max(has_column ? t.strain_column_max() : none, has_beam ? t.strain_beam : none) - fracture_strain;
}

bool EquationOfMotion::broken_at_rest(double fracture_strain) const { return strain_excess(0.0, fracture_strain) >= 0.0; }

double EquationOfMotion::fracture_angle_rad(double fracture_strain) const {
  // Strain grows with |θ₁| on the physical range; bisect on the first crossing found by a
  // coarse scan so that a non-monotone tail near the closing limit cannot fool us.
  auto excess = [&](double a) { return strain_excess(a, fracture_strain); };
  if (broken_at_rest(fracture_strain)) return 0.0;
  const double limit = closing_limit_rad();
  const int n = 100;
  double lo = 0.0;
  double excess_lo = excess(lo);
  for (int i = 1; i <= n; ++i) {
    double hi = limit * i / n;
    const double excess_hi = excess(hi);
    if (excess_hi >= 0.0) {
      if (excess_hi == 0.0) return hi;
      // TOMS 748 (Alefeld, Potra & Shi 1995) on the bracket, to the last bit: about ten
      // evaluations where bisection takes fifty. The far end (strain reached) is returned.
      std::uintmax_t iterations = 100;
      const auto bracket = boost::math::tools::toms748_solve(excess, lo, hi, excess_lo, excess_hi,
                                                             boost::math::tools::eps_tolerance<double>(52), iterations);
      return excess(bracket.first) >= 0.0 ? bracket.first : bracket.second;
    }
    lo = hi;
    excess_lo = excess_hi;
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace pcrf
