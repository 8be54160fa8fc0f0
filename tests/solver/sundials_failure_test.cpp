// SUNDIALS failures: a set-up call that SUNDIALS refuses throws naming the call (and, run
// under valgrind by the `leak` test label, frees every object made before it); a failure
// while integrating reaches the case's message with SUNDIALS's own text and function name.
#include <gtest/gtest.h>

#include <ostream>
#include <regex>
#include <string>

#include "solver/integrator/registry.hpp"  // private to the solver: the test makes one directly
#include "solver_test_support.hpp"

namespace pcrf {
namespace {

struct Method {
  const char* name;
  Integrator integrator;
  const char* tolerance_call;  ///< the call that refuses a negative relative tolerance
};

void PrintTo(const Method& m, std::ostream* out) { *out << m.name; }

class SundialsFailure : public ::testing::TestWithParam<Method> {};

/// θ'' = 0 with one root: enough for an integrator to be made.
class FreeFlight : public detail::OdeProblem {
 public:
  int rhs(double, const double* y, double* ydot) override {
    ydot[0] = y[1];
    ydot[1] = 0.0;
    return 0;
  }
  int roots(double, const double* y, double* g) override {
    g[0] = y[0];
    return 0;
  }
  int root_count() const override { return 1; }
};

// CVodeSVtolerances / ERKStepSVtolerances (ARKodeSVtolerances from SUNDIALS 7.1) refuse
// rtol < 0 after the context, the vectors and the integrator memory exist: each must be
// freed on the way out (valgrind's verdict under `ctest -L leak`). solve_case refuses such
// a setting before SUNDIALS sees it, hence the integrator made directly.
TEST_P(SundialsFailure, ARefusedSetUpCallThrowsNamingIt) {
  SolverSettings s = preset_settings("balanced");
  s.integrator = GetParam().integrator;
  s.rtol = -1.0;
  FreeFlight problem;
  try {
    detail::make_integrator(s, problem);
    FAIL() << "SUNDIALS accepted a negative rtol";
  } catch (const detail::IntegratorError& e) {
    EXPECT_TRUE(std::regex_search(e.what(), std::regex(GetParam().tolerance_call))) << e.what();
    EXPECT_NE(std::string(e.what()).find("failed with flag -"), std::string::npos) << e.what();
  }
}

// Too few steps allowed per call: SUNDIALS gives up (flag −1, "mxstep steps taken") and
// says so through the error handler, which must neither print nor lose it.
TEST_P(SundialsFailure, SundialsOwnMessageReachesTheCase) {
  SolverSettings s = preset_settings("balanced");
  s.integrator = GetParam().integrator;
  s.stop_at_samples = false;  // one call spans many steps
  s.max_steps = 3;
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  const CaseResult r = solve_case(basic_frame(), test::strong_record(), {}, s);
  EXPECT_EQ(testing::internal::GetCapturedStdout(), "");
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  EXPECT_EQ(r.status, CaseStatus::kSolverFailure);
  EXPECT_TRUE(std::regex_search(r.message, std::regex(R"(^(CVODE|ARKODE)::\w+ \(flag -1\): .*mxstep)"))) << r.message;
}

INSTANTIATE_TEST_SUITE_P(EverySundialsMethod, SundialsFailure,
                         ::testing::Values(Method{"CvodeBdf", Integrator::kCvodeBdf, "^CVodeSVtolerances "},
                                           Method{"CvodeAdams", Integrator::kCvodeAdams, "^CVodeSVtolerances "},
                                           Method{"ArkodeErk5", Integrator::kArkodeErk5, "^(ERKStep|ARKode)SVtolerances "},
                                           Method{"ArkodeErk8", Integrator::kArkodeErk8, "^(ERKStep|ARKode)SVtolerances "}),
                         [](const ::testing::TestParamInfo<Method>& method) { return std::string(method.param.name); });

}  // namespace
}  // namespace pcrf
