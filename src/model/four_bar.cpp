// Four-bar kinematics of the rocking frame (θ₁ ≤ 0 branch): positions by circle
// intersection, derivatives by implicit differentiation of the loop closure.
#include "pcrf/model/four_bar.hpp"

#include <cmath>
#include <numbers>

namespace pcrf {
namespace {

// Clockwise rotation by θ: (x, y) → (x cos θ + y sin θ, −x sin θ + y cos θ).
Vec2 rot(double c, double s, Vec2 v) { return {v.x * c + v.y * s, -v.x * s + v.y * c}; }
// d/dθ Rot(θ)·v = Rot(θ)·(v.y, −v.x).
Vec2 drot(double c, double s, Vec2 v) { return rot(c, s, {v.y, -v.x}); }
Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
Vec2 operator*(double k, Vec2 a) { return {k * a.x, k * a.y}; }

}  // namespace

FourBar::FourBar(const Frame& frame)
    : f_(frame),
      r_beam_(2.0 * std::hypot(frame.L_b, frame.h_b)),
      r_right_(2.0 * frame.h) {
  rest_closes_ = solve_at(0.0, rest_);
}

bool FourBar::solve_at(double theta1, Configuration& out) const {
  const double c1 = std::cos(theta1), s1 = std::sin(theta1);
  const Vec2 AB0{2.0 * f_.b, 2.0 * f_.h_prime};
  const Vec2 B = rot(c1, s1, AB0);
  const Vec2 D{2.0 * f_.L, 0.0};

  // C: intersection of |C − B| = 2R_b and |C − D| = 2h on the upper side of BD.
  const Vec2 BD = D - B;
  const double d = std::hypot(BD.x, BD.y);
  const double a = (r_beam_ * r_beam_ - r_right_ * r_right_ + d * d) / (2.0 * d);
  const double h2 = r_beam_ * r_beam_ - a * a;
  if (!(h2 > 0.0)) return false;
  const Vec2 e{BD.x / d, BD.y / d};
  const Vec2 n{-e.y, e.x};
  const Vec2 C = B + a * e + std::sqrt(h2) * n;

  const double theta3 = std::atan2(C.x - D.x, C.y - D.y);
  const double gamma = std::atan2(f_.h_b, f_.L_b);
  const double theta2 = gamma - std::atan2(C.y - B.y, C.x - B.x);

  const double c2 = std::cos(theta2), s2 = std::sin(theta2);
  const double c3 = std::cos(theta3), s3 = std::sin(theta3);
  const Vec2 u{2.0 * f_.L_b, 2.0 * f_.h_b};
  const Vec2 w{0.0, 2.0 * f_.h};

  // First derivatives: [Rot'(θ₂)u, −Rot'(θ₃)w]·(θ₂', θ₃') = −B'.
  const Vec2 col2 = drot(c2, s2, u);
  const Vec2 col3 = -1.0 * drot(c3, s3, w);
  const double det = col2.x * col3.y - col3.x * col2.y;
  if (!(std::abs(det) > 1e-12 * r_beam_ * r_right_)) return false;
  auto solve2 = [&](Vec2 rhs, double& x2, double& x3) {
    x2 = (rhs.x * col3.y - col3.x * rhs.y) / det;
    x3 = (col2.x * rhs.y - rhs.x * col2.y) / det;
  };
  const Vec2 dB = drot(c1, s1, AB0);
  double dt2 = 0, dt3 = 0;
  solve2(-1.0 * dB, dt2, dt3);
  // Second derivatives: same matrix; Rot'' = −Rot, so the right-hand side is
  // Rot(θ₁)·AB0 + Rot(θ₂)u·θ₂'² − Rot(θ₃)w·θ₃'².
  const Vec2 rhs2 = B + (dt2 * dt2) * rot(c2, s2, u) - (dt3 * dt3) * rot(c3, s3, w);
  double ddt2 = 0, ddt3 = 0;
  solve2(rhs2, ddt2, ddt3);

  out.theta1 = theta1;
  out.theta2 = theta2;
  out.theta3 = theta3;
  out.d_theta2 = dt2;
  out.d_theta3 = dt3;
  out.dd_theta2 = ddt2;
  out.dd_theta3 = ddt3;
  out.jacobian = det;

  // Centres of mass. Left column about A, beam from B, right column about D.
  const Vec2 gc{f_.b, f_.h};            // column centre relative to its pivot at rest
  const Vec2 gb{f_.L_b, f_.h_b};        // beam centre relative to B at rest
  out.left.p = rot(c1, s1, gc);
  out.left.dp = drot(c1, s1, gc);
  out.left.ddp = -1.0 * out.left.p;
  out.left.phi = theta1;
  out.left.dphi = 1.0;
  out.left.ddphi = 0.0;

  const Vec2 rb = rot(c2, s2, gb), drb = drot(c2, s2, gb);
  out.beam.p = B + rb;
  out.beam.dp = dB + dt2 * drb;
  out.beam.ddp = (-1.0 * B) - (dt2 * dt2) * rb + ddt2 * drb;
  out.beam.phi = theta2;
  out.beam.dphi = dt2;
  out.beam.ddphi = ddt2;

  const Vec2 rc = rot(c3, s3, gc), drc = drot(c3, s3, gc);
  out.right.p = D + rc;
  out.right.dp = dt3 * drc;
  out.right.ddp = -(dt3 * dt3) * rc + ddt3 * drc;
  out.right.phi = theta3;
  out.right.dphi = dt3;
  out.right.ddphi = ddt3;
  return true;
}

double FourBar::find_closing_limit() const {
  // Walk outwards from rest (steps of 20 mrad) to the first toggle, where beam and right
  // column align and the loop-closure Jacobian vanishes. Two shapes occur: the circles of
  // the closure stop meeting (solve fails: the usual case, then bisect on that), or they
  // touch at one angle and meet again, so |Jacobian| has a sharp local minimum at zero
  // (then locate it by golden section). π is beyond any physical sway.
  Configuration c;
  solve(0.0, c);
  const double rest = std::abs(c.jacobian);
  auto size = [&](double t) { return solve(t, c) ? std::abs(c.jacobian) / rest : -1.0; };
  const double step = 0.02;
  double prev2 = 1.0, prev = 1.0;
  for (double t = -step; t > -std::numbers::pi; t -= step) {
    const double now = size(t);
    if (now < 0.0) {  // does not close: bisect between the last good angle and t
      double good = t + step, bad = t;
      for (int i = 0; i < 60; ++i) {
        const double mid = 0.5 * (good + bad);
        if (mid == good || mid == bad) break;  // adjacent doubles: nothing left to halve
        (size(mid) >= 0.0 ? good : bad) = mid;
      }
      return good;
    }
    if (prev < prev2 && prev <= now && prev < 0.05) {  // local minimum of |J| around t + step
      double lo = t, hi = t + 2 * step;
      const double g = 0.5 * (std::sqrt(5.0) - 1.0);
      for (int i = 0; i < 80; ++i) {
        const double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
        (size(a) < size(b) ? hi : lo) = (size(a) < size(b) ? b : a);
      }
      const double t_min = 0.5 * (lo + hi);
      if (size(t_min) < 1e-6) return t_min;
    }
    prev2 = prev;
    prev = now;
  }
  return -std::numbers::pi;
}

}  // namespace pcrf
