// Chebyshev tabulation of the coefficients of Eq. (31), cell by cell, on first use.
#include "pcrf/model/eom_table.hpp"

#include <cmath>
#include <numbers>

#include "pcrf/record/ground_motion.hpp"

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

bool EomTable::acceleration(double theta1, double omega1, double ground_accel_m_s2, int side,
                            double& theta1_ddot) const {
  const double u = side < 0 ? -theta1 : theta1;  // distance into the branch
  const double k = std::floor(u * inv_cell_) + 1.0;
  if (k < 0.0 || k >= static_cast<double>(cells_.size()))
    return eom_.acceleration(theta1, omega1, ground_accel_m_s2, side, theta1_ddot);
  const int index = static_cast<int>(k);
  Cell& cell = cells_[static_cast<std::size_t>(index)];
  if (cell.state == Cell::State::kEmpty) build(cell, index);
  if (cell.state == Cell::State::kExact)
    return eom_.acceleration(theta1, omega1, ground_accel_m_s2, side, theta1_ddot);
  const double x = 2.0 * (u - (index - 1) * cell_rad_) * inv_cell_ - 1.0;
  const double I = clenshaw(cell.c.I, x), J = clenshaw(cell.c.J, x), Q = clenshaw(cell.c.Q, x),
               S = clenshaw(cell.c.S, x);
  // Side +1 is the odd mirror: J, G, K change sign, I and S do not (equation_of_motion.hpp).
  const double s = side < 0 ? 1.0 : -1.0;
  theta1_ddot = (S * ground_accel_m_s2 - s * J * omega1 * omega1 - s * Q) / I;
  return true;
}

}  // namespace pcrf
