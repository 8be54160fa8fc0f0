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


}  // namespace pcrf
