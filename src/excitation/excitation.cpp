// The excitation of one case (see excitation.hpp).
#include "pcrf/excitation/excitation.hpp"

#include "pcrf/user_error.hpp"

#include <stdexcept>
#include <string>

#include "pcrf/number_text.hpp"

namespace pcrf {

Excitation::Excitation(const GroundMotion& horizontal, const GroundMotion* vertical)
    : horizontal_(&horizontal), vertical_(vertical) {
  if (vertical_ == nullptr) return;
  if (!same_sample_interval(vertical_->dt_s(), horizontal_->dt_s()))
    throw UserError("the vertical component '" + vertical_->name() + "' is sampled every " +
                                number_text(vertical_->dt_s()) + " s, the horizontal '" + horizontal_->name() +
                                "' every " + number_text(horizontal_->dt_s()) + " s: they need the same dt");
  if (vertical_->size() != horizontal_->size())
    throw UserError("the vertical component '" + vertical_->name() + "' has " +
                                std::to_string(vertical_->size()) + " samples, the horizontal '" +
                                horizontal_->name() + "' " + std::to_string(horizontal_->size()) +
                                ": pad the shorter with zeros first");
}

bool ExcitationCursor::enter(double t_s) {
  const GroundMotion& h = excitation_.horizontal();
  if (!(t_s >= 0.0) || !(t_s < h.duration_s())) return false;
  // Components whose intervals agree only within the tolerance of same_sample_interval
  // interpolate each on its own time axis: at() then, to stay bit for bit.
  if (excitation_.has_vertical() && excitation_.vertical()->dt_s() != h.dt_s()) return false;
  const std::size_t k = h.interval_of(t_s);
  const double dt = h.dt_s();
  i_.lo_s = static_cast<double>(k) * dt;
  i_.hi_s = static_cast<double>(k + 1) * dt;
  i_.inv_dt_per_s = h.inverse_dt_per_s();
  const auto& a = h.samples_m_s2();
  i_.h0 = a[k], i_.dh = a[k + 1] - a[k];
  if (const GroundMotion* v = excitation_.vertical()) {
    const auto& b = v->samples_m_s2();
    i_.v0 = b[k], i_.dv = b[k + 1] - b[k];
  }
  return true;
}

ScaledExcitation::ScaledExcitation(const Excitation& of, double factor)
    : horizontal_(of.horizontal().scaled(factor)), factor_(factor) {
  if (of.vertical() != nullptr) vertical_.emplace(of.vertical()->scaled(factor));
}

}  // namespace pcrf
