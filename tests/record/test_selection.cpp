/// \file test_selection.cpp
/// \brief Record spectra tables and record selection (record_library.hpp, selection.hpp): the
/// table's round trip and refusals, the target's refusals (file, line, key), the correlation
/// model, selection from a synthetic library whose spectra can match the target, and the
/// spectra of the real records (skipped without ../shared/records).

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "pcrf/record/horizontal_pair.hpp"
#include "pcrf/record/intensity.hpp"
#include "pcrf/record/record_library.hpp"
#include "pcrf/record/record_readers.hpp"
#include "pcrf/record/rotd.hpp"
#include "pcrf/record/selection.hpp"
#include "pcrf/user_error.hpp"
#include "support/test_support.hpp"

namespace {

using pcrf::SpectraTable;

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const pcrf::UserError& e) {
    return e.what();
  }
  return "";
}

pcrf::SelectionTarget target_from(const std::string& text) {
  std::istringstream in(text);
  return pcrf::read_selection_target(in, "t.csv");
}

TEST(SelectionTarget, ReadsPeriodsMeansSigmasAndCorrelation) {
  const auto t = target_from("# from EzGM\nperiod_s,mean_ln_sa,sigma_ln_sa,rho_0.1s,rho_1s\n0.1,-0.5,0.6,1,0.3\n1,-1.2,0,0.3,1\n");
  ASSERT_EQ(t.periods_s.size(), 2u);
  EXPECT_EQ(t.mean_ln_sa[1], -1.2);
  EXPECT_EQ(t.sigma_ln_sa[1], 0.0);
  EXPECT_EQ(t.correlation[0][1], 0.3);
  EXPECT_EQ(t.row_lines[1], 4);
}

TEST(SelectionTarget, BadTargetsAreRefusedNamingFileLineAndKey) {
  const std::string head = "period_s,mean_ln_sa,sigma_ln_sa\n";
  auto refused = [&](const std::string& rows) { return error_of([&] { target_from(head + rows); }); };
  EXPECT_NE(refused("0.5,0,0.5\n0.2,0,0.5\n").find("t.csv:3: period_s: periods must increase"), std::string::npos);
  EXPECT_NE(refused("0.5,0,-0.1\n").find("t.csv:2: sigma_ln_sa: must not be negative"), std::string::npos);
  EXPECT_NE(refused("0.5,nan,0.1\n").find("t.csv:2: mean_ln_sa: 'nan' is not a finite number"), std::string::npos);
  EXPECT_NE(refused("0.5,0\n").find("t.csv:2: row"), std::string::npos);
  EXPECT_NE(error_of([] { target_from("period_s,mean\n1,2\n"); }).find("t.csv:1: mean_ln_sa"), std::string::npos);
  EXPECT_NE(error_of([] { target_from("period_s,mean_ln_sa,sigma_ln_sa,rho_1s,rho_2s\n1,0,0.5,1,0.5\n2,0,0.5,0.4,1\n"); })
                .find("symmetric"),
            std::string::npos);
}

TEST(SelectionTarget, BakerJayaramCorrelationIsOneOnTheDiagonalSymmetricAndDecays) {
  for (double t : {0.05, 0.1, 0.15, 0.5, 2.0}) EXPECT_NEAR(pcrf::baker_jayaram_correlation(t, t), 1.0, 1e-12) << t;
  EXPECT_EQ(pcrf::baker_jayaram_correlation(0.3, 2.0), pcrf::baker_jayaram_correlation(2.0, 0.3));
  // T_min > 0.109 s: ρ = 1 − cos(π/2 − 0.366 ln(T_max/T_min)) (Baker & Jayaram 2008, Eq. 7).
  EXPECT_NEAR(pcrf::baker_jayaram_correlation(1.0, 2.0), 1.0 - std::sin(0.366 * std::log(2.0)), 1e-12);
  EXPECT_GT(pcrf::baker_jayaram_correlation(1.0, 1.5), pcrf::baker_jayaram_correlation(1.0, 3.0));
}

SpectraTable synthetic_library(std::size_t count, std::uint64_t seed) {
  // ln Sa = shape(T) + a + b·ln(T/1 s) + small noise: spectra of varied level and slope, so that
  // a set can match any target mean and σ of moderate size.
  SpectraTable table{{0.1, 0.2, 0.5, 1.0, 2.0, 4.0}, {}};
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (std::size_t i = 0; i < count; ++i) {
    pcrf::LibraryEntry e{"r" + std::to_string(i), "component", "r" + std::to_string(i) + ".AT2", "", 0.01, 1000, 0.05, 0.3, {}};
    const double a = 0.6 * normal(rng), b = 0.3 * normal(rng);
    for (double t : table.periods_s)
      e.sa_g.push_back(std::exp(std::log(0.5) - 0.6 * std::log(t) * (t > 0.3) + a + b * std::log(t) + 0.1 * normal(rng)));
    table.entries.push_back(std::move(e));
  }
  return table;
}

TEST(Selection, ASetFromARichLibraryMatchesTheTargetMeanWithin5AndSigmaWithin10Percent) {
  const SpectraTable library = synthetic_library(400, 3);
  const auto target = target_from("period_s,mean_ln_sa,sigma_ln_sa\n0.1,-0.72,0.55\n0.2,-0.65,0.5\n0.5,-0.15,0.45\n1,-0.49,0.5\n2,-0.84,0.55\n");
  pcrf::SelectionSettings settings;
  settings.count = 20;
  settings.kind = "component";
  const auto r = pcrf::select_records(target, library, settings);
  ASSERT_EQ(r.records.size(), 20u);
  EXPECT_LT(r.median_error_percent, 5.0);
  EXPECT_LT(r.sigma_error_percent, 10.0);
  for (const auto& rec : r.records) {
    EXPECT_GE(rec.scale, settings.scale_min);
    EXPECT_LE(rec.scale, settings.scale_max);
  }
  // Each entry once.
  for (std::size_t i = 0; i < r.records.size(); ++i)
    for (std::size_t j = i + 1; j < r.records.size(); ++j) EXPECT_NE(r.records[i].entry, r.records[j].entry);
  // The reported fit is the set's: recomputed from its spectra.
  double mean0 = 0.0;
  for (const auto& s : r.ln_sa) mean0 += s[0] / static_cast<double>(r.ln_sa.size());
  EXPECT_NEAR(mean0, r.mean_ln_sa[0], 1e-12);
}

/// Baker & Lee's figure of merit of `set` against `target`: Σ (m̂ − μ)² + 2 Σ (ŝ − σ)² (ŝ with 1/N).
double figure_of_merit(const std::vector<std::vector<double>>& set, const pcrf::SelectionTarget& target) {
  double total = 0.0;
  const double n = static_cast<double>(set.size());
  for (std::size_t j = 0; j < target.periods_s.size(); ++j) {
    double m = 0.0, m2 = 0.0;
    for (const auto& s : set) m += s[j] / n;
    for (const auto& s : set) m2 += (s[j] - m) * (s[j] - m) / n;
    total += std::pow(m - target.mean_ln_sa[j], 2) + 2.0 * std::pow(std::sqrt(m2) - target.sigma_ln_sa[j], 2);
  }
  return total;
}

// Issue 42 item 5: the greedy runs until a pass replaces no entry, from every simulated set, with
// each scale optimised continuously. From the same first simulated set, more passes and more
// starts can only improve the fit of Baker & Lee's two passes from one set (the entry in place is
// always a candidate); and the set it ends with is one that no single replacement of an entry,
// by any entry at any scale within the limits (a grid of 401 in ln s), improves by more than a
// relative 1e-3.
TEST(Selection, TheGreedyEndsWhereNoReplacementImprovesAndBeatsTwoPassesFromOneSet) {
  const SpectraTable library = synthetic_library(120, 11);
  const auto target = target_from("period_s,mean_ln_sa,sigma_ln_sa\n0.1,-0.72,0.55\n0.2,-0.65,0.5\n0.5,-0.15,0.45\n1,-0.49,0.5\n2,-0.84,0.55\n");
  pcrf::SelectionSettings baker_lee;
  baker_lee.count = 8;
  baker_lee.kind = "component";
  baker_lee.starts = 1;
  baker_lee.loops = 2;
  const auto as_published = pcrf::select_records(target, library, baker_lee);
  pcrf::SelectionSettings one_start = baker_lee;
  one_start.loops = 100;
  const auto converged = pcrf::select_records(target, library, one_start);
  pcrf::SelectionSettings every_start = one_start;
  every_start.starts = every_start.trials;
  const auto best = pcrf::select_records(target, library, every_start);
  EXPECT_LE(converged.sum_of_squares, as_published.sum_of_squares);
  EXPECT_LE(best.sum_of_squares, converged.sum_of_squares);
  EXPECT_NEAR(best.sum_of_squares, figure_of_merit(best.ln_sa, target), 1e-12);

  // ln Sa of every library entry at the target's periods (they are the library's grid here).
  std::vector<std::vector<double>> ln_lib;
  for (const auto& e : library.entries) {
    std::vector<double> row;
    for (double t : target.periods_s)
      for (std::size_t g = 0; g < library.periods_s.size(); ++g)
        if (library.periods_s[g] == t) row.push_back(std::log(e.sa_g[g]));
    ln_lib.push_back(row);
  }
  double most_gained = 0.0;
  for (std::size_t i = 0; i < best.records.size(); ++i)
    for (std::size_t k = 0; k < library.entries.size(); ++k) {
      bool other = false;
      for (std::size_t m = 0; m < best.records.size(); ++m) other = other || (m != i && best.records[m].entry == k);
      if (other) continue;
      for (int step = 0; step <= 400; ++step) {
        const double ln_s = std::log(0.25) + std::log(16.0) * step / 400.0;
        auto set = best.ln_sa;
        for (std::size_t j = 0; j < set[i].size(); ++j) set[i][j] = ln_lib[k][j] + ln_s;
        most_gained = std::max(most_gained, best.sum_of_squares - figure_of_merit(set, target));
      }
    }
  EXPECT_LT(most_gained, 1e-3 * best.sum_of_squares) << "a single replacement still improves the fit";
}

TEST(Selection, AConditioningPeriodFixesEveryScaleToTheTargetThere) {
  const SpectraTable library = synthetic_library(300, 5);
  const auto target = target_from("period_s,mean_ln_sa,sigma_ln_sa\n0.2,-0.3,0.4\n1,-1.2,0\n2,-1.9,0.3\n");
  pcrf::SelectionSettings settings;
  settings.count = 10;
  settings.kind = "component";
  const auto r = pcrf::select_records(target, library, settings);
  for (const auto& s : r.ln_sa) EXPECT_NEAR(s[1], -1.2, 1e-9);
}

TEST(Selection, APeriodOutsideTheLibraryIsRefusedAtItsLine) {
  const SpectraTable library = synthetic_library(50, 1);
  const auto target = target_from("period_s,mean_ln_sa,sigma_ln_sa\n0.5,-0.3,0.4\n6,-1.2,0.5\n");
  const std::string e = error_of([&] { pcrf::SelectionSettings s;
    s.kind = "component";
    pcrf::select_records(target, library, s);
  });
  EXPECT_NE(e.find("t.csv:3: period_s: 6 s is outside the library's periods (0.1 s to 4 s)"), std::string::npos) << e;
}

TEST(SpectraTable, RoundTripsAndRefusesMalformedTables) {
  SpectraTable table = synthetic_library(3, 2);
  table.entries[1].kind = "rotd50";
  table.entries[1].file_h2 = "b,2.AT2";  // quoted in the CSV
  std::stringstream text;
  pcrf::write_spectra_csv(text, table);
  const SpectraTable back = pcrf::read_spectra_csv(text, "lib.csv");
  ASSERT_EQ(back.entries.size(), 3u);
  EXPECT_EQ(back.periods_s, table.periods_s);
  EXPECT_EQ(back.entries[1].file_h2, "b,2.AT2");
  EXPECT_EQ(back.entries[2].sa_g, table.entries[2].sa_g);  // shortest round-trip text: exact
  auto refused = [](const std::string& csv) {
    return error_of([&] {
      std::istringstream in(csv);
      pcrf::read_spectra_csv(in, "lib.csv");
    });
  };
  const std::string head = "name,kind,file,file_h2,dt_s,samples,damping,pga_g,sa_g_0.5s,sa_g_1s\n";
  EXPECT_NE(refused("name,kind\n").find("lib.csv:1"), std::string::npos);
  EXPECT_NE(refused("name,kind,file,file_h2,dt_s,samples,damping,pga_g,sa_g_1s,sa_g_0.5s\n").find("periods must increase"), std::string::npos);
  EXPECT_NE(refused(head + "a,component,a.AT2,,0.01,100,0.05,0.3,0.2,-1\n").find("lib.csv:2: sa_g_1s"), std::string::npos);
  EXPECT_NE(refused(head + "a,other,a.AT2,,0.01,100,0.05,0.3,0.2,0.1\n").find("lib.csv:2: kind"), std::string::npos);
}

TEST(SpectraTable, RealRecordsGiveTheEnginesSaAndRotD50) {
  PCRF_REQUIRE_RECORDS(dir);
  const auto folder = dir / "nearfault_sehyeon9121";
  std::vector<std::string> skipped;
  const auto files = pcrf::library_files({folder}, skipped);
  const std::vector<double> periods{0.2, 1.0};
  const SpectraTable table = pcrf::compute_spectra(files, periods, 0.05, skipped);
  // Lucerne: LCN260 and LCN345 (LCN-UP is left out), and their RotD50.
  ASSERT_EQ(table.entries.size(), 3u);
  const auto h1 = pcrf::read_at2(folder / "RSN879_LANDERS_LCN260.AT2"), h2 = pcrf::read_at2(folder / "RSN879_LANDERS_LCN345.AT2");
  EXPECT_EQ(table.entries[0].sa_g[1], pcrf::spectral_acceleration_g(h1, 1.0));
  EXPECT_EQ(table.entries[2].kind, "rotd50");
  const pcrf::IntensitySpec spec{pcrf::IntensityMeasure::kSaRotD50, 1.0, 0.05, pcrf::SetNormalisation::kNone};
  EXPECT_EQ(table.entries[2].sa_g[1], pcrf::rotd(pcrf::HorizontalPair{h1, 260.0, h2, 345.0}, spec).rotd50);
}


// Issue 42 item 5 on the real library (../shared/records, 96 components; skipped without it):
// the check target of bench/selection_check.py --make-target (the components' geometric-mean
// spectrum, σ 0.6, ε 1 at T* = 1 s, Baker & Jayaram 2008; 20 periods 0.1–3.3 s). With the
// objective weighted by the tolerances (σ errors relative, w_mean 4, w_sigma 1), sets of 20 and
// 30 components match its median within 5 % and σ within 10 % at every period; Baker & Lee's
// algorithm as published (one simulated set, two passes, absolute σ errors) does not.
TEST(Selection, RealLibrarySetsOf20And30MeetTheTolerancesWithTheirWeights) {
  PCRF_REQUIRE_RECORDS(dir);
  std::vector<std::string> skipped;
  const auto files = pcrf::library_files({dir}, skipped);
  const SpectraTable library = pcrf::compute_spectra(files, pcrf::default_spectra_periods_s(), 0.05, skipped);
  std::size_t components = 0;
  std::vector<double> mean_ln(library.periods_s.size(), 0.0);
  for (const auto& e : library.entries)
    if (e.kind == "component") {
      ++components;
      for (std::size_t g = 0; g < mean_ln.size(); ++g) mean_ln[g] += std::log(e.sa_g[g]);
    }
  if (components != 96) GTEST_SKIP() << "the check is for the 96 components of ../shared/records, not " << components;
  std::string csv = "period_s,mean_ln_sa,sigma_ln_sa\n";
  for (std::size_t g = 0; g < mean_ln.size(); ++g) {
    const double t = library.periods_s[g];
    if (t < 0.1 || t > 4.0) continue;
    const double rho = pcrf::baker_jayaram_correlation(t, 1.0);
    csv += std::to_string(t) + "," + std::to_string(mean_ln[g] / static_cast<double>(components) + rho * 0.6) + "," +
           std::to_string(0.6 * std::sqrt(1.0 - rho * rho)) + "\n";
  }
  const auto target = target_from(csv);
  ASSERT_EQ(target.periods_s.size(), 20u);
  pcrf::SelectionSettings tolerances;
  tolerances.kind = "component";
  tolerances.relative_sigma = true;
  tolerances.w_mean = 4.0;
  tolerances.w_sigma = 1.0;
  for (std::size_t n : {20u, 30u}) {
    tolerances.count = n;
    const auto r = pcrf::select_records(target, library, tolerances);
    EXPECT_LE(r.median_error_percent, 5.0) << n;
    EXPECT_LE(r.sigma_error_percent, 10.0) << n;
    for (const auto& rec : r.records) EXPECT_TRUE(rec.scale >= 0.25 && rec.scale <= 4.0) << rec.scale;
  }
  pcrf::SelectionSettings published;
  published.kind = "component";
  published.count = 30;
  published.starts = 1;
  published.loops = 2;
  const auto r = pcrf::select_records(target, library, published);
  EXPECT_TRUE(r.median_error_percent > 5.0 || r.sigma_error_percent > 10.0)
      << "Baker & Lee as published now meets the tolerances: update docs/commands/record.md";
}

}  // namespace
