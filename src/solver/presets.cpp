// Accuracy presets. The values come from the work-precision study
// (bench/work_precision, README "Speed against accuracy"); change them only with new
// measurements.
#include <stdexcept>

#include "pcrf/solver/settings.hpp"

namespace pcrf {

SolverSettings preset_settings(const std::string& name) {
  SolverSettings s;
  s.integrator = Integrator::kArkodeErk5;
  s.stop_at_samples = true;
  if (name == "fast") {
    s.rtol = 1e-5;
    s.atol_theta_rad = 1e-8;
    s.atol_omega_rad_s = 1e-7;
  } else if (name == "balanced") {
    s.rtol = 1e-8;
    s.atol_theta_rad = 1e-11;
    s.atol_omega_rad_s = 1e-10;
  } else if (name == "reference") {
    s.integrator = Integrator::kArkodeErk8;
    s.rtol = 1e-11;
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
