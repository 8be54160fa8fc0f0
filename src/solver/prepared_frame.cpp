// A frame prepared for solving, and where the rigid-body rocking model holds.
#include "prepared_frame.hpp"

#include <cstdio>

#include "pcrf/model/impact.hpp"

namespace pcrf {
namespace {

/// The domain of the model. The frame rests on its feet only while gravity and prestress
/// hold it closed: a threshold ≤ 0 means it opens under its own weight. An impact must
/// dissipate and keep the frame rocking towards the other side: r < 0 would send it back
/// (the momentum balance then needs a rebound the model does not have) and r > 1 would
/// create energy.
void check_domain(const EquationOfMotion& eom, double restitution) {
  char text[200];
  const double threshold_g = eom.uplift_threshold_m_s2() / kGravity_m_s2;
  if (!(threshold_g > 0.0)) {
    std::snprintf(text, sizeof text,
                  "the frame cannot stand at rest: its uplift threshold is %.4g g (gravity and prestress do not "
                  "hold it closed)", threshold_g);
    throw InvalidFrame(text);
  }
  if (!(restitution >= 0.0 && restitution <= 1.0)) {
    std::snprintf(text, sizeof text,
                  "coefficient of restitution r = %.4g is outside [0, 1]: the impacts are not rocking impacts "
                  "(the beam is too deep or the span too short for its columns)", restitution);
    throw InvalidFrame(text);
  }
}

EquationOfMotion equation_of(const Frame& frame) {
  try {
    return EquationOfMotion(frame);
  } catch (const std::invalid_argument& e) {
    throw InvalidFrame(e.what());
  }
}

}  // namespace

PreparedFrame::PreparedFrame(const Frame& frame, const PhysicsOptions& physics)
    : frame_(frame),
      physics_(physics),
      eom_(equation_of(frame)),
      restitution_(restitution_momentum(eom_)),
      broken_at_rest_(eom_.broken_at_rest(physics.fracture_strain)) {
  check_domain(eom_, restitution_);
}

const detail::StopAngles& PreparedFrame::stop_angles() {
  if (!stop_) stop_ = detail::stop_angles(eom_, physics_);
  return *stop_;
}

const EomTable& PreparedFrame::table() {
  if (!table_) table_ = std::make_unique<EomTable>(eom_);
  return *table_;
}

std::shared_ptr<PreparedFrame> prepare_frame(const Frame& frame, const PhysicsOptions& physics) {
  return std::make_shared<PreparedFrame>(frame, physics);
}

}  // namespace pcrf
