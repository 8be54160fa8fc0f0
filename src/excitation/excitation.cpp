// The excitation of one case (see excitation.hpp).
#include "pcrf/excitation/excitation.hpp"

#include <stdexcept>
#include <string>

#include "pcrf/number_text.hpp"

namespace pcrf {

Excitation::Excitation(const GroundMotion& horizontal, const GroundMotion* vertical)
    : horizontal_(&horizontal), vertical_(vertical) {
  if (vertical_ == nullptr) return;
  if (!same_sample_interval(vertical_->dt_s(), horizontal_->dt_s()))
    throw std::invalid_argument("the vertical component '" + vertical_->name() + "' is sampled every " +
                                number_text(vertical_->dt_s()) + " s, the horizontal '" + horizontal_->name() +
                                "' every " + number_text(horizontal_->dt_s()) + " s: they need the same dt");
  if (vertical_->size() != horizontal_->size())
    throw std::invalid_argument("the vertical component '" + vertical_->name() + "' has " +
                                std::to_string(vertical_->size()) + " samples, the horizontal '" +
                                horizontal_->name() + "' " + std::to_string(horizontal_->size()) +
                                ": pad the shorter with zeros first");
}

ScaledExcitation::ScaledExcitation(const Excitation& of, double factor)
    : horizontal_(of.horizontal().scaled(factor)) {
  if (of.vertical() != nullptr) vertical_.emplace(of.vertical()->scaled(factor));
}

}  // namespace pcrf
