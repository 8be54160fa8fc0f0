// Housner's block and the Makris–Vassiliou rocking frame (see rigid_rocker.hpp).
#include "pcrf/model/rigid_rocker.hpp"

#include <array>
#include <utility>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "pcrf/user_error.hpp"

namespace pcrf {
namespace {

/// rocker_sincos's and rigid_rocker_acceleration's operations on one double.
struct ScalarOps {
  static double select(bool m, double a, double b) { return m ? a : b; }
  static void sincos(double x, double& s, double& c) { rocker_sincos<ScalarOps>(x, s, c); }
};

/// `problem(value)` is formatted only when the check fails (a study builds a scene per case).
void check(bool ok, const char* key, const char* problem, double value) {
  if (!ok) throw UserError(key, problem + (", got " + std::to_string(value)));
}

}  // namespace

double RigidRocker::restitution_from_momentum(double alpha, double gamma) {
  const double s = std::sin(alpha);
  return (1.0 - 1.5 * s * s + 3.0 * gamma * std::cos(2.0 * alpha)) / (1.0 + 3.0 * gamma);
}

RigidRocker::RigidRocker(const RockerParameters& p) : p_(p) {
  check(p.slenderness_rad > 0.0 && p.slenderness_rad < 0.5 * std::numbers::pi, "slenderness_rad",
        "must lie between 0 and pi/2 (a column wider than tall is not a rocking column)", p.slenderness_rad);
  check(p.size_m > 0.0 && std::isfinite(p.size_m), "size_m", "must be positive", p.size_m);
  check(p.beam_mass_ratio >= 0.0 && std::isfinite(p.beam_mass_ratio), "beam_mass_ratio", "must not be negative",
        p.beam_mass_ratio);
  if (!(p.gravity_m_s2 > 0.0)) throw UserError("gravity_m_s2", "must be positive");
  restitution_ = p.restitution ? *p.restitution : restitution_from_momentum(p.slenderness_rad, p.beam_mass_ratio);
  check(restitution_ >= 0.0 && restitution_ <= 1.0, "restitution", "must lie in [0, 1]", restitution_);
  inertia_m2_ = p.size_m * p.size_m * (4.0 / 3.0 + 4.0 * p.beam_mass_ratio);
  moment_over_inertia_per_m_ = (1.0 + 2.0 * p.beam_mass_ratio) * p.size_m / inertia_m2_;
  ScalarOps::sincos(p.slenderness_rad, sin_alpha_, cos_alpha_);
  settle_rest();
}

bool RigidRocker::terms(double theta1, int side, EomTerms& out) const {
  // The branch θ ≤ 0 at φ = θ (side −1) or φ = −θ (side +1), then the odd mirror.
  const double phi = side < 0 ? theta1 : -theta1;
  const double c = 1.0 + 2.0 * p_.beam_mass_ratio, R = p_.size_m;
  out.I = inertia_m2_;
  out.J = 0.0;
  out.K = 0.0;
  double sin_a, cos_a;
  ScalarOps::sincos(p_.slenderness_rad + phi, sin_a, cos_a);
  out.G = -c * R * sin_a;
  out.S = -c * R * cos_a;
  if (side > 0) out.G = -out.G;
  return true;
}


bool RigidRocker::acceleration(double theta1, double, GroundAcceleration ground, int side,
                               double& theta1_ddot) const {
  theta1_ddot = rigid_rocker_acceleration<ScalarOps>(moment_over_inertia_per_m_, p_.slenderness_rad, p_.gravity_m_s2,
                                                     theta1, side < 0, ground.horizontal_m_s2, ground.vertical_m_s2);
  return true;
}

namespace {

/// What the series of one rigid rocker needs: the factor, the slenderness, and the ground
/// on the side's sign (σ(g + v0), σ v1, h0, h1).
struct SeriesInput {
  double k_inertia, alpha, sigma, g0, g1, h0, h1;
  double sin_alpha, cos_alpha;  ///< sin and cos of x at θ₁ = 0 (α + σ·0 is α)
};

/// Two doubles in one register (GCC/Clang vector extensions: SSE2 on x86-64, Advanced SIMD
/// on arm64): a pair (S_k, C_k) of the series of sin x and cos x, computed together.
using Pair = double __attribute__((vector_size(16)));

/// The recurrences of RigidRocker::taylor_series to order N, with N known to the compiler
/// (its loops unrolled). With x = α + σθ₁ and x_j its coefficients, k S_k = Σ j x_j C_{k−j}
/// and k C_k = −Σ j x_j S_{k−j} (j = 1 … k): one sum of pairs, P_k = (S_k, C_k) =
/// (1/k) Σ j x_j Q_{k−j} with Q = (C, −S). Each lane rounds as the scalar sums would.
template <int N>
bool series_of_order(const SeriesInput& in, double theta1, double omega1, double* a) {
  Pair p[N + 1], q[N + 1];  // P_k = (S_k, C_k), Q_k = (C_k, −S_k)
  double jx[N + 1];         // j·x_j
  a[0] = theta1;
  a[1] = omega1;
  double s0, c0;
  if (theta1 == 0.0) {  // a flight leaving an impact
    s0 = in.sin_alpha, c0 = in.cos_alpha;
  } else {
    ScalarOps::sincos(in.alpha + in.sigma * theta1, s0, c0);  // the acceleration's own sin/cos
  }
  p[0] = Pair{s0, c0}, q[0] = Pair{c0, -s0};
  jx[1] = in.sigma * omega1;
  a[2] = 0.5 * in.k_inertia * (in.g0 * s0 - in.h0 * c0);
  // f_k = g0 S_k + g1 S_{k−1} − (h0 C_k + h1 C_{k−1}): the lanes of w0 P_k + w1 P_{k−1}, added.
  const Pair w0{in.g0, -in.h0}, w1{in.g1, -in.h1};
#pragma GCC unroll 32
  for (int k = 1; k + 2 <= N; ++k) {
    jx[k + 1] = in.sigma * (k + 1.0) * a[k + 1];
    Pair sum{0.0, 0.0};
#pragma GCC unroll 32
    for (int j = 1; j <= k; ++j) sum += jx[j] * q[k - j];
    p[k] = sum * (1.0 / k);
    q[k] = Pair{p[k][1], -p[k][0]};
    const Pair f = w0 * p[k] + w1 * p[k - 1];
    a[k + 2] = in.k_inertia * (f[0] + f[1]) * (1.0 / ((k + 1.0) * (k + 2.0)));
  }
  double sum = 0.0;  // finite when every coefficient is (inf − inf and NaN are NaN)
#pragma GCC unroll 32
  for (int k = 2; k <= N; ++k) sum += a[k];
  return std::isfinite(sum);
}

/// The kernel of order N: constants (k_inertia, α, σ, g, sin α, cos α) and the ground on the
/// side's sign make the SeriesInput.
template <int N>
bool kernel_of_order(const double* c, double theta1, double omega1, const GroundLine& ground, double* a) {
  const double sigma = c[2];
  const SeriesInput in{c[0],  c[1], sigma, sigma * (c[3] + ground.v0_m_s2), sigma * ground.v1_m_s3, ground.h0_m_s2,
                       ground.h1_m_s3, c[4], c[5]};
  return series_of_order<N>(in, theta1, omega1, a);
}

template <int... N>
constexpr std::array<TaylorKernel::Series, sizeof...(N)> kernel_table(std::integer_sequence<int, N...>) {
  return {&kernel_of_order<N + 1>...};
}
/// kernel_of_order<n> at [n − 1], n = 1 … kTaylorOrderMax.
constexpr auto kKernels = kernel_table(std::make_integer_sequence<int, RigidRocker::kTaylorOrderMax>{});

}  // namespace

TaylorKernel RigidRocker::taylor_kernel(int side, int order) const {
  if (order < 1 || order > kTaylorOrderMax) return {};
  const double sigma = side < 0 ? 1.0 : -1.0;
  return {kKernels[static_cast<std::size_t>(order - 1)],
          {moment_over_inertia_per_m_, p_.slenderness_rad, sigma, p_.gravity_m_s2, sin_alpha_, cos_alpha_}};
}

bool RigidRocker::taylor_series(double theta1, double omega1, const GroundLine& ground, int side, int order,
                                double* a) const {
  const TaylorKernel kernel = taylor_kernel(side, order);
  return kernel.series != nullptr && kernel.series(kernel.constants.data(), theta1, omega1, ground, a);
}

double RigidRocker::overturn_angle_rad() const { return 0.5 * std::numbers::pi; }

double RigidRocker::closing_limit_rad() const { return 0.5 * std::numbers::pi; }

double RigidRocker::energy(double theta1, double omega1, int side) const {
  EomTerms t;
  terms(theta1, side, t);
  const double phi = side < 0 ? theta1 : -theta1;
  double sin_a, cos_a;
  ScalarOps::sincos(p_.slenderness_rad + phi, sin_a, cos_a);
  const double height = (1.0 + 2.0 * p_.beam_mass_ratio) * p_.size_m * cos_a;
  return 0.5 * t.I * omega1 * omega1 + p_.gravity_m_s2 * height;
}

}  // namespace pcrf
