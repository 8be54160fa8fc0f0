// What resolves a case still rocking at its end (see unresolved.hpp).
#include "pcrf/metrics/unresolved.hpp"

#include <cmath>

#include "pcrf/number_text.hpp"

namespace pcrf {

std::string tail_advice(double tail_s) {
  if (std::isnan(tail_s)) return "a longer physics.tail_s (fixed tail) or physics.max_tail_s (until-rest tail) resolves them";
  if (tail_s == kTailUntilRest) return "a longer physics.max_tail_s resolves them (the until-rest tail stops there)";
  return "a longer physics.tail_s resolves them (the tail is fixed at " + number_text(tail_s) +
         " s; physics.max_tail_s caps only an until-rest tail)";
}

}  // namespace pcrf
