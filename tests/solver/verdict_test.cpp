// Verdicts: the verdict check ([solver] verdict_check) flags a case whose verdict flips under
// a 1e-6 change of its record and passes frames that never lift or collapse at once; and a
// reduced verdict benchmark: on real records across the collapse intensity, every preset
// reaches the converged reference's verdict on the cases whose verdict is well-conditioned.
#include <gtest/gtest.h>

#include <cmath>

#include "pcrf/record/intensity.hpp"
#include "pcrf/record/record_readers.hpp"
#include "pcrf/record/synthetic.hpp"
#include "pcrf/solver/rocking_solver.hpp"
#include "support/test_support.hpp"

namespace pcrf {
namespace {

SolverSettings checked(const std::string& preset = "balanced") {
  SolverSettings s = preset_settings(preset);
  s.verdict_check = true;
  return s;
}

TEST(VerdictCheck, AFrameThatNeverLiftsIsStable) {
  const auto r = solve_case(basic_frame(), make_synthetic("sine:amplitude_g=0.5,period_s=0.5,cycles=2"), {}, checked());
  EXPECT_EQ(r.status, CaseStatus::kAtRest);
  EXPECT_EQ(r.status_stable, 1.0);
  EXPECT_EQ(r.collapse_fraction, 0.0);
}

TEST(VerdictCheck, AFrameThatCollapsesAtOnceIsStable) {
  const auto r = solve_case(basic_frame(), make_synthetic("sine:amplitude_g=6,period_s=0.5,cycles=2"), {}, checked());
  EXPECT_EQ(r.status, CaseStatus::kTendonFracture);
  EXPECT_EQ(r.status_stable, 1.0);
  EXPECT_EQ(r.collapse_fraction, 1.0);
  EXPECT_LT(r.theta_max_spread, 1e-9);
}

TEST(VerdictCheck, NotCheckedIsNaN) {
  const auto r = solve_case(basic_frame(), make_synthetic("sine:amplitude_g=6,period_s=0.5,cycles=2"), {},
                            preset_settings("balanced"));
  EXPECT_TRUE(std::isnan(r.status_stable));
  EXPECT_TRUE(std::isnan(r.collapse_fraction));
}

GroundMotion at_pga(const GroundMotion& record, double pga_g) {
  return record.scaled(pga_g / peak_acceleration(record).pga_g);
}

TEST(VerdictCheck, AVerdictThatFlipsUnderAMillionthIsUnstable) {
  PCRF_REQUIRE_RECORDS(records);
  // Northridge, Beverly Hills (MUL279), the basic frame at 2.7775 g: the converged reference
  // fractures its tendons, and the same record scaled by 1 − 1e-6 leaves it at rest.
  const auto record = read_two_column(records / "ngawest2_ff_youtian95" / "RSN953_NORTHR_MUL279.txt", AccelUnit::kG);
  const auto r = solve_case(basic_frame(), at_pga(record, 2.7774794565919168), {}, checked());
  EXPECT_EQ(r.status_stable, 0.0);
  EXPECT_GT(r.collapse_fraction, 0.0);
  EXPECT_LT(r.collapse_fraction, 1.0);
  EXPECT_GT(r.theta_max_spread, 0.01);
}

TEST(Verdicts, PresetsAgreeWithTheConvergedReferenceOnWellConditionedCases) {
  PCRF_REQUIRE_RECORDS(records);
  SolverSettings reference;
  reference.integrator = Integrator::kArkodeErk8;
  reference.rtol = 1e-12;
  reference.atol_theta_rad = 1e-16;
  reference.atol_omega_rad_s = 1e-15;
  int well = 0, collapses = 0;
  for (const char* name : {"RSN1111_KOBE_NIS000", "RSN752_LOMAP_CAP000", "RSN1602_DUZCE_BOL090"}) {
    const auto record = read_two_column(records / "ngawest2_ff_youtian95" / (std::string(name) + ".txt"), AccelUnit::kG);
    for (double pga_g : {0.8, 1.2, 1.6, 2.0, 2.4, 2.8, 3.4, 4.2}) {
      const auto motion = at_pga(record, pga_g);
      const auto ref = solve_case(basic_frame(), motion, {}, reference);
      bool conditioned = true;
      for (double e : {1e-9, -1e-9, 1e-7, -1e-7, 1e-6, -1e-6})
        conditioned = conditioned && solve_case(basic_frame(), motion.scaled(1.0 + e), {}, reference).status == ref.status;
      if (!conditioned) continue;
      ++well;
      collapses += ref.status == CaseStatus::kTendonFracture || ref.status == CaseStatus::kOverturned;
      for (const auto& preset : preset_names())
        EXPECT_EQ(status_name(solve_case(basic_frame(), motion, {}, preset_settings(preset)).status), status_name(ref.status))
            << name << " at " << pga_g << " g, preset " << preset;
    }
  }
  EXPECT_GE(well, 20);
  EXPECT_GT(collapses, 3);  // the set spans the collapse intensity
}

}  // namespace
}  // namespace pcrf
