// A group of cases (pcrf/solver/case_group.hpp) and the integrator registry
// (pcrf/solver/integrator_registry.hpp): each backend gives solve_case's answers bit for bit;
// a case a backend refuses is that case's answer, the others solved; the registry is the one
// list every consumer reads, and what it says an integrator can do is what the integrator does.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "batch_design.hpp"
#include "pcrf/solver/case_group.hpp"
#include "pcrf/solver/integrator_registry.hpp"
#include "solver/case/case_run.hpp"  // private to the solver: the test makes each integrator
#include "solver_test_support.hpp"

namespace pcrf {
namespace {

/// Twelve blocks and rocking frames of a design, plus one whose initial state is impossible
/// (|θ₀| beyond its overturning angle: solve_case refuses it) in the middle.
struct Group {
  std::vector<std::shared_ptr<PreparedFrame>> frames;
  std::vector<PreparedFrame*> views;
  std::size_t refused_at = 0;
  GroundMotion record = test::strong_record(5, 3.0);

  Group() {
    PhysicsOptions physics;
    physics.max_tail_s = 2.0;
    auto blocks = test::design(test::SceneKind::kBlock, 6, physics);
    auto rocking = test::design(test::SceneKind::kRockingFrame, 6, physics);
    frames = blocks;
    PhysicsOptions impossible = physics;
    impossible.theta0_rad = 2.0;  // rad: beyond any block's overturning angle (below π/2)
    RockerParameters block;
    block.slenderness_rad = 0.2;
    block.size_m = 1.0;
    refused_at = frames.size();
    frames.push_back(prepare_scene(std::make_unique<RigidRocker>(block), impossible));
    frames.insert(frames.end(), rocking.begin(), rocking.end());
    for (auto& f : frames) views.push_back(f.get());
    record = record.scaled(0.6 / record.pga_m_s2() * kGravity_m_s2);  // PGA 0.6 g: most rock, some rest
  }
};

class EveryGroupSolver : public ::testing::TestWithParam<int> {};  // lanes: 1 one at a time, else the CPU lanes

TEST_P(EveryGroupSolver, GivesSolveCasesAnswersAndRefusesOnlyTheImpossibleCase) {
  Group g;
  for (const char* preset : {"fast", "balanced"}) {
    for (const Integrator integrator : {Integrator::kDormandPrince5, Integrator::kTaylor, Integrator::kCvodeAdams}) {
      SolverSettings solver = preset_settings(preset);
      solver.integrator = integrator;
      SCOPED_TRACE(std::string(preset) + " " + to_string(integrator));
      const auto group = make_group_solver(solver, GetParam());
      EXPECT_EQ(group->name(), GetParam() > 1 && registry_entry(integrator).can.in_lanes ? "cpu-lanes" : "one-at-a-time");
      const std::vector<GroupCase> answers = group->solve(g.views, g.record, solver, {});
      ASSERT_EQ(answers.size(), g.views.size());
      int rocked = 0;
      for (std::size_t i = 0; i < answers.size(); ++i) {
        if (i == g.refused_at) {
          EXPECT_EQ(answers[i].outcome, GroupOutcome::kRefused);
          EXPECT_NE(answers[i].result.message.find("theta0_rad"), std::string::npos) << answers[i].result.message;
          EXPECT_THROW(solve_case(*g.views[i], g.record, solver), std::invalid_argument);
          continue;
        }
        ASSERT_EQ(answers[i].outcome, GroupOutcome::kSolved) << answers[i].result.message;
        test::expect_same(answers[i].result, solve_case(*g.views[i], g.record, solver), 0.0, "case " + std::to_string(i));
        rocked += answers[i].result.impacts > 0 ? 1 : 0;
      }
      EXPECT_GT(rocked, 3);  // the group is not trivially at rest
    }
  }
}

TEST_P(EveryGroupSolver, TakesAHistoryOnlyForAGroupOfOne) {
  Group g;
  const SolverSettings solver = preset_settings("balanced");
  const auto group = make_group_solver(solver, GetParam());
  test::Trace trace, alone;
  PreparedFrame* const one[] = {g.views[0]};
  const auto answer = group->solve(one, g.record, solver, {}, trace.sink());
  solve_case(*g.views[0], g.record, solver, {}, alone.sink());
  ASSERT_EQ(answer.size(), 1u);
  EXPECT_EQ(trace.samples.size(), alone.samples.size());
  EXPECT_GT(trace.samples.size(), 10u);
  EXPECT_THROW(group->solve(g.views, g.record, solver, {}, trace.sink()), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Lanes, EveryGroupSolver, ::testing::Values(1, 4, 8));

TEST(IntegratorRegistry, NamesAreUniqueAndAreTheSettingsSpelling) {
  std::set<std::string> names;
  for (const IntegratorEntry& e : integrator_registry()) {
    EXPECT_TRUE(names.insert(std::string(e.name)).second) << e.name;
    EXPECT_EQ(to_string(e.id), e.name);
    EXPECT_EQ(parse_integrator(std::string(e.name)), e.id);
    EXPECT_EQ(&registry_entry(e.id), &e);
  }
  EXPECT_EQ(integrator_choices(), test::every_integrator());
  const auto& table = solver_settings();
  const auto row = std::find_if(table.settings.begin(), table.settings.end(), [](const auto& s) { return s.key == "integrator"; });
  ASSERT_NE(row, table.settings.end());
  EXPECT_EQ(row->choices.size(), names.size());
  try {
    parse_integrator("rk45");
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    for (const std::string& name : names) EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
  }
}

TEST(IntegratorRegistry, EveryPresetNamesARegisteredIntegrator) {
  for (const std::string& preset : preset_names()) EXPECT_NO_THROW(registry_entry(preset_settings(preset).integrator)) << preset;
}

TEST(IntegratorRegistry, WhatAnEntrySaysItCanDoTheIntegratorItMakesDoes) {
  RockerParameters block;
  block.slenderness_rad = 0.2;
  block.size_m = 1.0;
  const auto prepared = prepare_scene(std::make_unique<RigidRocker>(block), {});
  const GroundMotion record = test::strong_record(3, 2.0);
  for (const IntegratorEntry& e : integrator_registry()) {
    SCOPED_TRACE(std::string(e.name));
    // A stepper or a method with its own case loop, never both.
    EXPECT_NE(e.make == nullptr, e.solve == nullptr);
    if (e.can.needs_series) {
      const IntegratorEntry& fallback = registry_entry(e.without_series);
      EXPECT_FALSE(fallback.can.needs_series);
      EXPECT_NE(fallback.make, nullptr);
    }
    // The lanes take it: in lockstep itself, or its cases without a series do.
    if (e.can.in_lanes) {
      EXPECT_TRUE(e.can.lockstep || registry_entry(e.without_series).can.lockstep);
    }
    EXPECT_EQ(lanes_take([&] { SolverSettings s; s.integrator = e.id; return s; }()), e.can.in_lanes);
    if (e.make == nullptr) continue;
    SolverSettings solver;
    solver.integrator = e.id;
    solver.stop_at_samples = true;
    const Excitation excitation(record);
    detail::FlightProblem problem(prepared->scene(), prepared->table(), excitation, 1.0, true);
    const detail::SampleGrid samples{record.dt_s(), record.size()};
    const auto made = detail::make_integrator(solver, problem, samples);
    EXPECT_EQ(made->steps_between_samples(), e.can.steps_between_samples);
    if (e.can.lockstep) {
      EXPECT_NE(detail::make_integrator(solver, problem, samples, true), nullptr);
    } else {
      EXPECT_THROW(detail::make_integrator(solver, problem, samples, true), detail::IntegratorError);
    }
  }
}

}  // namespace
}  // namespace pcrf
