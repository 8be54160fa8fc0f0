/// \file solver_test_support.hpp
/// \brief Records and settings shared by the solver tests.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include <vector>

#include "pcrf/record/ground_motion.hpp"
#include "pcrf/record/synthetic.hpp"
#include "pcrf/solver/integrator_registry.hpp"
#include "pcrf/solver/rocking_solver.hpp"

namespace pcrf::test {

/// No ground motion for `duration_s`.
inline GroundMotion quiet_record(double duration_s, double dt_s = 0.01) {
  return GroundMotion("quiet", dt_s, std::vector<double>(static_cast<std::size_t>(duration_s / dt_s) + 1, 0.0));
}

/// A seeded stochastic record strong enough to rock the basic frame (PGA 2 g).
inline GroundMotion strong_record(std::uint64_t seed = 7, double duration_s = 12.0) {
  StochasticSpec s;
  s.seed = seed;
  s.pga_g = 2.0;
  s.duration_s = duration_s;
  s.dt_s = 0.01;
  return make_stochastic(s);
}

/// Physics whose case ends with its record (tail_s = 0), for tests written about a fixed span
/// of time: the default tail (until the frame rests) would run past it.
inline PhysicsOptions record_only() {
  PhysicsOptions physics;
  physics.tail_s = 0.0;
  return physics;
}

inline SolverSettings tight(Integrator i = Integrator::kDormandPrince5) {
  SolverSettings s;
  s.integrator = i;
  s.rtol = 1e-12;
  s.atol_theta_rad = 1e-15;
  s.atol_omega_rad_s = 1e-13;
  return s;
}

/// Every integrator of the registry: the parameters of the tests that run "every integrator",
/// so that a family added to the registry is tested without editing them.
inline std::vector<Integrator> every_integrator() {
  std::vector<Integrator> ids;
  for (const IntegratorEntry& e : integrator_registry()) ids.push_back(e.id);
  return ids;
}

/// Those that locate their events (IntegratorCapabilities::locates_events): the tests of exact
/// physics (energy between and across impacts, bit-for-bit mirrored motion, convergence of a
/// located peak) leave out the fixed-step contender, which sees an impact only as a sign
/// change at a step's end and never puts a frame back at rest.
inline std::vector<Integrator> event_locating_integrators() {
  std::vector<Integrator> ids;
  for (const IntegratorEntry& e : integrator_registry())
    if (e.can.locates_events) ids.push_back(e.id);
  return ids;
}

/// A parameterised test's name for an integrator ("cvode_adams"): gtest names take no '-'.
inline std::string integrator_test_name(const ::testing::TestParamInfo<Integrator>& info) {
  std::string n = to_string(info.param);
  for (auto& c : n) c = c == '-' ? '_' : c;
  return n;
}

struct Trace {
  std::vector<HistorySample> samples;
  HistorySink sink() {
    return [this](const HistorySample& s) { samples.push_back(s); };
  }
};

/// `b` is `a` mirrored, row by row and bit for bit: the same times, θ₁ and θ̇₁ of opposite
/// signs (and, for a frame with tendons, the left column's strain where the right's was).
inline void expect_mirrored(const Trace& a, const Trace& b, bool tendons = false) {
  ASSERT_EQ(a.samples.size(), b.samples.size());
  for (std::size_t i = 0; i < a.samples.size(); ++i) {
    EXPECT_EQ(a.samples[i].t_s, b.samples[i].t_s);
    EXPECT_EQ(a.samples[i].theta1_rad, -b.samples[i].theta1_rad) << "t = " << a.samples[i].t_s;
    EXPECT_EQ(a.samples[i].omega1_rad_s, -b.samples[i].omega1_rad_s) << "t = " << a.samples[i].t_s;
    if (tendons) {
      EXPECT_EQ(a.samples[i].strain_column_left, b.samples[i].strain_column_right);
    }
  }
}

}  // namespace pcrf::test
