// Accuracy presets. The values come from the work-precision study
// (bench/work_precision, docs/work_precision.md); change them only with new measurements.
//
// Measured on 210 cases (7 frames x 13 paper records x2/x3 and 4 synthetic motions; 161
// rock), errors in theta_max against an ARKODE ERK8 rtol 1e-14 reference; median wall time
// per case on the 2-core development box (one run per case, another build running):
//   fast       dopri5 rtol 1e-4, atol 1e-6 / 1e-5: median 6.8e-8, 90th pct 6.8e-5; 0.24 ms
//              (before: ARKODE ERK5, same tolerances: 1.3e-7, 1.6e-4; 0.99 ms).
//   balanced   dopri5 rtol 1e-7, atol 1e-4 rtol / 1e-3 rtol: median 8.3e-9, 90th pct 1.5e-7;
//              0.44 ms (before: ARKODE ERK5 rtol 1e-6: 4.9e-8, 1.3e-6; 2.51 ms). At rtol 1e-6
//              dopri5's 90th percentile (1.7e-6) was above the old preset's.
//   reference  ARKODE ERK5 rtol 1e-10, atol 1e-4 rtol: median 2.8e-11, 90th pct 2.3e-9; 5.0 ms.
//              SUNDIALS on purpose: the reference is an engine independent of the other two.
// Every preset ends every case in the reference's final status. All stop at every record
// sample: u_g has a kink there (dopri5 keeps the samples as breakpoints of its own).
#include <stdexcept>

#include "pcrf/user_error.hpp"

#include "pcrf/solver/settings.hpp"

namespace pcrf {

SolverSettings preset_settings(const std::string& name) {
  SolverSettings s;
  s.integrator = parse_integrator("taylor");  // the registry's: its without_series (dopri5) for a scene without one
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
    s.integrator = parse_integrator("arkode-erk5");  // SUNDIALS: an independent check of the others
    s.rtol = 1e-10;
    s.atol_theta_rad = 1e-14;
    s.atol_omega_rad_s = 1e-13;
  } else {
    throw UserError("unknown preset '" + name + "' (expected fast, balanced or reference)");
  }
  return s;
}

const std::vector<std::string>& preset_names() {
  static const std::vector<std::string> names = {"fast", "balanced", "reference"};
  return names;
}

}  // namespace pcrf
