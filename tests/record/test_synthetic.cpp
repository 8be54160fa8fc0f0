/// \file test_synthetic.cpp
/// \brief Synthetic records: sine pulse values, stochastic determinism and exact PGA, the
/// Kanai–Tajimi spectral shape and the envelope (checked statistically against the formulas in
/// synthetic.hpp), spec validation and the "kind:key=value" parser.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "pcrf/record/synthetic.hpp"

namespace {

using pcrf::GroundMotion;
using pcrf::kGravity_m_s2;
using pcrf::SinePulseSpec;
using pcrf::StochasticSpec;

std::string invalid_argument_message(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  ADD_FAILURE() << "no std::invalid_argument";
  return "";
}

// ---- sine pulse train ---------------------------------------------------------------------

TEST(SinePulse, ValuesFollowTheFormulaThenZero) {
  SinePulseSpec spec;
  spec.amplitude_g = 0.3;
  spec.period_s = 0.4;
  spec.cycles = 3;
  spec.duration_s = 2.0;
  spec.dt_s = 0.01;
  const GroundMotion g = pcrf::make_sine_pulse_train(spec);
  ASSERT_EQ(g.size(), 201u);
  EXPECT_EQ(g.dt_s(), 0.01);
  EXPECT_DOUBLE_EQ(g.duration_s(), 2.0);
  const double amplitude_m_s2 = 0.3 * kGravity_m_s2;
  for (std::size_t i = 0; i < g.size(); ++i) {
    const double t_s = static_cast<double>(i) * 0.01;
    // Sample 120 (t = 1.2 = 3·T_p) is the end of the train, where sin is 0 either way.
    const double expected = t_s < 1.2 - 1e-9 ? amplitude_m_s2 * std::sin(2 * std::numbers::pi * t_s / 0.4) : 0.0;
    EXPECT_NEAR(g.samples_m_s2()[i], expected, 1e-12) << "t = " << t_s;
  }
  // dt divides T/4, so the crests are sampled: peak = A.
  EXPECT_NEAR(g.pga_m_s2(), amplitude_m_s2, 1e-12);
  EXPECT_NEAR(g.accel_m_s2(0.1), amplitude_m_s2, 1e-12);   // first crest
  EXPECT_NEAR(g.accel_m_s2(0.3), -amplitude_m_s2, 1e-12);  // first trough
  EXPECT_EQ(g.accel_m_s2(1.5), 0.0);
  EXPECT_EQ(g.accel_m_s2(2.5), 0.0);  // beyond the record
}

TEST(SinePulse, DefaultsAndName) {
  const GroundMotion g = pcrf::make_sine_pulse_train(SinePulseSpec{});
  EXPECT_EQ(g.size(), 1001u);  // 5 s at 0.005 s
  EXPECT_EQ(g.dt_s(), 0.005);
  EXPECT_NEAR(g.pga_m_s2(), 0.5 * kGravity_m_s2, 1e-12);
  EXPECT_EQ(g.name(), "sine:amplitude_g=0.5,period_s=0.5,cycles=2,duration_s=5,dt_s=0.005");
  // The name is the text form and makes the same record.
  EXPECT_EQ(pcrf::make_synthetic(g.name()).samples_m_s2(), g.samples_m_s2());
}

TEST(SinePulse, DurationEqualToTheTrainIsAllowed) {
  SinePulseSpec spec;
  spec.cycles = 1;
  spec.period_s = 0.3;
  spec.duration_s = 0.3;
  spec.dt_s = 0.01;
  const GroundMotion g = pcrf::make_sine_pulse_train(spec);
  EXPECT_EQ(g.size(), 31u);
}

TEST(SinePulse, InvalidSpecsNameTheField) {
  struct Case {
    const char* field;
    std::function<void(SinePulseSpec&)> spoil;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Case> cases = {
      {"amplitude_g", [](SinePulseSpec& s) { s.amplitude_g = 0.0; }},
      {"amplitude_g", [&](SinePulseSpec& s) { s.amplitude_g = nan; }},
      {"period_s", [](SinePulseSpec& s) { s.period_s = -0.5; }},
      {"period_s", [](SinePulseSpec& s) { s.period_s = 0.015; }},  // < 4·dt
      {"cycles", [](SinePulseSpec& s) { s.cycles = 0; }},
      {"duration_s", [](SinePulseSpec& s) { s.duration_s = 0.9; }},  // < 2 · 0.5
      {"duration_s", [](SinePulseSpec& s) { s.duration_s = std::numeric_limits<double>::infinity(); }},
      {"duration_s", [](SinePulseSpec& s) { s.duration_s = 1e7; }},  // > 1e8 samples
      {"dt_s", [](SinePulseSpec& s) { s.dt_s = 0.0; }},
      {"dt_s", [](SinePulseSpec& s) { s.dt_s = -0.01; }},
  };
  for (const Case& c : cases) {
    SinePulseSpec spec;
    c.spoil(spec);
    const std::string m = invalid_argument_message([&] { (void)pcrf::make_sine_pulse_train(spec); });
    EXPECT_NE(m.find(std::string(c.field) + " of sine"), std::string::npos) << m;
  }
}

// ---- stochastic record ----------------------------------------------------------------------

StochasticSpec short_spec(std::uint64_t seed) {
  StochasticSpec s;
  s.seed = seed;
  s.pga_g = 0.4;
  s.duration_s = 10.0;
  s.dt_s = 0.01;
  return s;
}

TEST(Stochastic, SameSeedSameSamplesOtherSeedOtherSamples) {
  const GroundMotion a = pcrf::make_stochastic(short_spec(3));
  const GroundMotion b = pcrf::make_stochastic(short_spec(3));
  const GroundMotion c = pcrf::make_stochastic(short_spec(4));
  EXPECT_EQ(a.samples_m_s2(), b.samples_m_s2());
  ASSERT_EQ(a.size(), c.size());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < a.size(); ++i) differing += a.samples_m_s2()[i] != c.samples_m_s2()[i];
  EXPECT_GT(differing, a.size() * 9 / 10);  // all but the first sample (0 for every seed)
}

TEST(Stochastic, PeakEqualsRequestedPgaExactly) {
  for (const double pga_g : {0.4, 0.123456789, 1.0, 0.05}) {
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
      StochasticSpec spec = short_spec(seed);
      spec.pga_g = pga_g;
      const GroundMotion g = pcrf::make_stochastic(spec);
      EXPECT_EQ(g.pga_m_s2(), pga_g * kGravity_m_s2) << "seed " << seed << " pga " << pga_g;
    }
  }
}

TEST(Stochastic, LengthStepFirstSampleAndName) {
  const GroundMotion g = pcrf::make_stochastic(short_spec(7));
  EXPECT_EQ(g.size(), 1001u);
  EXPECT_EQ(g.dt_s(), 0.01);
  EXPECT_EQ(g.samples_m_s2().front(), 0.0);  // filter at rest, envelope 0 at t = 0
  EXPECT_EQ(pcrf::make_synthetic(g.name()).samples_m_s2(), g.samples_m_s2());
  EXPECT_NE(g.name().find("seed=7"), std::string::npos) << g.name();
}

/// Kanai–Tajimi |H|² from synthetic.hpp's filter, r = f / f_g.
double kanai_tajimi_gain2(double f_hz, double fg_hz, double zeta) {
  const double r2 = (f_hz / fg_hz) * (f_hz / fg_hz);
  return (1.0 + 4.0 * zeta * zeta * r2) / ((1.0 - r2) * (1.0 - r2) + 4.0 * zeta * zeta * r2);
}

TEST(Stochastic, SpectrumHasTheKanaiTajimiShape) {
  // A long stationary record (no rise, plateau past the end): average Hann-windowed
  // periodograms over 512-sample segments and compare band powers with |H|².
  StochasticSpec spec;
  spec.seed = 11;
  spec.dt_s = 0.01;
  spec.duration_s = 2000.0;
  spec.ground_freq_hz = 2.5;
  spec.ground_damping = 0.3;
  spec.rise_s = 0.0;
  spec.strong_s = 1e6;
  const GroundMotion g = pcrf::make_stochastic(spec);
  const auto& a = g.samples_m_s2();

  constexpr std::size_t kLen = 512;
  const double df_hz = 1.0 / (kLen * spec.dt_s);
  const std::size_t max_bin = 45;  // ≈ 8.8 Hz
  std::vector<double> power(max_bin + 1, 0.0);
  std::vector<double> window(kLen);
  for (std::size_t j = 0; j < kLen; ++j) {
    window[j] = 0.5 - 0.5 * std::cos(2 * std::numbers::pi * static_cast<double>(j) / kLen);
  }
  for (std::size_t start = 100; start + kLen <= a.size(); start += kLen) {
    for (std::size_t k = 1; k <= max_bin; ++k) {
      double re = 0.0, im = 0.0;
      for (std::size_t j = 0; j < kLen; ++j) {
        const double phase = 2 * std::numbers::pi * static_cast<double>(k * j % kLen) / kLen;
        re += window[j] * a[start + j] * std::cos(phase);
        im += window[j] * a[start + j] * std::sin(phase);
      }
      power[k] += re * re + im * im;
    }
  }
  const auto band = [&](double lo_hz, double hi_hz, bool theory) {
    double sum = 0.0;
    int n = 0;
    for (std::size_t k = 1; k <= max_bin; ++k) {
      const double f_hz = static_cast<double>(k) * df_hz;
      if (f_hz < lo_hz || f_hz > hi_hz) continue;
      sum += theory ? kanai_tajimi_gain2(f_hz, 2.5, 0.3) : power[k];
      ++n;
    }
    return sum / n;
  };
  const double low = band(0.3, 1.0, false), low_th = band(0.3, 1.0, true);
  const double peak = band(2.0, 3.0, false), peak_th = band(2.0, 3.0, true);
  const double high = band(6.0, 8.5, false), high_th = band(6.0, 8.5, true);
  EXPECT_NEAR((peak / low) / (peak_th / low_th), 1.0, 0.15);
  EXPECT_NEAR((high / low) / (high_th / low_th), 1.0, 0.15);
  // The shape is pronounced enough that these checks discriminate.
  EXPECT_GT(peak_th / low_th, 2.5);
  EXPECT_LT(high_th / low_th, 0.15);
}

/// Envelope from synthetic.hpp, squared, averaged over [t0, t1] by the midpoint rule.
double mean_envelope2(const StochasticSpec& s, double t0, double t1) {
  constexpr int kSteps = 20000;
  double sum = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double t = t0 + (t1 - t0) * (i + 0.5) / kSteps;
    double e = 1.0;
    if (t < s.rise_s) e = (t / s.rise_s) * (t / s.rise_s);
    else if (t > s.rise_s + s.strong_s) e = std::exp(-s.decay_per_s * (t - s.rise_s - s.strong_s));
    sum += e * e;
  }
  return sum / kSteps;
}

double mean_square(const GroundMotion& g, double t0, double t1) {
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < g.size(); ++i) {
    const double t = static_cast<double>(i) * g.dt_s();
    if (t < t0 || t > t1) continue;
    sum += g.samples_m_s2()[i] * g.samples_m_s2()[i];
    ++n;
  }
  return sum / n;
}

TEST(Stochastic, EnvelopeShapesTheIntensity) {
  // Slow envelope so each window holds many correlation times; mean squares relative to the
  // plateau (which cancels the PGA scaling) against the envelope formula.
  StochasticSpec spec;
  spec.dt_s = 0.01;
  spec.duration_s = 600.0;
  spec.rise_s = 200.0;
  spec.strong_s = 200.0;
  spec.decay_per_s = 0.01;
  const double plateau_th = mean_envelope2(spec, 210, 390);
  struct Window {
    double t0, t1;
  };
  const std::vector<Window> windows = {{30, 90}, {120, 190}, {420, 480}, {500, 590}};
  std::vector<double> ratio(windows.size(), 0.0);
  constexpr int kSeeds = 5;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    spec.seed = static_cast<std::uint64_t>(seed);
    const GroundMotion g = pcrf::make_stochastic(spec);
    const double plateau = mean_square(g, 210, 390);
    for (std::size_t w = 0; w < windows.size(); ++w) {
      ratio[w] += mean_square(g, windows[w].t0, windows[w].t1) / plateau / kSeeds;
    }
  }
  for (std::size_t w = 0; w < windows.size(); ++w) {
    const double th = mean_envelope2(spec, windows[w].t0, windows[w].t1) / plateau_th;
    EXPECT_NEAR(ratio[w] / th, 1.0, 0.08) << "window [" << windows[w].t0 << ", " << windows[w].t1 << "]";
  }
}

TEST(Stochastic, InvalidSpecsNameTheField) {
  struct Case {
    const char* field;
    std::function<void(StochasticSpec&)> spoil;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Case> cases = {
      {"pga_g", [](StochasticSpec& s) { s.pga_g = 0.0; }},
      {"pga_g", [&](StochasticSpec& s) { s.pga_g = nan; }},
      {"duration_s", [](StochasticSpec& s) { s.duration_s = -1.0; }},
      {"duration_s", [](StochasticSpec& s) { s.duration_s = 0.005; }},  // < dt
      {"duration_s", [](StochasticSpec& s) { s.duration_s = 1e7; }},    // > 1e8 samples
      {"dt_s", [](StochasticSpec& s) { s.dt_s = 0.0; }},
      {"ground_freq_hz", [](StochasticSpec& s) { s.ground_freq_hz = 0.0; }},
      {"ground_freq_hz", [](StochasticSpec& s) { s.ground_freq_hz = 50.0; }},  // Nyquist at dt 0.01
      {"ground_damping", [](StochasticSpec& s) { s.ground_damping = -0.1; }},
      {"rise_s", [](StochasticSpec& s) { s.rise_s = -1.0; }},
      {"strong_s", [&](StochasticSpec& s) { s.strong_s = nan; }},
      {"decay_per_s", [](StochasticSpec& s) { s.decay_per_s = -0.35; }},
  };
  for (const Case& c : cases) {
    StochasticSpec spec;
    c.spoil(spec);
    const std::string m = invalid_argument_message([&] { (void)pcrf::make_stochastic(spec); });
    EXPECT_NE(m.find(std::string(c.field) + " of stochastic"), std::string::npos) << m;
  }
}

TEST(Stochastic, OverdampedAndCriticalFiltersWork) {
  for (const double zeta : {1.0, 2.0}) {
    StochasticSpec spec = short_spec(5);
    spec.ground_damping = zeta;
    const GroundMotion g = pcrf::make_stochastic(spec);
    EXPECT_EQ(g.pga_m_s2(), 0.4 * kGravity_m_s2) << zeta;
  }
}

// ---- text form ------------------------------------------------------------------------------

TEST(MakeSynthetic, TextGivesTheSameRecordAsTheSpec) {
  SinePulseSpec sine;
  sine.amplitude_g = 0.25;
  sine.period_s = 0.8;
  sine.cycles = 1;
  sine.duration_s = 3;
  sine.dt_s = 0.01;
  const std::string text = "sine:amplitude_g=0.25,period_s=0.8,cycles=1,duration_s=3,dt_s=0.01";
  const GroundMotion from_text = pcrf::make_synthetic(text);
  EXPECT_EQ(from_text.name(), text);
  EXPECT_EQ(from_text.samples_m_s2(), pcrf::make_sine_pulse_train(sine).samples_m_s2());
  EXPECT_EQ(from_text.dt_s(), 0.01);

  StochasticSpec sto;
  sto.seed = 3;
  sto.pga_g = 0.4;
  sto.duration_s = 20;
  sto.dt_s = 0.01;
  const std::string sto_text = "stochastic:seed=3,pga_g=0.4,duration_s=20,dt_s=0.01";
  const GroundMotion sto_g = pcrf::make_synthetic(sto_text);
  EXPECT_EQ(sto_g.name(), sto_text);
  EXPECT_EQ(sto_g.samples_m_s2(), pcrf::make_stochastic(sto).samples_m_s2());
}

TEST(MakeSynthetic, SubsetsDefaultsAndBlanks) {
  EXPECT_EQ(pcrf::make_synthetic("sine").samples_m_s2(),
            pcrf::make_sine_pulse_train(SinePulseSpec{}).samples_m_s2());
  EXPECT_EQ(pcrf::make_synthetic("sine:").samples_m_s2(),
            pcrf::make_sine_pulse_train(SinePulseSpec{}).samples_m_s2());
  StochasticSpec s;
  s.seed = 9;
  s.ground_damping = 0.4;
  EXPECT_EQ(pcrf::make_synthetic("stochastic: ground_damping = 0.4 , seed=9").samples_m_s2(),
            pcrf::make_stochastic(s).samples_m_s2());
  StochasticSpec all;
  all.seed = 2;
  all.pga_g = 0.3;
  all.duration_s = 12;
  all.dt_s = 0.005;
  all.ground_freq_hz = 4;
  all.ground_damping = 0.5;
  all.rise_s = 1;
  all.strong_s = 4;
  all.decay_per_s = 0.5;
  EXPECT_EQ(pcrf::make_synthetic("stochastic:seed=2,pga_g=0.3,duration_s=12,dt_s=0.005,"
                                 "ground_freq_hz=4,ground_damping=0.5,rise_s=1,strong_s=4,"
                                 "decay_per_s=0.5")
                .samples_m_s2(),
            pcrf::make_stochastic(all).samples_m_s2());
}

TEST(MakeSynthetic, ErrorsNameTheProblem) {
  struct Case {
    const char* text;
    const char* must_mention;
  };
  const std::vector<Case> cases = {
      {"square:amplitude_g=1", "unknown kind 'square'"},
      {"", "unknown kind ''"},
      {"sine:amplitude=0.5", "unknown key 'amplitude'"},
      {"stochastic:period_s=1", "unknown key 'period_s'"},
      {"sine:period_s=abc", "bad value 'abc' for key 'period_s'"},
      {"sine:period_s=", "bad value '' for key 'period_s'"},
      {"sine:period_s=0.5s", "bad value '0.5s'"},
      {"sine:amplitude_g=inf", "bad value 'inf'"},
      {"sine:cycles=2.5", "bad value '2.5' for key 'cycles'"},
      {"stochastic:seed=-1", "bad value '-1' for key 'seed'"},
      {"stochastic:seed=1.5", "bad value '1.5' for key 'seed'"},
      {"sine:cycles=2,cycles=3", "'cycles' given twice"},
      {"sine:cycles=2,,dt_s=0.01", "empty item"},
      {"sine:cycles=2,", "empty item"},
      {"sine:cycles", "expected key=value"},
      {"sine:period_s=-0.5", "period_s of sine"},
      {"stochastic:pga_g=0", "pga_g of stochastic"},
  };
  for (const Case& c : cases) {
    const std::string m = invalid_argument_message([&] { (void)pcrf::make_synthetic(c.text); });
    EXPECT_NE(m.find(c.must_mention), std::string::npos) << c.text << " → " << m;
    EXPECT_NE(m.find(std::string("'") + c.text + "'"), std::string::npos) << "text not quoted: " << m;
  }
}

}  // namespace
