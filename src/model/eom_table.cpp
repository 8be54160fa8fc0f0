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

// Four series at once, lane by lane: the arithmetic of clenshaw() on each, in an order a
// compiler vectorizes (the right-hand side's I, J, Q, S at one θ₁).
template <std::size_t N>
std::array<double, 4> clenshaw4(const std::array<std::array<double, 4>, N>& c, double x) {
  std::array<double, 4> b1{}, b2{}, out{};
  for (std::size_t k = N - 1; k >= 1; --k) {
    for (std::size_t l = 0; l < 4; ++l) {
      const double b0 = 2.0 * x * b1[l] - b2[l] + c[k][l];
      b2[l] = b1[l];
      b1[l] = b0;
    }
  }
  for (std::size_t l = 0; l < 4; ++l) out[l] = x * b1[l] - b2[l] + c[0][l];
  return out;
}

}  // namespace

EomTable::EomTable(const Scene& scene, double cell_rad)
    : eom_(scene), cell_rad_(cell_rad), inv_cell_(1.0 / cell_rad) {
  // Cell k ≥ 1 covers u = −φ ∈ [(k−1)w, k·w); cell 0 covers a small overshoot φ ∈ (0, w].
  // No cells for a scene whose exact terms are cheap: locate() then finds none.
  if (scene.worth_tabulating()) cells_.resize(static_cast<std::size_t>(scene.closing_limit_rad() * inv_cell_) + 2);
}

bool EomTable::negative_branch(double phi, Terms& out) const {
  EomTerms t;
  if (!eom_.terms(phi, -1, t)) return false;
  out = {t.I, t.J, t.G * eom_.gravity_m_s2() + t.K, t.S, t.G};
  return true;
}

[[gnu::noinline]] void EomTable::build(Cell& cell, int index) const {
  ++built_;
  cell.state = Cell::State::kExact;
  const double u0 = (index - 1) * cell_rad_;  // cell spans u ∈ [u0, u0 + w]
  std::array<double, kNodes> I{}, J{}, Q{}, S{}, G{};
  for (int j = 0; j < kNodes; ++j) {
    const double x = std::cos(std::numbers::pi * (j + 0.5) / kNodes);
    const double u = u0 + 0.5 * (x + 1.0) * cell_rad_;
    Terms t{};
    if (!negative_branch(-u, t)) return;
    I[j] = t.I, J[j] = t.J, Q[j] = t.Q, S[j] = t.S, G[j] = t.G;
  }
  cell.c = {chebyshev_fit(I), chebyshev_fit(J), chebyshev_fit(Q), chebyshev_fit(S), chebyshev_fit(G)};
  cell.dc = {chebyshev_derivative(cell.c.I), chebyshev_derivative(cell.c.J), chebyshev_derivative(cell.c.Q),
             chebyshev_derivative(cell.c.S), chebyshev_derivative(cell.c.G)};
  for (int k = 0; k < kNodes; ++k) {
    const auto j = static_cast<std::size_t>(k);
    cell.ijqs[j] = {cell.c.I[j], cell.c.J[j], cell.c.Q[j], cell.c.S[j]};
  }
  // Self-check at two points between the nodes.
  for (const double x : {0.31, -0.77}) {
    const double u = u0 + 0.5 * (x + 1.0) * cell_rad_;
    Terms t{};
    if (!negative_branch(-u, t)) return;
    auto close = [](double a, double b, double scale) { return std::abs(a - b) <= 1e-11 * scale; };
    const double g = eom_.gravity_m_s2();
    const double qs = std::abs(t.Q) + std::abs(t.S) * g;  // Q is compared with S·g
    // G·g is compared with the same scale: it enters as G·ü_v next to Q and S·ü_h.
    if (!close(clenshaw(cell.c.I, x), t.I, std::abs(t.I)) || !close(clenshaw(cell.c.J, x), t.J, std::abs(t.I)) ||
        !close(clenshaw(cell.c.Q, x), t.Q, qs) || !close(clenshaw(cell.c.S, x), t.S, std::abs(t.S)) ||
        !close(clenshaw(cell.c.G, x) * g, t.G * g, qs))
      return;
  }
  cell.state = Cell::State::kTabulated;
}

inline const EomTable::Cell* EomTable::locate(double theta1, int side, double& x) const {
  const double u = side < 0 ? -theta1 : theta1;  // distance into the branch
  const double v = u * inv_cell_;
  if (!(v >= -1.0 && v < static_cast<double>(cells_.size()))) return nullptr;  // also NaN
  // floor(v) + 1 without a libm call: truncation, one down for a negative fraction.
  auto whole = static_cast<long>(v);
  whole -= static_cast<long>(v < static_cast<double>(whole));
  const long index = whole + 1;
  if (index < 0 || index >= static_cast<long>(cells_.size())) return nullptr;
  Cell& cell = cells_[static_cast<std::size_t>(index)];
  if (cell.state == Cell::State::kEmpty) [[unlikely]] build(cell, static_cast<int>(index));
  if (cell.state == Cell::State::kExact) return nullptr;
  x = 2.0 * (u - static_cast<double>(index - 1) * cell_rad_) * inv_cell_ - 1.0;
  return &cell;
}

bool EomTable::acceleration(double theta1, double omega1, GroundAcceleration ground, int side,
                            double& theta1_ddot) const {
  double x = 0;
  const Cell* cell = locate(theta1, side, x);
  if (cell == nullptr) return eom_.acceleration(theta1, omega1, ground, side, theta1_ddot);
  const std::array<double, 4> ijqs = clenshaw4(cell->ijqs, x);
  const double I = ijqs[0], J = ijqs[1], S = ijqs[3];
  double Q = ijqs[2];
  if (ground.vertical_m_s2 != 0.0) Q += clenshaw(cell->c.G, x) * ground.vertical_m_s2;  // G (g + ü_v) + K
  // Side +1 is the odd mirror: J, G, K change sign, I and S do not (equation_of_motion.hpp).
  const double s = side < 0 ? 1.0 : -1.0;
  theta1_ddot = (S * ground.horizontal_m_s2 - s * J * omega1 * omega1 - s * Q) / I;
  return true;
}

bool EomTable::acceleration_jacobian(double theta1, double omega1, GroundAcceleration ground, int side,
                                     double& theta1_ddot, double& d_theta, double& d_omega) const {
  double x = 0;
  const Cell* cell = locate(theta1, side, x);
  if (cell == nullptr) {
    // Exact terms (near the closing limit): central difference with a step well above
    // round-off of the exact terms, which keep the θ₁-dependence at full precision.
    const double h = 1e-7 * std::max(1.0, std::abs(theta1));
    double up = 0, down = 0;
    if (!eom_.acceleration(theta1, omega1, ground, side, theta1_ddot) ||
        !eom_.acceleration(theta1 + h, omega1, ground, side, up) ||
        !eom_.acceleration(theta1 - h, omega1, ground, side, down))
      return false;
    d_theta = (up - down) / (2.0 * h);
    EomTerms t;
    eom_.terms(theta1, side, t);
    d_omega = -2.0 * t.J * omega1 / t.I;
    return true;
  }
  const double I = clenshaw(cell->c.I, x), J = clenshaw(cell->c.J, x), S = clenshaw(cell->c.S, x);
  double Q = clenshaw(cell->c.Q, x);
  const double a_v = ground.vertical_m_s2, a_h = ground.horizontal_m_s2;
  if (a_v != 0.0) Q += clenshaw(cell->c.G, x) * a_v;
  const double s = side < 0 ? 1.0 : -1.0;
  const double num = S * a_h - s * J * omega1 * omega1 - s * Q;
  theta1_ddot = num / I;
  // d/du = (2/w) d/dx, and u = −θ₁ on side −1, +θ₁ on side +1.
  const double du_dx = 2.0 * inv_cell_ * (side < 0 ? -1.0 : 1.0);
  const double dI = clenshaw(cell->dc.I, x), dJ = clenshaw(cell->dc.J, x), dS = clenshaw(cell->dc.S, x);
  double dQ = clenshaw(cell->dc.Q, x);
  if (a_v != 0.0) dQ += clenshaw(cell->dc.G, x) * a_v;
  const double dnum = dS * a_h - s * dJ * omega1 * omega1 - s * dQ;
  d_theta = du_dx * (dnum * I - num * dI) / (I * I);
  d_omega = -2.0 * s * J * omega1 / I;
  return true;
}

}  // namespace pcrf
