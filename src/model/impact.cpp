// Coefficient of restitution: the 5×5 momentum balance and the paper's closed form.
#include "pcrf/model/impact.hpp"

#include "pcrf/user_error.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>

namespace pcrf {
namespace {

// z-component of a × b (counter-clockwise positive).
double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
Vec2 sub(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }

// Velocity of one body per unit θ̇₁: centre velocity and clockwise angular velocity.
struct UnitVelocity {
  Vec2 v;
  double omega_cw;
  Vec2 centre;
};

// Angular momentum (counter-clockwise positive) about point P of body moving with unit
// velocity u scaled by s: m (c − P) × v − I^G ω_cw.
double angular_momentum(const UnitVelocity& u, double mass, double inertia_G, Vec2 P) {
  return mass * cross(sub(u.centre, P), u.v) - inertia_G * u.omega_cw;
}

/// A frame whose impact neither the momentum balance nor its closed form can compute.
UserError singular_impact() {
  return UserError(
      "impossible frame: its impact's momentum equations are singular in double precision (the "
      "beam to column mass ratio kappa, or another ratio, is too far from 1)");
}

}  // namespace

double restitution_momentum(const EquationOfMotion& eom) {
  const Frame& f = eom.frame();
  Configuration c;
  if (!eom.linkage().solve(0.0, c)) throw std::runtime_error("restitution: linkage does not close at rest");

  // Before: branch θ₁ ≤ 0 at 0⁻, per unit θ̇₁⁻.
  const UnitVelocity L_before{c.left.dp, c.left.dphi, c.left.p};
  const UnitVelocity B_before{c.beam.dp, c.beam.dphi, c.beam.p};
  const UnitVelocity R_before{c.right.dp, c.right.dphi, c.right.p};
  // After: the mirror image about x = L + b. The physical left column plays the role of
  // the negative branch's right column and vice versa; x-velocities and angular
  // velocities change sign under the mirror, and dθ/dθ₁ of the mirrored branch at 0⁺
  // equals that of the negative branch at 0⁻ with the roles swapped. Per unit θ̇₁⁺:
  auto mirrored = [](const BodyMotion& m, Vec2 centre) {
    return UnitVelocity{{m.dp.x, -m.dp.y}, m.dphi, centre};
  };
  const UnitVelocity L_after = mirrored(c.right, c.left.p);
  const UnitVelocity B_after = mirrored(c.beam, c.beam.p);
  const UnitVelocity R_after = mirrored(c.left, c.right.p);

  const Vec2 A1{2.0 * f.b, 0.0};                 // A': new pivot of the left column
  const Vec2 D1{2.0 * f.L + 2.0 * f.b, 0.0};     // D': new pivot of the right column
  const Vec2 B1{2.0 * f.b, 2.0 * f.h};           // B': left joint corner after impact
  const Vec2 C1{2.0 * f.L, 2.0 * f.h_prime};     // C': right joint corner after impact

  // Unknowns x = (I_Ax, I_Ay, I_Dx, I_Dy, θ̇₁⁺) with θ̇₁⁻ = 1: momentum after − before =
  // impulses (and their moments).
  Eigen::Matrix<double, 5, 5> M = Eigen::Matrix<double, 5, 5>::Zero();
  Eigen::Matrix<double, 5, 1> rhs;
  const double mc = f.m_c, mb = f.m_b, Ic = f.I_c_G, Ib = f.I_b_G;

  // Linear momentum, x and y.
  M(0, 0) = 1.0; M(0, 2) = 1.0;
  M(0, 4) = -(mc * L_after.v.x + mb * B_after.v.x + mc * R_after.v.x);
  rhs(0) = -(mc * L_before.v.x + mb * B_before.v.x + mc * R_before.v.x);
  M(1, 1) = 1.0; M(1, 3) = 1.0;
  M(1, 4) = -(mc * L_after.v.y + mb * B_after.v.y + mc * R_after.v.y);
  rhs(1) = -(mc * L_before.v.y + mb * B_before.v.y + mc * R_before.v.y);

  // Angular momentum of the whole frame about A': the impulse at A' has no moment.
  const Vec2 rD = sub(D1, A1);
  M(2, 2) = -rD.y; M(2, 3) = rD.x;  // (D' − A') × I_D
  M(2, 4) = -(angular_momentum(L_after, mc, Ic, A1) + angular_momentum(B_after, mb, Ib, A1) +
              angular_momentum(R_after, mc, Ic, A1));
  rhs(2) = -(angular_momentum(L_before, mc, Ic, A1) + angular_momentum(B_before, mb, Ib, A1) +
             angular_momentum(R_before, mc, Ic, A1));

  // Left column about B': the joint impulse acts at B' and has no moment.
  const Vec2 rA = sub(A1, B1);
  M(3, 0) = -rA.y; M(3, 1) = rA.x;
  M(3, 4) = -angular_momentum(L_after, mc, Ic, B1);
  rhs(3) = -angular_momentum(L_before, mc, Ic, B1);

  // Right column about C'.
  const Vec2 rDC = sub(D1, C1);
  M(4, 2) = -rDC.y; M(4, 3) = rDC.x;
  M(4, 4) = -angular_momentum(R_after, mc, Ic, C1);
  rhs(4) = -angular_momentum(R_before, mc, Ic, C1);

  const auto qr = M.colPivHouseholderQr();
  if (qr.rank() == 5) return qr.solve(rhs)(4);
  // A beam some 10^10 times heavier or lighter than the columns: the rows differ by more than
  // double precision resolves, and the QR calls the system rank-deficient. Eq. (42) with
  // erratum 3 is the same balance solved by hand (the tests hold the two within 1e-12 over
  // the ordinary frames); its terms scale together with kappa, so it stays exact there.
  const double r = restitution_closed_form(eom);
  if (!(r > 0.0 && r < 1.0)) throw singular_impact();
  return r;
}

double restitution_closed_form(const EquationOfMotion& eom, LambdaLSign sign) {
  const FrameParameters p = eom.frame().parameters();
  Configuration c;
  if (!eom.linkage().solve(0.0, c)) throw std::runtime_error("restitution: linkage does not close at rest");
  const double l13 = c.d_theta3;
  const double lL = sign == LambdaLSign::kCorrected ? -c.d_theta2 : c.d_theta2;  // erratum 3
  const double ta = p.tan_alpha, ta2 = ta * ta, lam = p.lambda, lh = p.lambda_h, lH = 1.0 - lh;
  const double k = p.kappa;
  const double common = lh * lh + lam * lam - 2.0 * lam * ta + ta2;
  const double c1 = ta * (2.0 * (1.0 + l13) * (2.0 - ta2) + 6.0 * l13 * lam * ta - lL * k * common +
                          3.0 * k * (4.0 * lH - 2.0 * lH * lh - 2.0 * lh * lL + lh * lh * lL + ta * lam - ta2));
  const double c2 = ta * (4.0 * (1.0 + l13) * (1.0 + ta2) - 6.0 * lam * ta - lL * k * common +
                          3.0 * k * (4.0 * lH - 2.0 * lH * lh - 2.0 * lh * lL + lh * lh * lL - ta * lam + ta2));
  const double c3 = 2.0 * lam * l13 * (3.0 * lh - 1.0 + 2.0 * ta2);
  const double c4 = 2.0 * lam * (3.0 * lh - 1.0 - ta2);
  const double c5 = 6.0 * lam * lH * ((1.0 + l13) + k * (2.0 * lH - lh * lL));
  const double c6 = 2.0 * lam * lH * (1.0 + ta2);
  const double c7 = 2.0 * lam * lH * l13 * (1.0 - 2.0 * ta2);
  return (c1 - c3 - c5 + c6) / (c2 - c4 - c5 + c7);
}

}  // namespace pcrf
