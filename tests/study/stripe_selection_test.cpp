// [selection]: records selected per hazard-consistent stripe from a spectra library, each
// stripe to its own target (conditioned on the study's Sa at the stripe's intensity); the
// case space runs stripe j's k-th record with its selection factor in slot k; the selection
// is part of the fingerprint; every refusal names the study file, line and key (and the
// library's or target's own line). And [[records]] scale, a record's own factor.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <set>

#include "pcrf/record/record_library.hpp"
#include "pcrf/record/synthetic.hpp"
#include "pcrf/study/case_space.hpp"
#include "pcrf/study/fingerprint.hpp"
#include "pcrf/study/study_check.hpp"
#include "pcrf/study/study_parser.hpp"
#include "pcrf/study/study_size.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study {
namespace {

namespace fs = std::filesystem;

const std::vector<double> kPeriods_s{0.2, 0.5, 1.0, 2.0};
const std::vector<double> kReturnPeriods_yr{100, 1000, 10000};

/// An AT2 file (in g) of a motion.
void write_at2(const fs::path& file, const GroundMotion& motion) {
  std::ofstream out(file);
  out << "PEER NGA STRONG MOTION DATABASE RECORD\nTest, 1/1/2000, Station, 000\nACCELERATION TIME SERIES IN UNITS OF G\n"
      << "NPTS=  " << motion.size() << ", DT=   " << motion.dt_s() << " SEC\n";
  out.precision(17);
  for (std::size_t i = 0; i < motion.size(); ++i) out << motion.samples_m_s2()[i] / kGravity_m_s2 << '\n';
}

/// ln Sa per period of the library's entries, by name (read back from the table the study reads).
std::map<std::string, std::vector<double>> library_ln_sa(const fs::path& table) {
  std::ifstream in(table);
  const SpectraTable t = read_spectra_csv(in, table.string());
  std::map<std::string, std::vector<double>> out;
  for (const auto& e : t.entries) {
    std::vector<double> ln;
    for (double sa : e.sa_g) ln.push_back(std::log(sa));
    out[e.name] = ln;
  }
  return out;
}

/// The folder: 16 stochastic records of different ground frequencies and PGAs (lib/), their
/// spectra table (lib.csv, absolute file paths), an Sa(1 s) hazard curve, and one target per
/// return period: conditioned at 1 s on the curve's intensity (σ = 0), elsewhere the library's
/// mean ln Sa(T) − ln Sa(1 s) above it with σ 0.3.
const fs::path& folder() {
  static const fs::path dir = [] {
    // One folder per test: ctest runs each test as its own process, several at once.
    const auto d = test::scratch_dir(std::string("stripe_selection_") +
                                     ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(d / "lib");
    std::vector<fs::path> files;
    for (int i = 0; i < 16; ++i) {
      StochasticSpec spec;
      spec.seed = static_cast<std::uint64_t>(i + 1);
      spec.pga_g = 0.2 + 0.05 * i;
      spec.duration_s = 5.0;
      spec.ground_freq_hz = 1.0 + 0.5 * (i % 6);
      files.push_back(d / "lib" / ("RSN" + std::to_string(i + 1) + "_TEST_X000.AT2"));
      write_at2(files.back(), make_stochastic(spec));
    }
    std::vector<std::string> skipped;
    const SpectraTable table = compute_spectra(files, kPeriods_s, 0.05, skipped);
    {
      std::ofstream out(d / "lib.csv");
      write_spectra_csv(out, table);
    }
    test::write_file(d, "hazard.csv", "# period_s = 1\nsa_g,annual_rate_per_yr\n0.05,0.1\n0.2,0.01\n0.6,1e-3\n2,1e-4\n5,1e-5\n");
    std::vector<double> shape(kPeriods_s.size(), 0.0);  // mean ln Sa(T) - ln Sa(1 s)
    for (const auto& e : table.entries)
      for (std::size_t j = 0; j < shape.size(); ++j) shape[j] += std::log(e.sa_g[j] / e.sa_g[2]) / double(table.entries.size());
    const std::vector<double> intensities{0.2, 0.6, 2.0};  // the curve's points at 1/T
    const std::vector<double> tilt{-0.4, 0.0, 0.4};         // each stripe its own shape: ln T times this
    for (std::size_t k = 0; k < intensities.size(); ++k) {
      std::ostringstream text;
      text.precision(17);
      text << "period_s,mean_ln_sa,sigma_ln_sa\n";
      for (std::size_t j = 0; j < kPeriods_s.size(); ++j)
        text << kPeriods_s[j] << ',' << std::log(intensities[k]) + shape[j] + tilt[k] * std::log(kPeriods_s[j]) << ','
             << (j == 2 ? 0.0 : 0.3) << '\n';
      test::write_file(d, "t" + std::to_string(int(kReturnPeriods_yr[k])) + ".csv", text.str());
    }
    return d;
  }();
  return dir;
}

const std::string kIntensity =
    "[intensity]\nmeasure = \"sa_g\"\nperiod_s = 1\nhazard = \"hazard.csv\"\nreturn_periods_yr = [100, 1000, 10000]\n";
const std::string kSelection =
    "[selection]\nlibrary = \"lib.csv\"\ntargets = [\"t100.csv\", \"t1000.csv\", \"t10000.csv\"]\ncount = 4\n"
    "scale_min = 0.05\nscale_max = 50\nseed = 3\n";

Study parse(const std::string& text) { return parse_study(text, "s.toml", folder()); }
std::string error_of(const std::string& text) { return study_test::error_of(parse, text); }

TEST(StripeSelection, EachStripeRunsItsOwnRecordsScaledToItsIntensity) {
  const Study s = parse(kIntensity + kSelection);
  ASSERT_TRUE(s.selection);
  const auto& sel = *s.selection;
  ASSERT_EQ(sel.stripes.size(), 3u);
  ASSERT_EQ(s.levels.size(), 3u);
  EXPECT_NEAR(s.levels[0], 0.2, 1e-12);  // the curve's points
  EXPECT_NEAR(s.levels[2], 2.0, 1e-12);
  const auto ln_sa = library_ln_sa(folder() / "lib.csv");
  std::set<std::size_t> used;
  for (std::size_t k = 0; k < 3; ++k) {
    const auto& stripe = sel.stripes[k];
    ASSERT_EQ(stripe.records.size(), 4u);
    ASSERT_EQ(stripe.scales.size(), 4u);
    EXPECT_EQ(std::set<std::size_t>(stripe.records.begin(), stripe.records.end()).size(), 4u) << "each record once a stripe";
    for (std::size_t slot = 0; slot < 4; ++slot) {
      const std::size_t r = stripe.records[slot];
      used.insert(r);
      ASSERT_LT(r, s.records.size());
      ASSERT_TRUE(s.records[r].file);
      EXPECT_TRUE(fs::exists(s.records[r].file->path)) << s.records[r].file->path;
      // Conditioned at 1 s: the library's Sa(1 s) times the factor is the stripe's intensity.
      EXPECT_NEAR(std::exp(ln_sa.at(s.records[r].name)[2]) * stripe.scales[slot] / s.levels[k], 1.0, 1e-9) << k << ' ' << slot;
    }
    EXPECT_TRUE(std::isfinite(stripe.fit.sum_of_squares));
  }
  EXPECT_EQ(used.size(), s.records.size()) << "the study's records are exactly those some stripe uses";
  // Each stripe to its own target: the first and last (shapes tilted apart) share not every record.
  EXPECT_NE(std::set<std::size_t>(sel.stripes[0].records.begin(), sel.stripes[0].records.end()),
            std::set<std::size_t>(sel.stripes[2].records.begin(), sel.stripes[2].records.end()));

  // The case space: slots × stripes × the frame; case (slot, stripe) runs that stripe's record.
  const CaseSpace space(s);
  ASSERT_GE(space.shape().size(), 2u);
  EXPECT_EQ(space.shape()[0], 4u);
  EXPECT_EQ(space.shape()[1], 3u);
  EXPECT_EQ(space.record_names(), (std::vector<std::string>{"slot_1", "slot_2", "slot_3", "slot_4"}));
  EXPECT_EQ(study_size(s).cases, double(space.size()));
  for (std::size_t slot = 0; slot < 4; ++slot)
    for (std::size_t k = 0; k < 3; ++k) {
      std::vector<std::size_t> c(space.shape().size(), 0);
      c[0] = slot;
      c[1] = k;
      const CaseSpec spec = space.case_at(space.index(c));
      EXPECT_EQ(spec.record, sel.stripes[k].records[slot]);
      ASSERT_TRUE(spec.factor);
      EXPECT_EQ(*spec.factor, sel.stripes[k].scales[slot]);
      EXPECT_EQ(spec.level, s.levels[k]);
    }

  // Deterministic by its seed: read again, the same records and factors; and the targets
  // given as one file name with the return period in it are the same files.
  std::string pattern = kSelection;
  pattern.replace(pattern.find("[\"t100.csv\", \"t1000.csv\", \"t10000.csv\"]"), 39, "\"t{return_period_yr}.csv\"");
  const Study again = parse(kIntensity + pattern);
  EXPECT_EQ(again.selection->stripes[2].target, "t10000.csv");
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(again.selection->stripes[k].scales, sel.stripes[k].scales);
    for (std::size_t slot = 0; slot < 4; ++slot)
      EXPECT_EQ(again.records[again.selection->stripes[k].records[slot]].name, s.records[sel.stripes[k].records[slot]].name);
  }
}

TEST(StripeSelection, TheSelectionIsPartOfTheFingerprintAndPassesTheChecks) {
  auto fingerprint = [](const std::string& text, std::string* description = nullptr) {
    const Study s = parse(text);
    const CaseSpace space(s);
    RecordCache records(s.records);
    (void)check_study(s, space, records);  // each scaled record at its stripe's intensity: no refusal
    if (description) *description = canonical_description(s, space, records);
    return study_fingerprint(s, space, records);
  };
  std::string description;
  const std::string base = fingerprint(kIntensity + kSelection, &description);
  EXPECT_NE(description.find("selection kind=component count=4 scale_min=0.05"), std::string::npos) << description;
  EXPECT_NE(description.find(" scale_max=50 seed=3 trials=20 loops=100\n"), std::string::npos) << description;
  const Study s = parse(kIntensity + kSelection);
  std::ostringstream stripe;
  stripe.precision(17);
  stripe << "stripe " << s.records[s.selection->stripes[1].records[0]].name << '*' << s.selection->stripes[1].scales[0];
  EXPECT_NE(description.find(stripe.str()), std::string::npos) << description;
  EXPECT_EQ(fingerprint(kIntensity + kSelection), base);
  std::string more = kSelection;
  more.replace(more.find("count = 4"), 9, "count = 5");
  EXPECT_NE(fingerprint(kIntensity + more), base);
  std::string other = kSelection;
  other.replace(other.find("\"t1000.csv\", \"t10000.csv\""), 25, "\"t1000.csv\", \"t1000b.csv\"");
  test::write_file(folder(), "t1000b.csv", test::read_file(folder() / "t10000.csv") + "");
  EXPECT_EQ(fingerprint(kIntensity + other), base) << "the same selection, by another file name: the same study";
}

TEST(StripeSelection, AScaledRecordOffItsStripesIntensityIsRefusedByTheCheck) {
  // A library whose Sa(1 s) is not the records' own (here: halved for every entry): the
  // selection scales to the target, but the records would shake at half the stripe's
  // intensity, and the cube's intensity, which cube risk integrates, would be wrong.
  std::ifstream in(folder() / "lib.csv");
  SpectraTable table = read_spectra_csv(in, "lib.csv");
  for (auto& e : table.entries) e.sa_g[2] *= 0.5;
  {
    std::ofstream out(folder() / "halved.csv");
    write_spectra_csv(out, table);
  }
  std::string text = kIntensity + kSelection;
  text.replace(text.find("\"lib.csv\""), 9, "\"halved.csv\"");
  const Study s = parse(text);
  const CaseSpace space(s);
  RecordCache records(s.records);
  try {
    (void)check_study(s, space, records);
    ADD_FAILURE() << "not refused";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("s.toml:8: [selection] targets: record \""), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not the stripe's intensity"), std::string::npos) << e.what();
  }
}

TEST(StripeSelection, RefusalsNameTheStudyFileLineAndKey) {
  test::write_file(folder(), "sigma.csv", "period_s,mean_ln_sa,sigma_ln_sa\n0.5,0,0.3\n1,-1.6094379124341003,0.2\n");
  test::write_file(folder(), "level.csv", "period_s,mean_ln_sa,sigma_ln_sa\n0.5,0,0.3\n1,-1.5,0\n");
  test::write_file(folder(), "nop.csv", "period_s,mean_ln_sa,sigma_ln_sa\n0.5,0,0.3\n0.7,-1.5,0\n");
  test::write_file(folder(), "far.csv", "period_s,mean_ln_sa,sigma_ln_sa\n1,-1.6094379124341003,0\n3,-2,0.3\n");
  test::write_file(folder(), "bad.csv", "period_s,mean_ln_sa,sigma_ln_sa\n1,-1.6094379124341003,0\n0.5,-1,-0.3\n");
  auto with = [](const std::string& from, const std::string& to) {
    std::string text = kIntensity + kSelection;
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  const std::string targets = "targets = [\"t100.csv\", \"t1000.csv\", \"t10000.csv\"]";
  const std::map<std::string, std::string> corpus = {
      {with(targets, "targets = [\"t100.csv\", \"t1000.csv\"]"),
       "s.toml:8: [selection] targets: 2 target(s) for 3 return periods in return_periods_yr (s.toml:5)"},
      {with(targets, "targets = [\"t100.csv\", \"none.csv\", \"t10000.csv\"]"), "s.toml:8: [selection] targets: none.csv: no such file"},
      {with(targets, "targets = [\"sigma.csv\", \"t1000.csv\", \"t10000.csv\"]"),
       "s.toml:8: [selection] targets: sigma.csv:3: sigma_ln_sa: is 0.2 at period_s = 1 s"},
      {with(targets, "targets = [\"level.csv\", \"t1000.csv\", \"t10000.csv\"]"),
       "s.toml:8: [selection] targets: level.csv:3: mean_ln_sa: the target is conditioned on Sa(1 s) = 0.22313016014842982 g, "
       "but the stripe of return period 100 yr is at 0.2 g"},
      {with(targets, "targets = [\"nop.csv\", \"t1000.csv\", \"t10000.csv\"]"),
       "s.toml:8: [selection] targets: nop.csv: no row at period_s = 1 s"},
      {with(targets, "targets = [\"far.csv\", \"t1000.csv\", \"t10000.csv\"]"),
       "s.toml:8: [selection] targets: stripe of 100 yr (far.csv): far.csv:3: period_s: 3 s is outside the library's periods"},
      {with(targets, "targets = [\"bad.csv\", \"t1000.csv\", \"t10000.csv\"]"), "s.toml:8: [selection] targets: bad.csv:3: period_s"},
      {with("\"lib.csv\"", "\"nolib.csv\""), "s.toml:7: [selection] library: nolib.csv: no such file"},
      {with("\"lib.csv\"", "\"t100.csv\""), "s.toml:7: [selection] library: t100.csv:1:"},
      {with("count = 4", "count = 40"), "s.toml:9: [selection] count: stripe of 100 yr (t100.csv): 16 entries of kind component"},
      {with("count = 4", "count = 1"), "s.toml:9: [selection] count: must be 2 to 100000, got 1"},
      {with("count = 4\n", ""), "s.toml:6: [selection] count: required"},
      {with("scale_max = 50", "scale_max = 0.01"), "s.toml:11: [selection] scale_max: must be a number at least scale_min"},
      {with("seed = 3", "seed = 3\nkind = \"rotd50\""),
       "s.toml:13: [selection] kind: the study's measure sa_g is compared with entries of kind component, not rotd50"},
      {with("seed = 3", "seed = 3\nloops = -1"), "s.toml:13: [selection] loops: must be 0 to 1000"},
      {with("seed = 3", "seed = 3\nlenght = 2"), "s.toml:13: [selection] lenght: "},
      {kSelection, "s.toml:2: [selection] library: selects records per stripe of hazard-consistent stripes"},
      {"[intensity]\nmeasure = \"pga_g\"\nhazard = \"hazard.csv\"\nreturn_periods_yr = [100]\n" + kSelection, "[intensity] hazard:"},
      {kIntensity + kSelection + "[[records]]\nsynthetic = \"sine:amplitude_g=1\"\n",
       "s.toml:13: records: [selection] chooses each stripe's records from its library: give no [[records]]"},
  };
  for (const auto& [text, message] : corpus) {
    const std::string error = error_of(text);
    EXPECT_NE(error.find(message), std::string::npos) << text << "\ngot: " << error;
  }
  // A measure without a spectrum (pga_g): its own hazard curve, then refused by [selection].
  test::write_file(folder(), "pga.csv", "pga_g,annual_rate_per_yr\n0.05,0.1\n2,1e-4\n");
  const std::string pga = error_of("[intensity]\nmeasure = \"pga_g\"\nhazard = \"pga.csv\"\nreturn_periods_yr = [100, 1000, 10000]\n" +
                                   kSelection);
  EXPECT_NE(pga.find("s.toml:6: [selection] library: a library holds spectra: the study's [intensity] measure must be sa_g"),
            std::string::npos)
      << pga;
}

TEST(RecordScale, ARecordsOwnFactorMultipliesTheScaleAxis) {
  const fs::path dir = test::scratch_dir("record_scale");
  auto parse = [&](const std::string& text) { return parse_study(text, "s.toml", dir); };
  auto error_of = [&](const std::string& text) { return study_test::error_of(parse, text); };
  const Study s = parse("[[records]]\nsynthetic = \"sine:amplitude_g=1\"\nscale = 2.5\n"
                        "[[records]]\nsynthetic = \"sine:amplitude_g=2\"\n[axes]\nscale = [1, 3]\n");
  ASSERT_EQ(s.records.size(), 2u);
  EXPECT_EQ(s.records[0].scale, 2.5);
  EXPECT_EQ(s.records[1].scale, 1.0);
  RecordCache records(s.records);
  EXPECT_EQ(records.scale_factor(0, 3.0, s.intensity), 7.5);
  EXPECT_EQ(records.scale_factor(1, 3.0, s.intensity), 3.0);
  // In the fingerprint: another factor, another study; none given, the study as it was.
  auto fingerprint = [&](const std::string& text) {
    const Study study = parse(text);
    RecordCache cache(study.records);
    return canonical_description(study, CaseSpace(study), cache);
  };
  const std::string plain = fingerprint("[[records]]\nsynthetic = \"sine:amplitude_g=1\"\n");
  EXPECT_EQ(plain.find("scale="), std::string::npos);
  EXPECT_NE(fingerprint("[[records]]\nsynthetic = \"sine:amplitude_g=1\"\nscale = 2\n"), plain);

  const std::map<std::string, std::string> corpus = {
      {"[[records]]\nsynthetic = \"sine:amplitude_g=1\"\nscale = 0\n", "s.toml:3: [[records]] #1 scale: must be a positive number"},
      {"[[records]]\nsynthetic = \"sine:amplitude_g=1\"\nscale = -2\n", "s.toml:3: [[records]] #1 scale: must be a positive number"},
      {"[[records]]\nsynthetic = \"sine:amplitude_g=1\"\nscale = \"2\"\n", "s.toml:3: [[records]] #1 scale: expected a number"},
      {"[intensity]\nmeasure = \"pga_g\"\n[axes]\nintensity = [1]\n[[records]]\nsynthetic = \"sine:amplitude_g=1\"\nscale = 2\n",
       "s.toml:7: [[records]] #1 scale: [intensity] scales every record to each of its intensities, which would cancel"},
      {"[[records]]\npulse = \"ricker\"\nscale = 2\n[axes]\npulse_period_s = [0.5]\npulse_amplitude_g = [1]\n",
       "s.toml:3: [[records]] #1 scale: does not apply to pulse records"},
  };
  for (const auto& [text, message] : corpus) {
    const std::string error = error_of(text);
    EXPECT_NE(error.find(message), std::string::npos) << text << "\ngot: " << error;
  }
}

}  // namespace
}  // namespace pcrf::study
