// Accuracy presets: numerics only. The physics, the return-to-rest cut-off included
// ([physics] rest_rise_rad, 1e-10 rad), is PhysicsOptions' and the same for every preset;
// until it was, the cut-off was 10 atol_theta, and `fast` rested frames at a rise of 1e-5 rad.
// The values come from the work-precision study (bench/work_precision, docs/work_precision.md);
// change them only with new measurements.
//
// Measured on 210 cases (7 frames x the 11 paper records here x2/x3 and 4 synthetic motions;
// 161 rock), errors in theta_max against an ARKODE ERK8 rtol 1e-14 reference with the same
// cut-off; median steps / right-hand sides per case (pcrf_work_precision --integrators none
// --fixed-divs none, commit after 75d5fd5):
//   fast       rtol 1e-4, atol 1e-6 / 1e-5: median 6.8e-8, 90th pct 6.8e-5, worst well-conditioned
//              3.7e-4 (3.9e-1 with the cut-off at 10 atol); 577 / 3609 (220 / 1374 then: the
//              cascade below a rise of 1e-5 rad now is integrated, as by every preset).
//   balanced   rtol 1e-7, atol 1e-11 / 1e-10: median 9.0e-9, 90th pct 1.6e-7, worst well-cond.
//              6.0e-6; 734 / 4615. Unchanged bit for bit: its cut-off was 1e-10 already.
//   reference  ARKODE ERK5 rtol 1e-10, atol 1e-14 / 1e-13: median 3.0e-11, 90th pct 2.3e-9,
//              worst well-cond. 1.9e-7; 1764 / 14505. SUNDIALS on purpose: the reference is an
//              engine independent of the other two.
// Every preset ends every case in the reference's final status; the median |difference| of
// impact counts is 0 for each (it was 141 for fast and 23 for balanced). fast and balanced name `taylor`
// (Taylor steps for the rigid rockers, dopri5 elsewhere). All stop at every record sample: u_g
// has a kink there (dopri5 keeps the samples as breakpoints of its own).
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
