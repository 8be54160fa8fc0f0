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

// The power-series coefficients in x of Σ c_k T_k(x): T_{k+1} = 2x T_k − T_{k−1}, whose
// integer coefficients are exact in double for these degrees.
template <std::size_t N>
std::array<double, N> chebyshev_to_powers(const std::array<double, N>& c) {
  std::array<double, N> out{}, t_prev{}, t{};
  t_prev[0] = 1.0;  // T_0
  if constexpr (N > 1) t[1] = 1.0;  // T_1
  for (std::size_t i = 0; i < N; ++i) out[i] += c[0] * t_prev[i];
  for (std::size_t k = 1; k < N; ++k) {
    for (std::size_t i = 0; i < N; ++i) out[i] += c[k] * t[i];
    std::array<double, N> next{};
    for (std::size_t i = 0; i < N; ++i) next[i] = (i > 0 ? 2.0 * t[i - 1] : 0.0) - t_prev[i];
    t_prev = t;
    t = next;
  }
  return out;
}

template <class Row, std::size_t N>
std::array<double, 4> horner4_derivative(const std::array<Row, N>& m, double x) {
  std::array<double, 4> r{};
  for (std::size_t k = N - 1; k >= 1; --k)
    for (std::size_t l = 0; l < 4; ++l) r[l] = r[l] * x + static_cast<double>(k) * m[k][l];
  return r;
}

}  // namespace

EomTable::EomTable(const Scene& scene, double cell_rad)
    : eom_(scene), cell_rad_(cell_rad), inv_cell_(1.0 / cell_rad) {
  // Cell k ≥ 1 covers u = −φ ∈ [(k−1)w, k·w); cell 0 covers a small overshoot φ ∈ (0, w].
  // No cells for a scene whose exact terms are cheap: locate() then finds none.
  if (scene.worth_tabulating()) cells_.resize(static_cast<std::size_t>(scene.closing_limit_rad() * inv_cell_) + 2);
  cell_count_ = static_cast<double>(cells_.size());
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
  std::array<std::array<double, kNodes>, 4> f{};  // A, B, C, D at the nodes
  for (int j = 0; j < kNodes; ++j) {
    const double x = std::cos(std::numbers::pi * (j + 0.5) / kNodes);
    const double u = u0 + 0.5 * (x + 1.0) * cell_rad_;
    Terms t{};
    if (!negative_branch(-u, t)) return;
    const auto n = static_cast<std::size_t>(j);
    f[0][n] = t.S / t.I, f[1][n] = t.J / t.I, f[2][n] = t.Q / t.I, f[3][n] = t.G / t.I;
  }
  for (std::size_t l = 0; l < 4; ++l) {
    const std::array<double, kNodes> m = chebyshev_to_powers(chebyshev_fit(f[l]));
    for (std::size_t k = 0; k < static_cast<std::size_t>(kNodes); ++k) cell.abcd[k][l] = m[k];
  }
  // Self-check at two points between the nodes, each ratio against its term's scale in
  // Eq. (31) over I: S·ü_h against |S|, J·θ̇² against |I| (as in θ̈ = … per unit θ̇²), and
  // Q, G·g against |Q| + |S|·g (G enters as G·ü_v next to Q and S·ü_h).
  for (const double x : {0.31, -0.77}) {
    const double u = u0 + 0.5 * (x + 1.0) * cell_rad_;
    Terms t{};
    if (!negative_branch(-u, t)) return;
    const std::array<double, 4> v = detail::power_series4(cell.abcd, x);
    auto close = [](double a, double b, double scale) { return std::abs(a - b) <= 1e-11 * scale; };
    const double g = eom_.gravity_m_s2(), I = std::abs(t.I);
    const double qs = (std::abs(t.Q) + std::abs(t.S) * g) / I;
    if (!close(v[0], t.S / t.I, std::abs(t.S) / I) || !close(v[1], t.J / t.I, 1.0) || !close(v[2], t.Q / t.I, qs) ||
        !close(v[3] * g, t.G / t.I * g, qs))
      return;
  }
  cell.state = Cell::State::kTabulated;
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
  const std::array<double, 4> v = detail::power_series4(cell->abcd, x), dv = horner4_derivative(cell->abcd, x);
  theta1_ddot = detail::ratios_acceleration(v, omega1, ground, side);
  // d/du = (2/w) d/dx, and u = −θ₁ on side −1, +θ₁ on side +1.
  const double du_dx = 2.0 * inv_cell_ * (side < 0 ? -1.0 : 1.0);
  d_theta = du_dx * detail::ratios_acceleration(dv, omega1, ground, side);
  d_omega = (side < 0 ? -2.0 : 2.0) * v[1] * omega1;
  return true;
}

EomTable::Cells EomTable::all_cells() const {
  Cells out;
  out.inv_cell_per_rad = inv_cell_;
  out.coefficients.assign(cells_.size() * static_cast<std::size_t>(kCellValues), 0.0);
  out.tabulated.assign(cells_.size(), 0);
  for (std::size_t k = 0; k < cells_.size(); ++k) {
    Cell& cell = cells_[k];
    if (cell.state == Cell::State::kEmpty) build(cell, static_cast<int>(k));
    if (cell.state != Cell::State::kTabulated) continue;
    out.tabulated[k] = 1;
    for (std::size_t n = 0; n < static_cast<std::size_t>(kNodes); ++n)
      for (std::size_t l = 0; l < 4; ++l) out.coefficients[k * kCellValues + 4 * n + l] = cell.abcd[n][l];
  }
  return out;
}

}  // namespace pcrf
