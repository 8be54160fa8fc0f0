/// \file test_pulse_identification.cpp
/// \brief Pulse identification (Baker 2007; Shahi & Baker 2014): the db4 wavelet against its
/// defining properties, synthetic pulses and noise, and the near-fault records of
/// ../shared/records against their MANIFEST labels and published pulse periods (skipped
/// without the records).

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numeric>
#include <string>
#include <vector>

#include "pcrf/record/pulse_identification.hpp"
#include "pcrf/record/pulses.hpp"
#include "pcrf/record/record_readers.hpp"
#include "pcrf/record/synthetic.hpp"
#include "support/test_support.hpp"

namespace {

using pcrf::Db4Wavelet;
using pcrf::GroundMotion;

TEST(Db4Wavelet, FilterIsOrthonormalWithFourVanishingMoments) {
  const auto& h = Db4Wavelet::lowpass();
  ASSERT_EQ(h.size(), 8u);
  EXPECT_NEAR(std::accumulate(h.begin(), h.end(), 0.0), std::sqrt(2.0), 1e-12);
  for (int shift = 0; shift < 4; ++shift) {  // Σ h_k h_{k+2m} = δ_m
    double dot = 0.0;
    for (std::size_t k = 0; k + 2 * shift < h.size(); ++k) dot += h[k] * h[k + 2 * shift];
    EXPECT_NEAR(dot, shift == 0 ? 1.0 : 0.0, 1e-12) << "shift " << shift;
  }
  for (int p = 0; p < 4; ++p) {  // Σ (−1)^k k^p h_k = 0: the wavelet has 4 vanishing moments
    double moment = 0.0;
    for (std::size_t k = 0; k < h.size(); ++k) moment += (k % 2 ? -1.0 : 1.0) * std::pow(double(k), p) * h[k];
    EXPECT_NEAR(moment, 0.0, 1e-9) << "moment " << p;
  }
}

TEST(Db4Wavelet, PsiHasUnitEnergyZeroMeanAndMatlabsCentreFrequency) {
  double energy = 0.0, mean = 0.0;
  const double dx = 1.0 / 4096;
  for (double x = 0.0; x < 7.0; x += dx) {
    const double psi = Db4Wavelet::psi(x);
    energy += psi * psi * dx;
    mean += psi * dx;
  }
  EXPECT_NEAR(energy, 1.0, 2e-3);
  EXPECT_NEAR(mean, 0.0, 1e-3);
  EXPECT_EQ(Db4Wavelet::psi(-0.1), 0.0);
  EXPECT_EQ(Db4Wavelet::psi(7.1), 0.0);
  // MATLAB's centfrq('db4') = 0.7143 Hz (= 5/7), the factor behind Shahi & Baker's "T_p / 1.4".
  EXPECT_NEAR(Db4Wavelet::centre_frequency(), 0.7143, 1e-4);
}

GroundMotion padded_pulse(double period_s, double start_s, double length_s, double dt_s) {
  pcrf::PulseSpec spec;
  spec.shape = pcrf::PulseShape::kRicker;
  spec.period_s = period_s;
  spec.amplitude_g = 0.4;
  spec.dt_s = dt_s;
  const GroundMotion pulse = pcrf::make_pulse(spec);
  std::vector<double> a(static_cast<std::size_t>(length_s / dt_s), 0.0);
  const auto start = static_cast<std::size_t>(start_s / dt_s);
  for (std::size_t i = 0; i < pulse.size() && start + i < a.size(); ++i) a[start + i] = pulse.samples_m_s2()[i];
  return GroundMotion("ricker", dt_s, a);
}

TEST(PulseIdentification, ALonePulseIsPulseLikeAndItsPeriodScalesWithThePulse) {
  const auto short_pulse = pcrf::classify_pulse(padded_pulse(1.0, 2.0, 30.0, 0.01));
  const auto long_pulse = pcrf::classify_pulse(padded_pulse(3.0, 2.0, 30.0, 0.01));
  ASSERT_TRUE(short_pulse.pulse_like);
  ASSERT_TRUE(long_pulse.pulse_like);
  EXPECT_NEAR(long_pulse.period_s / short_pulse.period_s, 3.0, 0.3);
  // The pulse is nearly all of the motion: little is left in the residual.
  EXPECT_LT(short_pulse.candidates[0].energy_ratio, 0.2);
  EXPECT_LT(short_pulse.candidates[0].pgv_ratio, 0.5);
  EXPECT_EQ(short_pulse.method, pcrf::PulseMethod::kBaker2007);
}

TEST(PulseIdentification, BroadbandNoiseIsNotPulseLike) {
  pcrf::StochasticSpec spec;
  spec.seed = 7;
  spec.pga_g = 0.5;
  const auto result = pcrf::classify_pulse(pcrf::make_stochastic(spec));
  EXPECT_FALSE(result.pulse_like);
  EXPECT_GT(result.candidates[0].energy_ratio, 0.5);
}

TEST(PulseIdentification, APairFindsThePulsesOrientationAndItsPeriod) {
  // A pulse polarised along azimuth 30°, recorded on north (0°) and east (90°) components.
  const GroundMotion along = padded_pulse(2.0, 3.0, 30.0, 0.01);
  std::vector<double> north = along.samples_m_s2(), east = along.samples_m_s2();
  for (double& x : north) x *= std::cos(M_PI / 6);
  for (double& x : east) x *= std::sin(M_PI / 6);
  const GroundMotion n("n", 0.01, north), e("e", 0.01, east);
  const auto pair = pcrf::classify_pulse(pcrf::HorizontalPair{n, 0.0, e, 90.0});
  const auto alone = pcrf::classify_pulse(along);
  ASSERT_TRUE(pair.pulse_like);
  EXPECT_EQ(pair.method, pcrf::PulseMethod::kShahiBaker2014);
  EXPECT_NEAR(pair.candidates[pair.decided_by].azimuth_deg, 30.0, 0.5);
  EXPECT_NEAR(pair.period_s, alone.period_s, 1e-6 * alone.period_s);
}

// ---- the near-fault records of ../shared/records -------------------------------------------

struct NearFault {
  std::string rsn;
  std::string h1, h2;      ///< files under the records folder; h2 empty: one component
  double az1_deg, az2_deg; ///< used for the Chi-Chi "-E"/"-N" files (their headers state no azimuth)
  bool labelled_pulse;     ///< MANIFEST.csv (FEMA P695 near-field set / extra pulse records)
};

std::vector<NearFault> near_fault_records() {
  const std::string v = "nearfault_vacalderon/";
  const double nan = std::nan("");
  return {
      {"165", "nearfault_hsiifu3/RSN165_IMPVALL.H_H-CHI012.AT2", "nearfault_hsiifu3/RSN165_IMPVALL.H_H-CHI282.AT2", nan, nan, false},
      {"181", "nearfault_hsiifu3/RSN181_IMPVALL.H_H-E06140.AT2", "nearfault_hsiifu3/RSN181_IMPVALL.H_H-E06230.AT2", nan, nan, true},
      {"292", v + "RSN292_ITALY_A-STU000.AT2", v + "RSN292_ITALY_A-STU270.AT2", nan, nan, true},
      {"723", v + "RSN723_SUPER.B_B-PTS225.AT2", v + "RSN723_SUPER.B_B-PTS315.AT2", nan, nan, true},
      {"1004", v + "RSN1004_NORTHR_SPV270.AT2", v + "RSN1004_NORTHR_SPV360.AT2", nan, nan, false},
      {"1044", v + "RSN1044_NORTHR_NWH090.AT2", v + "RSN1044_NORTHR_NWH360.AT2", nan, nan, true},
      {"1048", v + "RSN1048_NORTHR_STC090.AT2", v + "RSN1048_NORTHR_STC180.AT2", nan, nan, false},
      {"1063", v + "RSN1063_NORTHR_RRS228.AT2", v + "RSN1063_NORTHR_RRS318.AT2", nan, nan, true},
      {"1086", v + "RSN1086_NORTHR_SYL090.AT2", v + "RSN1086_NORTHR_SYL360.AT2", nan, nan, true},
      {"1176", v + "RSN1176_KOCAELI_YPT060.AT2", v + "RSN1176_KOCAELI_YPT150.AT2", nan, nan, false},
      {"1503", v + "RSN1503_CHICHI_TCU065-E.AT2", v + "RSN1503_CHICHI_TCU065-N.AT2", 90.0, 0.0, true},
      {"1504", v + "RSN1504_CHICHI_TCU067-E.AT2", v + "RSN1504_CHICHI_TCU067-N.AT2", 90.0, 0.0, false},
      {"1505", v + "RSN1505_CHICHI_TCU068-E.AT2", v + "RSN1505_CHICHI_TCU068-N.AT2", 90.0, 0.0, true},
      {"1529", v + "RSN1529_CHICHI_TCU102-E.AT2", v + "RSN1529_CHICHI_TCU102-N.AT2", 90.0, 0.0, true},
      {"1605", v + "RSN1605_DUZCE_DZC180.AT2", v + "RSN1605_DUZCE_DZC270.AT2", nan, nan, true},
      {"879", "nearfault_sehyeon9121/RSN879_LANDERS_LCN260.AT2", "nearfault_sehyeon9121/RSN879_LANDERS_LCN345.AT2", nan, nan, true},
      {"753", "nearfault_bishwajeet56/RSN753_LOMAP_CLS000.AT2", "nearfault_bishwajeet56/RSN753_LOMAP_CLS090.AT2", nan, nan, false},
      {"828", "nearfault_mtareqsoliman/RSN828_CAPEMEND_PET000.AT2", "", nan, nan, true},
      {"1106", "nearfault_tum/RSN1106_KOBE_KJM000.AT2", "nearfault_tum/RSN1106_KOBE_KJM090.AT2", nan, nan, true},
  };
}

/// The azimuth a component's file name states ("…_LCN345.AT2" → 345).
double azimuth_of(const std::string& file) {
  const std::string stem = std::filesystem::path(file).stem().string();
  const auto az = pcrf::azimuth_of_component(stem.substr(stem.rfind('_') + 1));
  return az ? *az : std::nan("");
}

pcrf::PulseClassification classify(const std::filesystem::path& dir, const NearFault& r) {
  const GroundMotion h1 = pcrf::read_at2(dir / r.h1);
  if (r.h2.empty()) return pcrf::classify_pulse(h1);
  const GroundMotion h2 = pcrf::read_at2(dir / r.h2);
  const double az1 = std::isnan(r.az1_deg) ? azimuth_of(r.h1) : r.az1_deg;
  const double az2 = std::isnan(r.az2_deg) ? azimuth_of(r.h2) : r.az2_deg;
  return pcrf::classify_pulse(pcrf::HorizontalPair{h1, az1, h2, az2});
}

/// Erzincan 1992 (RSN821): the benchmark text file, N-S and E-W side by side in cm/s²; the
/// E-W column repeats the N-S one from row 4156 on, so both are cut to the first 4155 rows.
pcrf::PulseClassification classify_erzincan(const std::filesystem::path& dir) {
  const auto file = dir / "nearfault_lihongweiseu/erzikan.txt";
  auto cut = [&](std::size_t column) {
    const GroundMotion all = pcrf::read_one_column(file, 0.005, pcrf::AccelUnit::kCentimeterPerSecond2, 2, column);
    return GroundMotion(all.name(), all.dt_s(), std::vector<double>(all.samples_m_s2().begin(), all.samples_m_s2().begin() + 4155));
  };
  const GroundMotion ns = cut(1), ew = cut(2);
  return pcrf::classify_pulse(pcrf::HorizontalPair{ns, 0.0, ew, 90.0});
}

// Where the result differs from the MANIFEST label, and why (docs/commands/record.md):
// the labels classify the fault-normal component (FEMA P695, Baker 2007's criterion); these
// files are as recorded and Shahi & Baker (2014) classify every orientation.
//   1004 Sepulveda: a 0.95 s pulse polarised near E-W (azimuth 92°); SPV270 alone is pulse-like by Baker 2007 too.
//   1176 Yarimca: a 5 s pulse; both as-recorded components are pulse-like by Baker 2007 too.
//   1044 Newhall: the strongest pulse (T_p 1.0 s, indicator +10) arrives late: the record has 32 %
//        of its cumulative squared velocity when the pulse has 5 % (limit 17 %).
const std::map<std::string, bool> kExplainedDifferences{{"1004", true}, {"1176", true}, {"1044", false}};

TEST(PulseIdentificationRecords, LabelsAgreeOrTheDifferenceIsExplained) {
  PCRF_REQUIRE_RECORDS(dir);
  int agree = 0;
  for (const auto& r : near_fault_records()) {
    const auto result = classify(dir, r);
    const auto explained = kExplainedDifferences.find(r.rsn);
    const bool expected = explained != kExplainedDifferences.end() ? explained->second : r.labelled_pulse;
    EXPECT_EQ(result.pulse_like, expected) << "RSN" << r.rsn;
    agree += result.pulse_like == r.labelled_pulse;
  }
  EXPECT_TRUE(classify_erzincan(dir).pulse_like) << "RSN821";
  EXPECT_EQ(agree, 16);  // of 19 (plus Erzincan): the three above differ
}

TEST(PulseIdentificationRecords, PulsePeriodsAgreeWithPublishedValues) {
  PCRF_REQUIRE_RECORDS(dir);
  // T_p [s] of the fault-normal components in Baker (2007), Table 4 (as reproduced in FEMA
  // P695 Table A-4C). Sylmar (3.1 s) and Petrolia (3.0 s, only PET000 here) are left out:
  // see docs/commands/record.md.
  const std::map<std::string, double> published{{"181", 3.8}, {"292", 3.1}, {"723", 2.3}, {"1063", 1.2},
                                                {"1503", 5.7}, {"1505", 12.2}, {"1529", 9.7}, {"1605", 5.9},
                                                {"879", 5.1}, {"1106", 1.0}};
  for (const auto& r : near_fault_records()) {
    const auto it = published.find(r.rsn);
    if (it == published.end()) continue;
    const auto result = classify(dir, r);
    EXPECT_NEAR(result.period_s, it->second, 0.10 * it->second) << "RSN" << r.rsn;
  }
  EXPECT_NEAR(classify_erzincan(dir).period_s, 2.7, 0.27) << "RSN821";
}

}  // namespace
