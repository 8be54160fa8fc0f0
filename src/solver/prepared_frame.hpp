// A frame prepared for solving (see rocking_solver.hpp, PreparedFrame). Private to the solver.
#pragma once

#include <memory>
#include <optional>

#include "case_common.hpp"
#include "pcrf/model/eom_table.hpp"
#include "pcrf/model/equation_of_motion.hpp"
#include "pcrf/solver/rocking_solver.hpp"

namespace pcrf {

class PreparedFrame {
 public:
  PreparedFrame(const Frame& frame, const PhysicsOptions& physics);

  const Frame& frame() const { return frame_; }
  const PhysicsOptions& physics() const { return physics_; }
  const EquationOfMotion& eom() const { return eom_; }
  double restitution() const { return restitution_; }
  bool broken_at_rest() const { return broken_at_rest_; }
  /// Fracture and overturning angles (the closing limit and a strain scan, on first use).
  const detail::StopAngles& stop_angles();
  /// The tabulated coefficients of Eq. (31) (cells built as flights visit them).
  const EomTable& table();

 private:
  Frame frame_;
  PhysicsOptions physics_;
  EquationOfMotion eom_;
  double restitution_;
  bool broken_at_rest_;
  std::optional<detail::StopAngles> stop_;
  std::unique_ptr<EomTable> table_;
};

}  // namespace pcrf
