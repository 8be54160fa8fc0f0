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
  /// The prestressed rocking frame. \throws UserError.
  PreparedFrame(const Frame& frame, const PhysicsOptions& physics);
  /// Any scene. \throws UserError when it lies outside the model's domain.
  PreparedFrame(std::unique_ptr<Scene> scene, const PhysicsOptions& physics);

  const PhysicsOptions& physics() const { return physics_; }
  const Scene& scene() const { return *scene_; }
  double restitution() const { return restitution_; }
  bool broken_at_rest() const { return broken_at_rest_; }
  /// Fracture and overturning angles (the closing limit and a strain scan, on first use).
  const detail::StopAngles& stop_angles();
  /// The coefficients of Eq. (31') for the integrator: tabulated (cells built as flights
  /// visit them) for a scene worth it, else its exact terms.
  const EomTable& table();

 private:
  PhysicsOptions physics_;
  std::unique_ptr<Scene> scene_;
  double restitution_;
  bool broken_at_rest_;
  std::optional<detail::StopAngles> stop_;
  std::unique_ptr<EomTable> table_;
};

}  // namespace pcrf
