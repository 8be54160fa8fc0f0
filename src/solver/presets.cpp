// Accuracy presets. The values come from the work-precision study
// (bench/work_precision, docs/work_precision.md); change them only with new measurements.
//
// Measured on 210 cases (7 frames × 13 paper records ×2/×3 and 4 synthetic motions; 161
// rock), errors in θ_max against an ARKODE ERK8 rtol 1e-14 reference; "worst" over the 151
// well-conditioned cases; median wall time per case on the 2-core development box (median
// of 3 runs each):
//   fast       ERK5 rtol 1e-4:  median 1.3e-7, 90th pct 1.6e-4, worst 5.5e-4; 0.85 ms.
//   balanced   ERK5 rtol 1e-6, atol 1e-4·rtol: median 4.9e-8, 90th pct 1.3e-6, worst 5.0e-6;
//              1.9 ms.
//   reference  ERK5 rtol 1e-10, atol 1e-4·rtol: median 2.8e-11, 90th pct 2.3e-9, worst
//              4.8e-8; 3.4 ms.
// All three stop at every record sample: ü_g has a kink there, and stepping across it
// costs accuracy and, at loose tolerances, robustness (docs/work_precision.md). ERK5 beats
// ERK8, CVODE Adams and BDF at every accuracy in this problem: the steps are bounded by the
// sample spacing, so the cheaper stages win.
#include <stdexcept>

#include "pcrf/solver/settings.hpp"

namespace pcrf {

SolverSettings preset_settings(const std::string& name) {
  SolverSettings s;
  s.integrator = Integrator::kDormandPrince5;
  s.stop_at_samples = true;
  s.preset = name;
  if (name == "fast") {
    s.rtol = 1e-4;
    s.atol_theta_rad = 1e-6;
    s.atol_omega_rad_s = 1e-5;
  } else if (name == "balanced") {
    s.rtol = 1e-7;
    s.atol_theta_rad = 1e-11;
    s.atol_omega_rad_s = 1e-10;
  } else if (name == "reference") {
    s.integrator = Integrator::kArkodeErk5;  // SUNDIALS: an independent check of the others
    s.rtol = 1e-10;
    s.atol_theta_rad = 1e-14;
    s.atol_omega_rad_s = 1e-13;
  } else {
    throw std::invalid_argument("unknown preset '" + name + "' (expected fast, balanced or reference)");
  }
  return s;
}

const std::vector<std::string>& preset_names() {
  static const std::vector<std::string> names = {"fast", "balanced", "reference"};
  return names;
}

}  // namespace pcrf
