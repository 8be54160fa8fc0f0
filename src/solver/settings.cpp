// Text forms of the physics and solver options (command line, study files, results).
#include "pcrf/solver/settings.hpp"

#include <stdexcept>

namespace pcrf {

UpliftCriterion parse_uplift_criterion(const std::string& text) {
  if (text == "physical") return UpliftCriterion::kPhysical;
  if (text == "paper") return UpliftCriterion::kPaper;
  throw std::invalid_argument("unknown uplift criterion '" + text + "' (expected physical or paper)");
}

std::string to_string(UpliftCriterion c) { return c == UpliftCriterion::kPaper ? "paper" : "physical"; }

Integrator parse_integrator(const std::string& text) {
  if (text == "cvode-bdf") return Integrator::kCvodeBdf;
  if (text == "cvode-adams") return Integrator::kCvodeAdams;
  if (text == "arkode-erk5") return Integrator::kArkodeErk5;
  if (text == "arkode-erk8") return Integrator::kArkodeErk8;
  if (text == "fixed-rk4") return Integrator::kFixedRk4SignChange;
  throw std::invalid_argument("unknown integrator '" + text +
                              "' (expected cvode-adams, cvode-bdf, arkode-erk5, arkode-erk8 or fixed-rk4)");
}

std::string to_string(Integrator i) {
  switch (i) {
    case Integrator::kCvodeBdf: return "cvode-bdf";
    case Integrator::kCvodeAdams: return "cvode-adams";
    case Integrator::kArkodeErk5: return "arkode-erk5";
    case Integrator::kArkodeErk8: return "arkode-erk8";
    case Integrator::kFixedRk4SignChange: return "fixed-rk4";
  }
  return "unknown";
}

}  // namespace pcrf
