/// \file eom_table.hpp
/// \brief Lazily tabulated coefficients of Eq. (31) for the integrator's inner loop.
///
/// The right-hand side needs I, J, Q = G·g + K, S and, under vertical shaking, G at θ₁ (then
/// G(g + ü_v) + K = Q + G·ü_v: a case without a vertical component never evaluates G, and
/// gets bit for bit what it got before G was tabulated). Evaluating them exactly costs a
/// loop closure and ~16 transcendental functions; they are smooth in θ₁, so this class
/// samples them once per cell of width `cell_rad` at 10 Chebyshev nodes and evaluates the
/// degree-9 interpolant (Clenshaw) afterwards. Cells are built on first use, so a case pays
/// only for the range it visits. Each cell checks itself against the exact terms at two
/// interior points when it is built; a cell that misses 1e-11 relative (near the linkage's
/// closing limit, where derivatives blow up) falls back to exact evaluation.
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

  /// θ̈₁ [rad/s²] as EquationOfMotion::acceleration, from the tabulated terms.
  bool acceleration(double theta1, double omega1, GroundAcceleration ground, int side, double& theta1_ddot) const;

  /// θ̈₁ and its partial derivatives ∂θ̈₁/∂θ₁ [1/s²] and ∂θ̈₁/∂θ̇₁ [1/s], for implicit
  /// integrators. The θ₁-derivative comes from differentiating the Chebyshev series
  /// (exact for the interpolant); a difference quotient of the tabulated θ̈₁ would lose
  /// the small θ₁-dependent part to round-off next to the large step force at θ₁ = 0.
  bool acceleration_jacobian(double theta1, double omega1, GroundAcceleration ground, int side,
                             double& theta1_ddot, double& d_theta, double& d_omega) const;

  /// Number of cells built so far (for tests and benchmarks).
  int cells_built() const { return built_; }

 private:
  static constexpr int kNodes = 10;
  struct Coefficients {
    std::array<double, kNodes> I, J, Q, S, G;
  };
  struct Cell {
    // User-provided: a vector of cells is not zero-filled first (a frame's table holds ~80
    // cells of 1 kB, and a case visits a few); build() fills what it uses.
    Cell() {}  // NOLINT(modernize-use-equals-default)
    enum class State : char { kEmpty, kTabulated, kExact } state = State::kEmpty;
    Coefficients c;   ///< the series
    Coefficients dc;  ///< the series of their x-derivatives
    std::array<std::array<double, 4>, kNodes> ijqs;  ///< c.I, c.J, c.Q, c.S interleaved (clenshaw4)
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
  mutable std::vector<Cell> cells_;
  mutable int built_ = 0;
};

}  // namespace pcrf
