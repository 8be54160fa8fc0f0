// Chebyshev tabulation of the coefficients of Eq. (31), cell by cell, on first use.
#include "pcrf/model/eom_table.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "pcrf/units.hpp"

namespace pcrf {
namespace {

// Chebyshev coefficients of f sampled at the nodes x_j = cos(π (j + ½)/n).
template <std::size_t N>
std::array<double, N> chebyshev_fit(const std::array<double, N>& f) {
  std::array<double, N> c{};
  const double n = static_cast<double>(N);
  for (std::size_t k = 0; k < N; ++k) {
    double sum = 0.0;
    for (std::size_t j = 0; j < N; ++j)
      sum += f[j] * std::cos(std::numbers::pi * static_cast<double>(k) * (static_cast<double>(j) + 0.5) / n);
    c[k] = 2.0 * sum / n;
  }
  c[0] *= 0.5;
  return c;
}

// Coefficients of d/dx Σ c_k T_k(x): c'_{k−1} = c'_{k+1} + 2k c_k, c'_0 halved.
template <std::size_t N>
std::array<double, N> chebyshev_derivative(const std::array<double, N>& c) {
  std::array<double, N + 1> d{};
  for (std::size_t k = N - 1; k >= 1; --k) d[k - 1] = d[k + 1] + 2.0 * static_cast<double>(k) * c[k];
  d[0] *= 0.5;
  std::array<double, N> out{};
  for (std::size_t k = 0; k < N; ++k) out[k] = d[k];
  return out;
}

// Σ c_k T_k(x) by Clenshaw's recurrence.
template <std::size_t N>
double clenshaw(const std::array<double, N>& c, double x) {
  double b1 = 0.0, b2 = 0.0;
  for (std::size_t k = N - 1; k >= 1; --k) {
    const double b0 = 2.0 * x * b1 - b2 + c[k];
    b2 = b1;
    b1 = b0;
  }
  return x * b1 - b2 + c[0];
}

}  // namespace

EomTable::EomTable(const EquationOfMotion& eom, double cell_rad)
    : eom_(eom), cell_rad_(cell_rad), inv_cell_(1.0 / cell_rad) {
  // Cell k ≥ 1 covers u = −φ ∈ [(k−1)w, k·w); cell 0 covers a small overshoot φ ∈ (0, w].
  cells_.resize(static_cast<std::size_t>(eom.closing_limit_rad() * inv_cell_) + 2);
}

bool EomTable::negative_branch(double phi, double& I, double& J, double& Q, double& S) const {
  EomTerms t;
  if (!eom_.terms(phi, -1, t)) return false;
  I = t.I;
  J = t.J;
  Q = t.G * kGravity_m_s2 + t.K;
  S = t.S;
  return true;
}

void EomTable::build(Cell& cell, int index) const {
  ++built_;
  cell.state = Cell::State::kExact;
  const double u0 = (index - 1) * cell_rad_;  // cell spans u ∈ [u0, u0 + w]
  std::array<double, kNodes> I{}, J{}, Q{}, S{};
  for (int j = 0; j < kNodes; ++j) {
    const double x = std::cos(std::numbers::pi * (j + 0.5) / kNodes);
    const double u = u0 + 0.5 * (x + 1.0) * cell_rad_;
    if (!negative_branch(-u, I[j], J[j], Q[j], S[j])) return;
  }
  cell.c = {chebyshev_fit(I), chebyshev_fit(J), chebyshev_fit(Q), chebyshev_fit(S)};
  cell.dc = {chebyshev_derivative(cell.c.I), chebyshev_derivative(cell.c.J), chebyshev_derivative(cell.c.Q),
             chebyshev_derivative(cell.c.S)};
  // Self-check at two points between the nodes.
  for (const double x : {0.31, -0.77}) {
    const double u = u0 + 0.5 * (x + 1.0) * cell_rad_;
    double i = 0, jj = 0, q = 0, s = 0;
    if (!negative_branch(-u, i, jj, q, s)) return;
    auto close = [](double a, double b, double scale) { return std::abs(a - b) <= 1e-11 * scale; };
    const double qs = std::abs(q) + std::abs(s) * kGravity_m_s2;  // Q is compared with S·g
    if (!close(clenshaw(cell.c.I, x), i, std::abs(i)) || !close(clenshaw(cell.c.J, x), jj, std::abs(i)) ||
        !close(clenshaw(cell.c.Q, x), q, qs) || !close(clenshaw(cell.c.S, x), s, std::abs(s)))
      return;
  }
  cell.state = Cell::State::kTabulated;
}

const EomTable::Cell* EomTable::locate(double theta1, int side, double& x) const {
  const double u = side < 0 ? -theta1 : theta1;  // distance into the branch
  const double k = std::floor(u * inv_cell_) + 1.0;
  if (k < 0.0 || k >= static_cast<double>(cells_.size())) return nullptr;
  const int index = static_cast<int>(k);
  Cell& cell = cells_[static_cast<std::size_t>(index)];
  if (cell.state == Cell::State::kEmpty) build(cell, index);
  if (cell.state == Cell::State::kExact) return nullptr;
  x = 2.0 * (u - (index - 1) * cell_rad_) * inv_cell_ - 1.0;
  return &cell;
}

bool EomTable::acceleration(double theta1, double omega1, double ground_accel_m_s2, int side,
                            double& theta1_ddot) const {
  double x = 0;
  const Cell* cell = locate(theta1, side, x);
  if (cell == nullptr) return eom_.acceleration(theta1, omega1, ground_accel_m_s2, side, theta1_ddot);
  const double I = clenshaw(cell->c.I, x), J = clenshaw(cell->c.J, x), Q = clenshaw(cell->c.Q, x),
               S = clenshaw(cell->c.S, x);
  // Side +1 is the odd mirror: J, G, K change sign, I and S do not (equation_of_motion.hpp).
  const double s = side < 0 ? 1.0 : -1.0;
  theta1_ddot = (S * ground_accel_m_s2 - s * J * omega1 * omega1 - s * Q) / I;
  return true;
}

bool EomTable::acceleration_jacobian(double theta1, double omega1, double ground_accel_m_s2, int side,
                                     double& theta1_ddot, double& d_theta, double& d_omega) const {
  double x = 0;
  const Cell* cell = locate(theta1, side, x);
  if (cell == nullptr) {
    // Exact terms (near the closing limit): central difference with a step well above
    // round-off of the exact terms, which keep the θ₁-dependence at full precision.
    const double h = 1e-7 * std::max(1.0, std::abs(theta1));
    double up = 0, down = 0;
    if (!eom_.acceleration(theta1, omega1, ground_accel_m_s2, side, theta1_ddot) ||
        !eom_.acceleration(theta1 + h, omega1, ground_accel_m_s2, side, up) ||
        !eom_.acceleration(theta1 - h, omega1, ground_accel_m_s2, side, down))
      return false;
    d_theta = (up - down) / (2.0 * h);
    EomTerms t;
    eom_.terms(theta1, side, t);
    d_omega = -2.0 * t.J * omega1 / t.I;
    return true;
  }
  const double I = clenshaw(cell->c.I, x), J = clenshaw(cell->c.J, x), Q = clenshaw(cell->c.Q, x),
               S = clenshaw(cell->c.S, x);
  const double s = side < 0 ? 1.0 : -1.0;
  const double num = S * ground_accel_m_s2 - s * J * omega1 * omega1 - s * Q;
  theta1_ddot = num / I;
  // d/du = (2/w) d/dx, and u = −θ₁ on side −1, +θ₁ on side +1.
  const double du_dx = 2.0 * inv_cell_ * (side < 0 ? -1.0 : 1.0);
  const double dI = clenshaw(cell->dc.I, x), dJ = clenshaw(cell->dc.J, x), dQ = clenshaw(cell->dc.Q, x),
               dS = clenshaw(cell->dc.S, x);
  const double dnum = dS * ground_accel_m_s2 - s * dJ * omega1 * omega1 - s * dQ;
  d_theta = du_dx * (dnum * I - num * dI) / (I * I);
  d_omega = -2.0 * s * J * omega1 / I;
  return true;
}

}  // namespace pcrf
