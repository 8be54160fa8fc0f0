/// \file test_intensity.cpp
/// \brief Intensity measures against closed forms: a constant acceleration has known
/// velocity, displacement, Arias intensity and significant duration, and the oscillator's
/// response to a step has a closed form that the Nigam–Jennings recurrence must reproduce at
/// every sample. Real records: metadata from the AT2 header, and skip_rows on the FEMA files.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "pcrf/record/intensity.hpp"
#include "pcrf/record/record_readers.hpp"
#include "support/test_support.hpp"

namespace pcrf {
namespace {

constexpr double kA_m_s2 = 2.0;  // a constant ground acceleration

GroundMotion constant_record(double duration_s, double dt_s) {
  return GroundMotion("step", dt_s, std::vector<double>(static_cast<std::size_t>(std::lround(duration_s / dt_s)) + 1, kA_m_s2));
}

TEST(Intensity, ConstantAccelerationIntegratesExactly) {
  const auto rec = constant_record(4.0, 0.01);
  EXPECT_NEAR(peak_velocity_m_s(rec), kA_m_s2 * 4.0, 1e-12);
  EXPECT_NEAR(peak_displacement_m(rec), 0.5 * kA_m_s2 * 16.0, 1e-10);
  EXPECT_NEAR(arias_intensity_m_s(rec), std::numbers::pi / (2.0 * kGravity_m_s2) * kA_m_s2 * kA_m_s2 * 4.0, 1e-12);
  EXPECT_NEAR(significant_duration_s(rec), 0.9 * 4.0, 1e-12);
  const auto peak = peak_acceleration(rec);
  EXPECT_DOUBLE_EQ(peak.pga_g, kA_m_s2 / kGravity_m_s2);
  EXPECT_EQ(peak.t_pga_s, 0.0);
}

TEST(Intensity, PeakAccelerationAndItsFirstTime) {
  const GroundMotion rec("r", 0.02, {0.0, 1.0, -3.0, 2.0, 3.0});
  const auto peak = peak_acceleration(rec);
  EXPECT_DOUBLE_EQ(peak.pga_g, 3.0 / kGravity_m_s2);
  EXPECT_DOUBLE_EQ(peak.t_pga_s, 0.04);
}

/// Displacement of the oscillator ü + 2ζωu̇ + ω²u = −A from rest, closed form.
double step_response(double t, double omega, double zeta) {
  const double wd = omega * std::sqrt(1.0 - zeta * zeta);
  return -kA_m_s2 / (omega * omega) *
         (1.0 - std::exp(-zeta * omega * t) * (std::cos(wd * t) + zeta / std::sqrt(1.0 - zeta * zeta) * std::sin(wd * t)));
}

TEST(Intensity, SpectralAccelerationIsExactForAStep) {
  // A constant record long enough for the response to settle: the peak is the first
  // overshoot, at a sample or not; the recurrence must give the closed form at the samples.
  for (const double period_s : {0.1, 0.37, 1.0, 2.5}) {
    for (const double zeta : {0.0, 0.02, 0.05, 0.2}) {
      const double dt = 0.005, duration = 6.0 * period_s + 10.0;
      const double omega = 2.0 * std::numbers::pi / period_s;
      double peak = 0.0;
      for (double i = 0; i * dt <= duration + 1e-12; ++i) peak = std::max(peak, std::fabs(step_response(i * dt, omega, zeta)));
      const double expected_g = omega * omega * peak / kGravity_m_s2;
      const double sa = spectral_acceleration_g(constant_record(duration, dt), period_s, zeta);
      // Undamped, the free vibration after the record reaches its bound 2A/ω² between samples.
      const double tolerance = zeta > 0.0 ? 1e-10 : 2e-3;
      EXPECT_NEAR(sa, expected_g, tolerance * expected_g) << "T = " << period_s << " s, zeta = " << zeta;
      // and the true peak (1 + e^{−ζπ/√(1−ζ²)}) A/ω² is within the sampling error
      const double true_peak_g = (1.0 + std::exp(-zeta * std::numbers::pi / std::sqrt(1.0 - zeta * zeta))) * kA_m_s2 / kGravity_m_s2;
      EXPECT_NEAR(sa, true_peak_g, 2e-3 * true_peak_g) << "T = " << period_s << " s, zeta = " << zeta;
    }
  }
}

TEST(Intensity, ShortPeriodSpectralAccelerationIsThePga) {
  std::vector<double> a;
  for (int i = 0; i < 2000; ++i) a.push_back(3.0 * std::sin(0.01 * i * 2.0 * std::numbers::pi * 1.3) * std::exp(-0.001 * i));
  const GroundMotion rec("sine", 0.01, a);
  EXPECT_NEAR(spectral_acceleration_g(rec, 0.02, 0.05), peak_acceleration(rec).pga_g, 0.01 * peak_acceleration(rec).pga_g);
  EXPECT_THROW(spectral_acceleration_g(rec, 0.0), std::invalid_argument);
  EXPECT_THROW(spectral_acceleration_g(rec, 1.0, 1.0), std::invalid_argument);
}

TEST(Intensity, MeasuresByName) {
  EXPECT_EQ(parse_intensity_measure("sa_g"), IntensityMeasure::kSa);
  EXPECT_EQ(to_string(IntensityMeasure::kPgv), "pgv_m_s");
  EXPECT_THROW(parse_intensity_measure("pga"), std::invalid_argument);
  const auto rec = constant_record(1.0, 0.01);
  EXPECT_DOUBLE_EQ(intensity_of(rec, {IntensityMeasure::kPga, 0.0, 0.05}), kA_m_s2 / kGravity_m_s2);
}

TEST(RecordMetadata, FromTheAt2HeaderAndTheFileName) {
  const auto dir = test::scratch_dir("metadata");
  const auto file = test::write_file(dir, "RSN174_IMPVALL.H_H-E11230.AT2",
                                     "PEER NGA STRONG MOTION DATABASE RECORD\r\n"
                                     "Imperial Valley-06, 10/15/1979, El Centro Array #11, 230\r\n"
                                     "ACCELERATION TIME SERIES IN UNITS OF G\r\nNPTS=   2, DT=   .0050 SEC,\r\n 0.1 0.2\r\n");
  RecordFileSpec spec;
  spec.path = file;
  const auto meta = read_metadata(spec);
  EXPECT_EQ(meta.title, "Imperial Valley-06, 10/15/1979, El Centro Array #11, 230");
  EXPECT_EQ(meta.event, "Imperial Valley-06");
  EXPECT_EQ(meta.station, "El Centro Array #11");
  EXPECT_EQ(meta.component, "230");
  EXPECT_EQ(meta.rsn, "174");
}

TEST(RecordMetadata, ReadOnceWithTheMotionAsEachAlone) {
  const auto dir = test::scratch_dir("record_file");
  const auto at2 = test::write_file(dir, "RSN174_A.AT2",
                                    "PEER NGA STRONG MOTION DATABASE RECORD\n"
                                    "Imperial Valley-06, 10/15/1979, El Centro Array #11, 230\n"
                                    "ACCELERATION TIME SERIES IN UNITS OF G\nNPTS=   3, DT=   .0050 SEC,\n 0.1 0.2 -0.3\n");
  const auto text = test::write_file(dir, "RSN9_B.txt", "0 0.1\n0.01 0.2\n");
  for (const RecordFileSpec& spec : {RecordFileSpec{at2}, RecordFileSpec{text, RecordFormat::kTwoColumn}}) {
    SCOPED_TRACE(spec.path.string());
    const RecordFile file = read_record_file(spec);
    const GroundMotion alone = read_record(spec);
    EXPECT_EQ(file.motion.name(), alone.name());
    EXPECT_EQ(file.motion.dt_s(), alone.dt_s());
    EXPECT_EQ(file.motion.samples_m_s2(), alone.samples_m_s2());
    const RecordMetadata meta = read_metadata(spec);
    EXPECT_EQ(file.metadata.title, meta.title);
    EXPECT_EQ(file.metadata.event, meta.event);
    EXPECT_EQ(file.metadata.component, meta.component);
    EXPECT_EQ(file.metadata.rsn, meta.rsn);
  }
  EXPECT_EQ(read_record_file(RecordFileSpec{at2}).metadata.station, "El Centro Array #11");
  // A bad record fails as read_record does.
  const auto bad = test::write_file(dir, "bad.AT2", "a\nb\nc\nNPTS=   3, DT=   .0050 SEC,\n 0.1 0.2\n");
  EXPECT_THROW(read_record_file(RecordFileSpec{bad}), UserError);
}

TEST(RecordHandling, SkipRowsDropsTheFemaFilesAddedLeadingSample) {
  PCRF_REQUIRE_RECORDS(records);
  // paper/ER4 is SortedEQFile_(120622).txt with its added leading zero removed, values unchanged.
  const auto at2 = read_at2(records / "paper" / "ER4_H-E11230.AT2");
  const auto fema = records / "fema_p695_ff_sorted_hadi" / "SortedEQFile_(120622).txt";
  const auto skipped = read_two_column(fema, AccelUnit::kG, 1);
  const auto shifted = read_two_column(fema, AccelUnit::kG);
  ASSERT_EQ(skipped.size(), at2.size());
  EXPECT_EQ(skipped.samples_m_s2(), at2.samples_m_s2());
  EXPECT_EQ(shifted.size(), at2.size() + 1);
  EXPECT_NEAR(peak_acceleration(skipped).t_pga_s, peak_acceleration(at2).t_pga_s, 1e-9);
  EXPECT_NEAR(peak_acceleration(shifted).t_pga_s - peak_acceleration(at2).t_pga_s, at2.dt_s(), 1e-9);
}

TEST(Intensity, PeriodsAndRecordsThatCannotBeMeasuredAreNamed) {
  EXPECT_EQ(sa_period_problem(1.0, 0.01), "");
  EXPECT_EQ(sa_period_problem(0.02, 0.01), "");
  EXPECT_EQ(sa_period_problem(0.019, 0.01),
            "an oscillator period of 0.019 s is below 2·dt = 0.02 s of the record: its Sa is not resolved");
  for (double bad : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity(), 100.5, 1e300})
    EXPECT_NE(sa_period_problem(bad, 0.0).find("must be above 0 s and at most 100 s"), std::string::npos) << bad;
  EXPECT_EQ(intensity_spec_problem({IntensityMeasure::kPgv, 1.0, 0.05}), "pgv_m_s has no oscillator: period_s belongs to sa_g");
  EXPECT_EQ(intensity_spec_problem({IntensityMeasure::kPga, 0.0, 0.05}), "");
  EXPECT_NE(intensity_spec_problem({IntensityMeasure::kSa, std::numeric_limits<double>::infinity(), 0.05}), "");
  EXPECT_EQ(measures_problem(GroundMotion("ok", 0.01, std::vector<double>(100, 1.0))), "");
  std::vector<double> huge(100, 1e300);
  EXPECT_NE(measures_problem(GroundMotion("huge", 0.01, huge)).find("overflow the intensity measures"), std::string::npos);
}

}  // namespace
}  // namespace pcrf
