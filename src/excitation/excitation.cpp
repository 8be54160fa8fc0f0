// The excitation of one case (see excitation.hpp).
#include "pcrf/excitation/excitation.hpp"

#include "pcrf/user_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
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
  if (!(t_s >= 0.0)) return false;
  // Components whose intervals agree only within the tolerance of same_sample_interval
  // interpolate each on its own time axis: at() then, to stay bit for bit.
  if (excitation_.has_vertical() && excitation_.vertical()->dt_s() != h.dt_s()) return false;
  if (!(t_s < h.duration_s())) return enter_tail(t_s);
  const std::size_t k = k_ = h.interval_of(t_s);
  const double dt = h.dt_s();
  sampled_ = true;
  i_.lo_s = static_cast<double>(k) * dt;
  i_.hi_s = static_cast<double>(k + 1) * dt;
  i_.inv_dt_per_s = h.inverse_dt_per_s();
  load_samples(k);
  return true;
}

bool ExcitationCursor::enter_tail(double t_s) {
  // After every component's last sample the ground is still: at() is exactly 0 there, and so
  // is 0 + frac·0 for any finite t. The last sample itself stays at()'s.
  double end_s = excitation_.horizontal().duration_s();
  if (const GroundMotion* v = excitation_.vertical()) end_s = std::max(end_s, v->duration_s());
  if (!(t_s > end_s) || !(t_s < std::numeric_limits<double>::max())) return false;
  i_ = Interval{};
  sampled_ = false;
  i_.lo_s = std::nextafter(end_s, std::numeric_limits<double>::infinity());
  i_.hi_s = std::numeric_limits<double>::max();
  i_.inv_dt_per_s = excitation_.horizontal().inverse_dt_per_s();
  return true;
}

ScaledExcitation::ScaledExcitation(const Excitation& of, double factor)
    : horizontal_(of.horizontal().scaled(factor)), factor_(factor) {
  if (of.vertical() != nullptr) vertical_.emplace(of.vertical()->scaled(factor));
}

}  // namespace pcrf
