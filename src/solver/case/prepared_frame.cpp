// A frame prepared for solving, and where the rigid-body rocking model holds.
#include "prepared_frame.hpp"

#include <cstdio>

#include "pcrf/model/impact.hpp"

namespace pcrf {
namespace {

/// The domain of the model (studies/README.md, "Valid frames"), three conditions at rest,
/// in terms of Eq. (31) on the θ₁ ≤ 0 branch (I θ̈ + … + G g + K = S ü_g):
///  - the ground's inertia and gravity act on the mechanism the way a rocking frame's do,
///    λ_g = G/S > 0: with a beam so deep that S changes sign (λ_h ≈ 0.865 at λ = 2,
///    tan α = 0.8) the uplift threshold passes through a pole and turns negative, the linkage
///    moving against the ground — not a rocking frame;
///  - gravity and prestress hold the frame closed, threshold (G g + K)/S > 0, else it opens
///    under its own weight;
///  - an impact dissipates and sends the frame on to the other side, 0 ≤ r ≤ 1: r < 0 would
///    send it back (a rebound the momentum balance of rocking impacts does not have), r > 1
///    would create energy.
void check_domain(const Scene& eom, double restitution) {
  char text[240];
  if (!(eom.lambda_g() > 0.0)) {
    std::snprintf(text, sizeof text,
                  "the ground cannot rock this frame: its uplift coefficient G/S = %.4g is not positive (a beam this "
                  "deep turns the linkage against the ground motion)", eom.lambda_g());
    throw UserError(text);
  }
  const double threshold_g = eom.uplift_threshold_m_s2() / kGravity_m_s2;
  if (!(threshold_g > 0.0)) {
    std::snprintf(text, sizeof text,
                  "the frame cannot stand at rest: its uplift threshold is %.4g g (gravity and prestress do not hold "
                  "it closed)", threshold_g);
    throw UserError(text);
  }
  if (!(restitution >= 0.0 && restitution <= 1.0)) {
    std::snprintf(text, sizeof text,
                  "coefficient of restitution r = %.4g is outside [0, 1]: the impacts are not rocking impacts "
                  "(the beam is too deep or the span too short for its columns)", restitution);
    throw UserError(text);
  }
}

std::unique_ptr<Scene> equation_of(const Frame& frame) {
  return std::make_unique<EquationOfMotion>(frame);
}

}  // namespace

PreparedFrame::PreparedFrame(const Frame& frame, const PhysicsOptions& physics)
    : PreparedFrame(equation_of(frame), physics) {}

PreparedFrame::PreparedFrame(std::unique_ptr<Scene> scene, const PhysicsOptions& physics)
    : physics_(physics),
      scene_(std::move(scene)),
      restitution_(scene_->restitution()),
      broken_at_rest_(scene_->broken_at_rest(physics.fracture_strain)) {
  check_domain(*scene_, restitution_);
}

const detail::StopAngles& PreparedFrame::stop_angles() {
  if (!stop_) stop_ = detail::stop_angles(*scene_, physics_);
  return *stop_;
}

const EomTable& PreparedFrame::table() {
  if (!table_) table_ = std::make_unique<EomTable>(*scene_);
  return *table_;
}

std::shared_ptr<PreparedFrame> prepare_frame(const Frame& frame, const PhysicsOptions& physics) {
  return std::make_shared<PreparedFrame>(frame, physics);
}

std::shared_ptr<PreparedFrame> prepare_scene(std::unique_ptr<Scene> scene, const PhysicsOptions& physics) {
  return std::make_shared<PreparedFrame>(std::move(scene), physics);
}

}  // namespace pcrf
