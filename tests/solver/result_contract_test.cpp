// Every solver path sets every metric it claims: a metric is a number where it exists and
// NaN exactly where case_result.hpp says it does not (no uplift, not requested, not checked,
// no tendons), for every integrator and every way a case can end.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

#include "pcrf/model/rigid_rocker.hpp"
#include "pcrf/record/pulses.hpp"
#include "solver_test_support.hpp"

namespace pcrf {
namespace {

struct Path {
  std::string name;
  GroundMotion record;
  PhysicsOptions physics;
  SolverSettings solver;
  CaseStatus expected;
};

std::vector<Path> paths(Integrator integrator) {
  SolverSettings solver;
  solver.integrator = integrator;
  solver.fixed_step_s = 1e-3;
  PhysicsOptions physics = test::record_only();
  const GroundMotion strong = test::strong_record(7, 12.0);
  PulseSpec pulse;
  pulse.amplitude_g = 1.6;
  pulse.duration_s = 2.0;
  std::vector<Path> out;
  out.push_back({"never lifts", test::quiet_record(2.0), physics, solver, CaseStatus::kAtRest});
  PhysicsOptions tail = physics;
  tail.tail_s = 10.0;
  // The fixed-step contender never puts a frame back at rest (fixed_step_solver.hpp).
  out.push_back({"rocks, then rests", make_pulse(pulse), tail, solver,
                 registry_entry(integrator).can.locates_events ? CaseStatus::kAtRest : CaseStatus::kRockingAtEnd});
  out.push_back({"still rocking", strong, physics, solver, CaseStatus::kRockingAtEnd});
  out.push_back({"collapses", strong.scaled(3.0), physics, solver, CaseStatus::kTendonFracture});
  PhysicsOptions brittle = physics;
  brittle.fracture_strain = 1e-4;  // below the tendons' initial strain
  out.push_back({"broken at rest", strong, brittle, solver, CaseStatus::kTendonFracture});
  PhysicsOptions displaced = physics;
  displaced.theta0_rad = -0.02;
  out.push_back({"displaced start", test::quiet_record(1.0), displaced, solver, CaseStatus::kRockingAtEnd});
  if (registry_entry(integrator).can.locates_events) {  // the contender has no step or time budget
    SolverSettings starved = solver;
    starved.max_steps = 3;
    out.push_back({"solver failure", strong, physics, starved, CaseStatus::kSolverFailure});
    SolverSettings hurried = solver;
    hurried.wall_time_limit_s = 1e-9;
    out.push_back({"time limit", strong, physics, hurried, CaseStatus::kTimeLimit});
  }
  return out;
}

/// The contract of case_result.hpp for one result.
void expect_contract(const CaseResult& r, bool omega_requested, bool verdict_checked, bool tendons) {
  const bool lifted = !std::isnan(r.t_uplift_s);
  for (const auto& m : all_metrics()) {
    const std::string name(m.name);
    const double v = m.get(r);
    SCOPED_TRACE(name + " = " + std::to_string(v));
    if (m.needs_verdict_check) {
      EXPECT_EQ(std::isnan(v), !verdict_checked);
    } else if (name == "t_trigger_paper_s" || name == "t_uplift_s") {
      EXPECT_TRUE(std::isnan(v) || v >= 0.0);
    } else if (!m.exists_with.empty()) {
      // The time of an event (t_theta_max_s, t_omega_max_s, ...): NaN exactly when the event
      // did not happen, as the table says (MetricInfo::exists_with), else within the case.
      const MetricInfo* event = find_metric(m.exists_with);
      ASSERT_NE(event, nullptr) << m.exists_with;
      EXPECT_EQ(std::isnan(v), !(event->get(r) > 0.0));
      if (!std::isnan(v)) {
        EXPECT_GE(v, 0.0);
        EXPECT_LE(v, r.t_end_s);
      }
    } else if (name == "omega_max_rad_s") {
      EXPECT_EQ(std::isnan(v), !omega_requested);
    } else if (name == "strain_column_max" || name == "strain_beam_max") {
      EXPECT_EQ(std::isnan(v), !tendons);
    } else {
      EXPECT_TRUE(std::isfinite(v)) << "always a number";
    }
  }
  if (!lifted) {
    EXPECT_EQ(r.theta_max_rad, 0.0);
    EXPECT_EQ(r.impacts, 0);
  }
}

class ResultContract : public ::testing::TestWithParam<Integrator> {};

TEST_P(ResultContract, EveryPathSetsEveryMetricItClaims) {
  const bool fixed = !registry_entry(GetParam()).can.locates_events;
  for (const Path& path : paths(GetParam())) {
    for (const bool omega : {true, false}) {
      SCOPED_TRACE(path.name + (omega ? ", omega requested" : ", omega not requested"));
      OutputRequest request;
      request.omega_peak = omega;
      const CaseResult r = solve_case(basic_frame(), path.record, path.physics, path.solver, request);
      EXPECT_EQ(r.status, path.expected) << r.message;
      expect_contract(r, omega || fixed, false, true);
    }
  }
}

TEST_P(ResultContract, TheVerdictCheckFillsItsMetrics) {
  SolverSettings solver;
  solver.integrator = GetParam();
  solver.fixed_step_s = 1e-3;
  solver.verdict_check = true;
  const CaseResult r = solve_case(basic_frame(), test::strong_record(7, 12.0).scaled(3.0), {}, solver);
  expect_contract(r, true, true, true);
}

TEST_P(ResultContract, AScenewithoutTendonsHasNoStrains) {
  SolverSettings solver;
  solver.integrator = GetParam();
  solver.fixed_step_s = 1e-3;
  RockerParameters block;
  block.slenderness_rad = 0.2;
  block.size_m = 1.0;
  const auto prepared = prepare_scene(std::make_unique<RigidRocker>(block), {});
  for (const GroundMotion& record : {test::quiet_record(2.0), test::strong_record(7, 4.0).scaled(0.2)}) {
    const CaseResult r = solve_case(*prepared, record, solver);
    expect_contract(r, true, false, false);
  }
}

// Every integrator of the registry (taylor included: on the block below it takes its own
// steps, on the prestressed frame its without_series, dopri5).
TEST_P(ResultContract, EveryPathOfTheBlockSetsEveryMetricItClaims) {
  // The rigid block: the scene whose series the Taylor steps take (the prestressed frame
  // above has none). Never lifts, rocks, overturns, starts displaced; out of steps or time.
  SolverSettings solver;
  solver.integrator = GetParam();
  solver.fixed_step_s = 1e-3;
  const bool fixed = !registry_entry(GetParam()).can.locates_events;
  RockerParameters block;
  block.slenderness_rad = 0.2;
  block.size_m = 1.0;
  const auto prepared = [&](const PhysicsOptions& physics) {
    return prepare_scene(std::make_unique<RigidRocker>(block), physics);
  };
  const PhysicsOptions physics = test::record_only();
  PhysicsOptions displaced = physics;
  displaced.theta0_rad = -0.02;
  PulseSpec pulse;  // a long pulse at five times the uplift threshold tips the block over
  pulse.amplitude_g = 1.0;
  pulse.period_s = 2.0;
  pulse.duration_s = 4.0;
  struct BlockPath {
    std::string name;
    GroundMotion record;
    PhysicsOptions physics;
    SolverSettings solver;
    CaseStatus expected;
  };
  std::vector<BlockPath> paths = {
      {"never lifts", test::quiet_record(2.0), physics, solver, CaseStatus::kAtRest},
      {"overturns", make_pulse(pulse), physics, solver, CaseStatus::kOverturned},
      {"displaced start", test::quiet_record(0.5), displaced, solver, CaseStatus::kRockingAtEnd}};
  if (!fixed) {  // the contender has no step or time budget
    SolverSettings starved = solver;
    starved.max_steps = 3;
    paths.push_back({"solver failure", test::strong_record(7, 4.0), physics, starved, CaseStatus::kSolverFailure});
    SolverSettings hurried = solver;
    hurried.wall_time_limit_s = 1e-9;
    paths.push_back({"time limit", test::strong_record(7, 4.0), physics, hurried, CaseStatus::kTimeLimit});
  }
  for (const BlockPath& path : paths) {
    for (const bool omega : {true, false}) {
      SCOPED_TRACE(path.name + (omega ? ", omega requested" : ", omega not requested"));
      OutputRequest request;
      request.omega_peak = omega;
      const CaseResult r = solve_case(*prepared(path.physics), path.record, path.solver, request);
      EXPECT_EQ(r.status, path.expected) << r.message;
      expect_contract(r, omega || fixed, false, false);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Integrators, ResultContract, ::testing::ValuesIn(test::every_integrator()),
                         test::integrator_test_name);

}  // namespace
}  // namespace pcrf
