/// \file eom_table.hpp
/// \brief Lazily tabulated coefficients of Eq. (31) for the integrator's inner loop.
///
/// The right-hand side needs I, J, Q = G·g + K, S and, under vertical shaking, G at θ₁ (then
/// G(g + ü_v) + K = Q + G·ü_v: a case without a vertical component never evaluates G, and
/// gets bit for bit what it got before G was tabulated). Evaluating them exactly costs a
/// loop closure and ~16 transcendental functions; they are smooth in θ₁, so this class
/// samples them once per cell of width `cell_rad` at 10 Chebyshev nodes. What it
/// interpolates are the ratios the right-hand side needs,
///   A = S/I,  B = J/I,  C = Q/I,  D = G/I,   θ̈₁ = A ü_h − s (B θ̇₁² + C + D ü_v)
/// (s = −1 on side −1, +1 on side +1): no division per call, and four series rather than
/// five. Each is the degree-9 Chebyshev interpolant, converted once to powers of the cell's
/// coordinate x ∈ [−1, 1] and evaluated by Estrin's scheme, the four in two pairs of lanes.
/// (The conversion costs nothing in accuracy here: the series' coefficients fall off fast
/// over a 0.02 rad cell, and the self-check below evaluates the converted form.)
/// Cells are built on first use, so a case pays only for the range it visits. Each cell
/// checks itself against the exact terms at two interior points when it is built; a cell
/// that misses 1e-11 of each term's scale (near the linkage's closing limit, where
/// derivatives blow up) falls back to exact evaluation.
///
/// Not thread-safe (cells are filled lazily): one table per case.
#pragma once

#include <array>
#include <vector>

#include "pcrf/model/scene.hpp"

namespace pcrf {

class EomTable {
 public:
  /// A scene not worth tabulating (Scene::worth_tabulating) is evaluated exactly throughout.
  explicit EomTable(const Scene& scene, double cell_rad = 0.02);

  /// θ̈₁ [rad/s²] as EquationOfMotion::acceleration, from the tabulated terms. Inline: it
  /// is the integrator's right-hand side.
  bool acceleration(double theta1, double omega1, GroundAcceleration ground, int side, double& theta1_ddot) const;

  /// θ̈₁ and its partial derivatives ∂θ̈₁/∂θ₁ [1/s²] and ∂θ̈₁/∂θ̇₁ [1/s], for implicit
  /// integrators. The θ₁-derivative comes from differentiating the Chebyshev series
  /// (exact for the interpolant); a difference quotient of the tabulated θ̈₁ would lose
  /// the small θ₁-dependent part to round-off next to the large step force at θ₁ = 0.
  bool acceleration_jacobian(double theta1, double omega1, GroundAcceleration ground, int side,
                             double& theta1_ddot, double& d_theta, double& d_omega) const;

  /// Number of cells built so far (for tests and benchmarks).
  int cells_built() const { return built_; }

  /// Every cell built, as the case kernel reads the table (src/solver/device/): cell k's
  /// power series at coefficients[kCellValues·k …], row by row (degree 0 … kNodes − 1 of A,
  /// B, C, D, as power_series4 reads them), and whether it is tabulated (else the exact terms
  /// hold there). No cells for a scene evaluated exactly throughout.
  static constexpr int kSeriesDegree = 9;
  static constexpr int kCellValues = 4 * (kSeriesDegree + 1);
  struct Cells {
    double inv_cell_per_rad = 0.0;  ///< 1 / the cell width
    std::vector<double> coefficients;
    std::vector<unsigned char> tabulated;
  };
  Cells all_cells() const;

 private:
  static constexpr int kNodes = kSeriesDegree + 1;
  /// Power-series coefficients in x of A, B, C, D (lanes 0…3), lowest degree first.
  struct alignas(32) Lanes4 : std::array<double, 4> {};
  using Series4 = std::array<Lanes4, kNodes>;
  struct Cell {
    // User-provided: a vector of cells is not zero-filled first (a frame's table holds ~80
    // cells, and a case visits a few); build() fills what it uses.
    Cell() {}  // NOLINT(modernize-use-equals-default)
    enum class State : char { kEmpty, kTabulated, kExact } state = State::kEmpty;
    Series4 abcd;
  };

  /// The cell holding θ₁ on `side` (built on first use) and the local coordinate
  /// x ∈ [−1, 1]; nullptr where the table does not apply (exact terms then).
  const Cell* locate(double theta1, int side, double& x) const;

  /// The terms on the θ₁ ≤ 0 branch at θ₁ = φ, with Q = G·g + K.
  struct Terms {
    double I, J, Q, S, G;
  };
  bool negative_branch(double phi, Terms& out) const;
  void build(Cell& cell, int index) const;

  const Scene& eom_;
  double cell_rad_;
  double inv_cell_;
  double cell_count_ = 0.0;  ///< cells_.size(), as the bound locate() compares with
  mutable std::vector<Cell> cells_;
  mutable int built_ = 0;
};

namespace detail {

// Four power series of degree 9 at once, as two pairs of lanes (GCC's and Clang's vector
// extension: two doubles per SSE2 register on any x86-64, NEON on arm64; compilers do not
// vectorize across the series by themselves), by Estrin's scheme: the pairs c_k + c_{k+1} x
// and the powers x², x⁴, x⁸ are independent, so the dependent chain is four multiply-adds
// deep instead of Horner's nine (the right-hand side waits on it at every stage).
template <class Row, std::size_t N>
std::array<double, 4> power_series4(const std::array<Row, N>& m, double x) {
  static_assert(N == 10, "Estrin's scheme below is written out for degree 9");
  using Pair = double __attribute__((vector_size(16)));
  static_assert(alignof(Row) >= alignof(Pair) && sizeof(Row) == 2 * sizeof(Pair));
  const double x2 = x * x, x4 = x2 * x2, x8 = x4 * x4;
  auto lanes = [&](std::size_t k, int half) { return reinterpret_cast<const Pair*>(m[k].data())[half]; };
  auto series = [&](int half) {
    const Pair q01 = lanes(0, half) + x * lanes(1, half), q23 = lanes(2, half) + x * lanes(3, half);
    const Pair q45 = lanes(4, half) + x * lanes(5, half), q67 = lanes(6, half) + x * lanes(7, half);
    const Pair q89 = lanes(8, half) + x * lanes(9, half);
    return (q01 + x2 * q23) + x4 * (q45 + x2 * q67) + x8 * q89;
  };
  const Pair ab = series(0), cd = series(1);
  return {ab[0], ab[1], cd[0], cd[1]};
}

/// θ̈₁ = A ü_h − s (B θ̇₁² + C + D ü_v) from the ratios v = (A, B, C, D), s = +1 on side −1
/// and −1 on side +1 (the odd mirror: J, G, K change sign, I and S do not). Linear in v, so
/// the same combination of their x-derivatives is ∂θ̈₁/∂x. Without vertical shaking D·ü_v
/// is a signed zero and C + D·ü_v is C bit for bit.
inline double ratios_acceleration(const std::array<double, 4>& v, double omega1, GroundAcceleration ground,
                                  int side) {
  const double s = side < 0 ? 1.0 : -1.0;
  return v[0] * ground.horizontal_m_s2 - s * (v[1] * omega1 * omega1 + (v[2] + v[3] * ground.vertical_m_s2));
}

}  // namespace detail

inline const EomTable::Cell* EomTable::locate(double theta1, int side, double& x) const {
  const double u = side < 0 ? -theta1 : theta1;  // distance into the branch
  const double v = u * inv_cell_;
  if (!(v >= -1.0 && v < cell_count_)) return nullptr;  // also NaN
  // floor(v) + 1 without a libm call: truncation, one down for a negative fraction.
  auto whole = static_cast<long>(v);
  whole -= static_cast<long>(v < static_cast<double>(whole));
  const long index = whole + 1;
  if (index < 0 || index >= static_cast<long>(cells_.size())) return nullptr;
  Cell& cell = cells_[static_cast<std::size_t>(index)];
  if (cell.state == Cell::State::kEmpty) [[unlikely]] build(cell, static_cast<int>(index));
  if (cell.state == Cell::State::kExact) return nullptr;
  // v − ⌊v⌋ is the fraction of the cell: x = 2·fraction − 1, without going back to u.
  x = 2.0 * (v - static_cast<double>(whole)) - 1.0;
  return &cell;
}

inline bool EomTable::acceleration(double theta1, double omega1, GroundAcceleration ground, int side,
                                  double& theta1_ddot) const {
  double x = 0;
  const Cell* cell = locate(theta1, side, x);
  if (cell == nullptr) return eom_.acceleration(theta1, omega1, ground, side, theta1_ddot);
  theta1_ddot = detail::ratios_acceleration(detail::power_series4(cell->abcd, x), omega1, ground, side);
  return true;
}

}  // namespace pcrf
