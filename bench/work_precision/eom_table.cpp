// pcrf_eom_table: exports the basic frame's equation-of-motion coefficients for the SciPy
// comparison (scipy_compare.py), so that the Python script solves the same equations as the
// engine without re-deriving the four-bar kinematics.
//
//   pcrf_eom_table OUT.csv [PHI_MAX] [N] [RECORD.AT2 SCALE RECORD_OUT.txt]
//
// OUT.csv: comment lines "# key = value" (restitution, uplift threshold, rest acceleration
// terms), then columns phi,I,J,G,K,S of the θ₁ ≤ 0 branch at θ₁ = −phi, for phi on a
// uniform grid from −PHI_MAX/100 (an integrator overshooting an impact) to PHI_MAX.
// Side +1 is the mirror image: I, S even; J, G, K odd (equation_of_motion.hpp).
// RECORD_OUT.txt: "dt" on the first line, then the scaled samples in m/s², one a line.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

#include "pcrf/model/equation_of_motion.hpp"
#include "pcrf/model/frame.hpp"
#include "pcrf/model/impact.hpp"
#include "pcrf/record/record_readers.hpp"

int main(int argc, char** argv) {
  using namespace pcrf;
  if (argc < 2) {
    std::cerr << "usage: pcrf_eom_table OUT.csv [PHI_MAX=0.3] [N=300001] [RECORD.AT2 SCALE RECORD_OUT.txt]\n";
    return 2;
  }
  const double phi_max = argc > 2 ? std::atof(argv[2]) : 0.3;
  const long n = argc > 3 ? std::atol(argv[3]) : 300001;
  const Frame frame = basic_frame();
  const EquationOfMotion eom(frame);
  std::ofstream out(argv[1]);
  char buf[256];
  out << "# frame = basic\n";
  std::snprintf(buf, sizeof buf, "# restitution = %.17g\n# uplift_threshold_m_s2 = %.17g\n# g = %.17g\n",
                restitution_momentum(eom), eom.uplift_threshold_m_s2(), kGravity_m_s2);
  out << buf;
  std::snprintf(buf, sizeof buf, "# fracture_angle_rad = %.17g\n# closing_limit_rad = %.17g\n",
                eom.fracture_angle_rad(0.01), eom.closing_limit_rad());
  out << buf << "phi,I,J,G,K,S\n";
  const double phi0 = -phi_max / 100.0;
  for (long i = 0; i < n; ++i) {
    const double phi = phi0 + (phi_max - phi0) * static_cast<double>(i) / static_cast<double>(n - 1);
    EomTerms t;
    if (!eom.terms(-phi, -1, t)) break;
    std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", phi, t.I, t.J, t.G, t.K, t.S);
    out << buf;
  }
  if (argc > 6) {
    const GroundMotion rec = read_at2(argv[4]).scaled(std::atof(argv[5]));
    std::ofstream r(argv[6]);
    std::snprintf(buf, sizeof buf, "%.17g\n", rec.dt_s());
    r << buf;
    for (const double a : rec.samples_m_s2()) {
      std::snprintf(buf, sizeof buf, "%.17g\n", a);
      r << buf;
    }
  }
  return 0;
}
