// The pulse library against its closed forms: exact PGA, PGV from each formula, the Cₙ
// phases of Makris & Roussos (2000), the Ricker wavelets' spectral peak at 1/T_p.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>
#include <string>

#include "pcrf/record/intensity.hpp"
#include "pcrf/record/pulses.hpp"
#include "pcrf/record/synthetic.hpp"

namespace {

using pcrf::PulseShape;
using pcrf::PulseSpec;

constexpr PulseShape kShapes[] = {PulseShape::kSine,   PulseShape::kCosine,
                                  PulseShape::kCycles, PulseShape::kRicker,
                                  PulseShape::kRickerAntisymmetric, PulseShape::kMavroeidis};

PulseSpec spec_of(PulseShape shape, double dt_s) {
  PulseSpec p;
  p.shape = shape;
  p.period_s = 0.37;
  p.amplitude_g = 0.8;
  p.dt_s = dt_s;
  p.cycles = 2;
  p.gamma = 2.5;
  return p;
}

TEST(Pulses, EveryPulseHasItsAmplitudeAsItsExactPga) {
  for (const PulseShape shape : kShapes) {
    for (const double dt : {0.005, 0.0037, 0.001}) {
      const PulseSpec p = spec_of(shape, dt);
      const pcrf::GroundMotion g = pcrf::make_pulse(p);
      EXPECT_EQ(g.pga_m_s2(), p.amplitude_g * pcrf::kGravity_m_s2) << pcrf::pulse_kind(shape) << " dt " << dt;
      EXPECT_EQ(g.samples_m_s2().size() > 1, true);
    }
  }
}

TEST(Pulses, PeakVelocityOfTheRecordConvergesToTheClosedForm) {
  for (const PulseShape shape : kShapes) {
    SCOPED_TRACE(pcrf::pulse_kind(shape));
    // Second order in dt (trapezoid, linear interpolation): the error falls ~4× per halving.
    double previous_error = 0.0;
    for (const double dt : {0.37 / 200, 0.37 / 400, 0.37 / 800}) {
      const PulseSpec p = spec_of(shape, dt);
      const double exact = pcrf::pulse_peak_velocity_m_s(p);
      const double error = std::abs(pcrf::peak_velocity_m_s(pcrf::make_pulse(p)) - exact) / exact;
      EXPECT_LT(error, 2e-4) << "dt " << dt;
      if (previous_error > 1e-9) {
        EXPECT_LT(error, 0.4 * previous_error) << "dt " << dt;
      }
      previous_error = error;
    }
  }
}

TEST(Pulses, ClosedFormVelocitiesAreTheKnownMultiplesOfAmplitudeTimesPeriod) {
  const double a_p = 0.8 * pcrf::kGravity_m_s2, T = 0.37, pi = std::numbers::pi;
  EXPECT_DOUBLE_EQ(pcrf::pulse_peak_velocity_m_s(spec_of(PulseShape::kSine, 0.001)), a_p * T / pi);
  EXPECT_DOUBLE_EQ(pcrf::pulse_peak_velocity_m_s(spec_of(PulseShape::kCosine, 0.001)), a_p * T / (2 * pi));
  // Mavroeidis–Papageorgiou at ν = 0: the velocity peaks at the envelope's centre, v = A.
  PulseSpec mp = spec_of(PulseShape::kMavroeidis, 0.001);
  mp.nu_deg = 0.0;
  const double from_record = pcrf::peak_velocity_m_s(pcrf::make_pulse(mp));
  EXPECT_NEAR(from_record, pcrf::pulse_peak_velocity_m_s(mp), 1e-4 * from_record);
}

TEST(Pulses, CyclesPulsesHaveThePhasesOfMakrisAndRoussosAndEndAtRest) {
  // Makris & Roussos (2000), Géotechnique 50(3): φ = 0.0697π (C₁) and 0.0410π (C₂).
  EXPECT_NEAR(pcrf::cycles_pulse_phase_rad(1) / std::numbers::pi, 0.0697, 5e-5);
  EXPECT_NEAR(pcrf::cycles_pulse_phase_rad(2) / std::numbers::pi, 0.0410, 5e-5);
  for (const int n : {1, 2, 3}) {
    PulseSpec p = spec_of(PulseShape::kCycles, 0.37 / 2000);
    p.cycles = n;
    const pcrf::GroundMotion g = pcrf::make_pulse(p);
    double v = 0.0, d = 0.0;
    const auto& a = g.samples_m_s2();
    for (std::size_t i = 1; i < a.size(); ++i) {
      const double v_next = v + 0.5 * g.dt_s() * (a[i - 1] + a[i]);
      d += 0.5 * g.dt_s() * (v + v_next);
      v = v_next;
    }
    // The jump at the pulse's end is a ramp over one sample: the ground keeps at most
    // a_p cos φ · dt/2 of velocity, and the displacement drifts accordingly.
    const double a_p = p.amplitude_g * pcrf::kGravity_m_s2;
    EXPECT_LT(std::abs(v), a_p * g.dt_s()) << "n = " << n << ": the ground stops";
    EXPECT_LT(std::abs(d), a_p * g.dt_s() * g.duration_s()) << "n = " << n << ": where it started";
    EXPECT_GT(pcrf::peak_displacement_m(g), 100.0 * std::abs(d)) << "n = " << n;
  }
}

/// |∫ a(t) e^{−2πi f t} dt| of a record (trapezoid).
double fourier_amplitude(const pcrf::GroundMotion& g, double f_hz) {
  std::complex<double> sum = 0.0;
  const auto& a = g.samples_m_s2();
  for (std::size_t i = 0; i < a.size(); ++i)
    sum += a[i] * std::exp(std::complex<double>(0.0, -2.0 * std::numbers::pi * f_hz * g.dt_s() * static_cast<double>(i)));
  return std::abs(sum) * g.dt_s();
}

TEST(Pulses, RickerWaveletsPeakInFrequencyAtOneOverTheirPeriod) {
  for (const PulseShape shape : {PulseShape::kRicker, PulseShape::kRickerAntisymmetric}) {
    const PulseSpec p = spec_of(shape, 0.001);
    const pcrf::GroundMotion g = pcrf::make_pulse(p);
    const double f_p = 1.0 / p.period_s;
    double best_f = 0.0, best = 0.0;
    for (double f = 0.5 * f_p; f <= 1.5 * f_p; f += 0.002 * f_p) {
      const double amplitude = fourier_amplitude(g, f);
      if (amplitude > best) best = amplitude, best_f = f;
    }
    EXPECT_NEAR(best_f, f_p, 0.004 * f_p) << pcrf::pulse_kind(shape);
  }
}

TEST(Pulses, BadPulsesAreRefusedNamingTheField) {
  const std::vector<std::pair<std::string, std::string>> corpus = {
      {"pulse-sine:period_s=0.01,dt_s=0.005", "period_s of pulse-sine = 0.01"},
      {"pulse-sine:period_s=-1", "period_s of pulse-sine must be positive"},
      {"ricker:amplitude_g=0", "amplitude_g of ricker must be positive"},
      {"pulse-cycles:cycles=0", "cycles of pulse-cycles must be at least 1"},
      {"mavroeidis:gamma=1", "gamma of mavroeidis must be above 1"},
      // The key as the user wrote it, and the value in full: 1e-07, not 0.000000.
      {"ricker:period_s=1e-7", "period_s of ricker = 1e-07 s"},
      {"ricker:period_s=0", "period_s of ricker must be positive and finite, got 0"},
      {"ricker:cycles=2", "unknown key 'cycles' for ricker"},
      {"pulse-square:period_s=1", "unknown kind 'pulse-square'"},
  };
  for (const auto& [text, message] : corpus) {
    try {
      pcrf::make_synthetic(text);
      ADD_FAILURE() << text << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << text << ": " << e.what();
    }
  }
  const pcrf::GroundMotion named = pcrf::make_synthetic("pulse-sine:period_s=0.5,amplitude_g=0.3");
  EXPECT_EQ(named.name(), "pulse-sine:period_s=0.5,amplitude_g=0.3");
  EXPECT_DOUBLE_EQ(named.pga_m_s2(), 0.3 * pcrf::kGravity_m_s2);
}

}  // namespace
