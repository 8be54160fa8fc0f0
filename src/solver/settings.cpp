// Text forms of the physics and solver options (command line, study files, results).
#include "pcrf/solver/settings.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

#include "pcrf/number_text.hpp"

namespace pcrf {


UpliftCriterion parse_uplift_criterion(const std::string& text) {
  return parse_name(detail::kUpliftNames, text, "uplift criterion");
}

std::string to_string(UpliftCriterion c) { return name_of(detail::kUpliftNames, c); }

std::string tail_advice(double tail_s) {
  if (std::isnan(tail_s)) return "a longer physics.tail_s (fixed tail) or physics.max_tail_s (until-rest tail) resolves them";
  if (tail_s == kTailUntilRest) return "a longer physics.max_tail_s resolves them (the until-rest tail stops there)";
  return "a longer physics.tail_s resolves them (the tail is fixed at " + number_text(tail_s) +
         " s; physics.max_tail_s caps only an until-rest tail)";
}

}  // namespace pcrf
