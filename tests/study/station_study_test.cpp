// Studies of stations: [[records]] h1/h2/up through the same StationRecord/frame_excitation
// code as `pcrf run`; the incidence axis (h1 alone at φ = az₁ bit for bit, a half turn
// mirrors, the components' order does not matter); RotD measures; a DWN vertical's sign;
// `pcrf cube stats --reduce-over incidence_deg`; one-line errors for bad stations.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>

#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/excitation/station_record.hpp"
#include "pcrf/record/intensity.hpp"
#include "pcrf/record/record_readers.hpp"
#include "pcrf/record/synthetic.hpp"
#include "pcrf/study/record_source.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study_test {
namespace {

/// `motion` as a two-column file in m/s² (17 digits: read back exactly).
void write_motion(const std::filesystem::path& file, const GroundMotion& motion, double dt_s) {
  std::ofstream out(file);
  char line[80];
  for (std::size_t i = 0; i < motion.size(); ++i) {
    std::snprintf(line, sizeof line, "%.17g %.17g\n", static_cast<double>(i) * dt_s, motion.samples_m_s2()[i]);
    out << line;
  }
}

GroundMotion noise(std::uint64_t seed, double pga_g) {
  StochasticSpec s;
  s.seed = seed;
  s.pga_g = pga_g;
  s.duration_s = 6.0;
  return make_stochastic(s);
}

/// h1.txt and h2.txt (two stochastic components), zero.txt (no motion), up.txt (a vertical).
std::filesystem::path station_files(const std::string& name) {
  const auto dir = test::scratch_dir(name);
  const GroundMotion h1 = noise(3, 1.0), h2 = noise(4, 0.9), up = noise(5, 0.4);
  write_motion(dir / "h1.txt", h1, h1.dt_s());
  write_motion(dir / "h2.txt", h2, h2.dt_s());
  write_motion(dir / "up.txt", up, up.dt_s());
  write_motion(dir / "zero.txt", h1.scaled(0.0), h1.dt_s());
  write_motion(dir / "slow.txt", h2, 2.0 * h2.dt_s());
  return dir;
}

test::CommandResult study(const std::filesystem::path& dir, const std::string& name, const std::string& text) {
  const auto file = test::write_file(dir, name + ".toml", text);
  return test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study " + quoted(file) + " -o " + name +
                           ".h5 --overwrite --progress-interval 0");
}

const std::string kFrame = "[axes]\nscale = [1.4]\n";

TEST(StationStudy, TheIncidenceAxisGivesTheFirstComponentAloneMirrorsAndIgnoresOrder) {
  const auto dir = station_files("station_incidence");
  ASSERT_EQ(study(dir, "alone", "[[records]]\nfile = \"h1.txt\"\nunits = \"m/s2\"\n" + kFrame).exit_code, 0);
  const std::string axis = "incidence_deg = [260, 80, 47, 227]\n";
  auto r = study(dir, "pair",
                 "[[records]]\nh1 = \"h1.txt\"\nh2 = \"h2.txt\"\nunits = \"m/s2\"\naz1_deg = 260\naz2_deg = 345\n" + kFrame + axis);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = study(dir, "swapped",
            "[[records]]\nh1 = \"h2.txt\"\nh2 = \"h1.txt\"\nunits = \"m/s2\"\naz1_deg = 345\naz2_deg = 260\n" + kFrame + axis);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  cube::CubeReader alone(dir / "alone.h5"), pair(dir / "pair.h5"), swapped(dir / "swapped.h5");
  ASSERT_EQ(pair.layout().dimensions[2].name, "incidence_deg");
  EXPECT_EQ(pair.layout().find_coordinate("incidence_deg")->units, "degree");
  EXPECT_EQ(pair.layout().find_coordinate("record_azimuth_h2_deg")->numbers[0], 345.0);
  const auto a = alone.read_metric("theta_max_rad"), p = pair.read_metric("theta_max_rad"),
             s = swapped.read_metric("theta_max_rad");
  ASSERT_EQ(p.size(), 4u);
  ASSERT_GT(a[0], 0.0);           // it rocks
  EXPECT_EQ(p[0], a[0]);          // φ = az₁: the first component alone, bit for bit
  EXPECT_EQ(p[1], p[0]);          // φ + 180°: mirrored, the same θ_max
  EXPECT_EQ(p[3], p[2]);
  EXPECT_NE(p[2], p[0]);          // another orientation is another motion
  EXPECT_EQ(s, p);                // the components' order does not matter
  EXPECT_EQ(alone.read_metric("impacts")[0], pair.read_metric("impacts")[0]);
}

TEST(StationStudy, RotDMeasuresScalePairsAndTheVerticalWithThem) {
  const auto dir = station_files("station_rotd");
  const GroundMotion h1 = read_record({dir / "h1.txt", RecordFormat::kTwoColumn, AccelUnit::kMeterPerSecond2, 0.0, 0, 0});
  const double pga_g = peak_acceleration(h1).pga_g;
  // One direction only (h2 = 0): RotD100 is its PGA and RotD50 PGA·cos 45° (Boore 2010).
  for (const auto& [measure, expected] : std::map<std::string, double>{{"pga_rotd100_g", pga_g},
                                                                       {"pga_rotd50_g", pga_g * std::sqrt(0.5)}}) {
    const auto r = study(dir, "one_" + measure,
                         "[[records]]\nh1 = \"h1.txt\"\nh2 = \"zero.txt\"\nunits = \"m/s2\"\naz1_deg = 10\naz2_deg = 100\n"
                         "[intensity]\nmeasure = \"" + measure + "\"\n[axes]\nintensity = [1.0]\n");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    cube::CubeReader cube(dir / ("one_" + measure + ".h5"));
    const auto* unscaled = cube.layout().find_coordinate("record_" + measure);
    ASSERT_NE(unscaled, nullptr);
    EXPECT_NEAR(unscaled->numbers[0], expected, 1e-12 * expected) << measure;
    EXPECT_NEAR(cube.read_side("scale_factor")[0], 1.0 / expected, 1e-12 / expected);
  }
  // A station with its vertical: the study's case is `pcrf run`'s, bit for bit (one
  // implementation: the pair and the vertical scaled by one factor).
  auto r = study(dir, "three",
                 "[[records]]\nh1 = \"h1.txt\"\nh2 = \"h2.txt\"\nup = \"up.txt\"\nunits = \"m/s2\"\naz1_deg = 0\naz2_deg = 90\n"
                 "[intensity]\nmeasure = \"sa_rotd50_g\"\nperiod_s = 0.5\n[axes]\nintensity = [1.1]\nincidence_deg = [30]\n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto run = test::run_command(
      "cd " + quoted(dir) + " && " + pcrf() +
      " run --record h1.txt --record-h2 h2.txt --record-up up.txt --units m/s2 --azimuth-deg 0 --h2-azimuth-deg 90"
      " --incidence-deg 30 --measure sa_rotd50_g --period-s 0.5 --intensity 1.1");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  cube::CubeReader cube(dir / "three.h5");
  const auto at = run.out.find("\"theta_max_rad\": ");
  ASSERT_NE(at, std::string::npos);
  EXPECT_EQ(std::strtod(run.out.c_str() + at + 17, nullptr), cube.read_metric("theta_max_rad")[0]);
  const auto f = run.out.find("\"scale_factor\": ");
  EXPECT_EQ(std::strtod(run.out.c_str() + f + 16, nullptr), cube.read_side("scale_factor")[0]);
}

TEST(StationStudy, StatsReduceOverTheIncidence) {
  const auto dir = station_files("station_stats");
  const auto r = study(dir, "sweep",
                       "[[records]]\nh1 = \"h1.txt\"\nh2 = \"h2.txt\"\nunits = \"m/s2\"\naz1_deg = 0\naz2_deg = 90\nname = \"a\"\n"
                       "[[records]]\nh1 = \"h2.txt\"\nh2 = \"h1.txt\"\nunits = \"m/s2\"\naz1_deg = 30\naz2_deg = 120\nname = \"b\"\n"
                       "[axes]\nscale = [1.2, 1.6]\nincidence_deg = {from = 0, to = 150, count = 6}\n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  cube::CubeReader cube(dir / "sweep.h5");
  const auto theta = cube.read_metric("theta_max_rad");
  const auto status = cube.read_status();
  // By hand: per record and scale, the largest and the median θ_max over the six incidences.
  for (const std::string how : {"max", "median", "min"}) {
    const auto out = test::run_command(pcrf() + " cube stats " + quoted(dir / "sweep.h5") +
                                       " --by scale -m theta_max_rad --reduce-over incidence_deg --reduce " + how);
    ASSERT_EQ(out.exit_code, 0) << out.err;
    for (std::size_t l = 0; l < 2; ++l) {
      std::vector<double> reduced;
      std::size_t collapses = 0;
      for (std::size_t rec = 0; rec < 2; ++rec) {
        std::vector<double> v;
        std::size_t apart = 0;
        for (std::size_t k = 0; k < 6; ++k) {
          const std::size_t i = (rec * 2 + l) * 6 + k;
          if (status[i] == 2 || status[i] == 3) ++apart;
          else v.push_back(theta[i]);
        }
        std::sort(v.begin(), v.end());
        const bool is_apart = how == "max" ? apart > 0 : how == "min" ? apart == 6 : 2 * apart > 6;
        if (is_apart) ++collapses;
        else reduced.push_back(how == "max" ? v.back() : how == "min" ? v.front() : 0.5 * (v[(v.size() - 1) / 2] + v[v.size() / 2]));
      }
      std::sort(reduced.begin(), reduced.end());
      // The CSV line of this scale: scale,cases,collapses,values,median,…
      const std::string scale = l == 0 ? "1.2," : "1.6,";
      const auto line = out.out.find("\n" + scale);
      ASSERT_NE(line, std::string::npos) << out.out;
      unsigned cases = 0, apart = 0, values = 0;
      double median = 0.0;
      ASSERT_EQ(std::sscanf(out.out.c_str() + line + 1 + scale.size(), "%u,%u,%u,%lf", &cases, &apart, &values, &median), 4)
          << out.out;
      EXPECT_EQ(cases, 2u);
      EXPECT_EQ(apart, collapses) << how;
      ASSERT_EQ(values, reduced.size()) << how;
      if (!reduced.empty()) {
        EXPECT_DOUBLE_EQ(median, reduced.size() == 2 ? 0.5 * (reduced[0] + reduced[1]) : reduced[0]) << how << " " << l;
      }
    }
  }
  const auto bad = test::run_command(pcrf() + " cube stats " + quoted(dir / "sweep.h5") +
                                     " --by incidence_deg -m theta_max_rad --reduce-over incidence_deg");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("cannot group by 'incidence_deg' and reduce over its dimension"), std::string::npos) << bad.err;
}

TEST(StationStudy, AnIdasCollapseIntensityReducesOverTheIncidence) {
  const auto dir = station_files("station_ida");
  const auto r = study(dir, "ida",
                       "[[records]]\nh1 = \"h1.txt\"\nh2 = \"h2.txt\"\nunits = \"m/s2\"\naz1_deg = 0\naz2_deg = 90\nstrike_deg = 20\n"
                       "[intensity]\nmeasure = \"pga_rotd50_g\"\n[ida]\nstart = 1.0\nstep = 1.0\nmax_intensity = 12\nmax_runs = 8\n"
                       "[axes]\nincidence = \"fault-normal\"\nincidence_deg = [0, 40, 80, 120]\n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  cube::CubeReader cube(dir / "ida.h5");
  const auto* azimuth = cube.layout().find_side_variable("frame_azimuth_deg");
  ASSERT_NE(azimuth, nullptr);
  EXPECT_EQ(cube.read_side("frame_azimuth_deg"), (std::vector<double>{110.0, 150.0, 190.0, 230.0}));
  const auto ci = cube.read_side("collapse_intensity");
  ASSERT_EQ(ci.size(), 4u);
  std::vector<double> found;
  for (double c : ci)
    if (std::isfinite(c)) found.push_back(c);
  ASSERT_FALSE(found.empty());
  for (const std::string how : {"min", "max"}) {
    const auto out = test::run_command(pcrf() + " cube stats " + quoted(dir / "ida.h5") +
                                       " --by kappa -m collapse_intensity --reduce-over incidence_deg --reduce " + how);
    ASSERT_EQ(out.exit_code, 0) << out.err;
    const auto line = out.out.find('\n');
    unsigned cases = 0, apart = 0, values = 0;
    double median = 0.0;
    ASSERT_EQ(std::sscanf(out.out.c_str() + line + 1, "%*[^,],%u,%u,%u,%lf", &cases, &apart, &values, &median), 4) << out.out;
    EXPECT_EQ(cases, 1u);
    EXPECT_EQ(values, 1u);
    EXPECT_EQ(median, how == "min" ? *std::min_element(found.begin(), found.end()) : *std::max_element(found.begin(), found.end()));
  }
}

TEST(StationStudy, BadStationsAreRefusedWithTheirLine) {
  const auto dir = station_files("station_bad");
  test::write_file(dir, "h090.AT2",
                   "PEER NGA STRONG MOTION DATABASE RECORD\nTest, 1/1/2000, Station, 090\n"
                   "ACCELERATION TIME SERIES IN UNITS OF G\nNPTS=    3, DT=   .0100 SEC\n  0.0  0.1  -0.1\n");
  const std::string pair = "[[records]]\nh1 = \"h1.txt\"\nh2 = \"h2.txt\"\nunits = \"m/s2\"\naz1_deg = 0\naz2_deg = 90\n";
  const std::map<std::string, std::string> corpus = {
      {"[[records]]\nh1 = \"h1.txt\"\nh2 = \"slow.txt\"\nunits = \"m/s2\"\naz1_deg = 0\naz2_deg = 90\n" + kFrame,
       "bad.toml:2: [[records]] #1 h1: cannot load record \"h1\""},
      {"[[records]]\nh1 = \"h1.txt\"\nunits = \"m/s2\"\nup = \"h090.AT2\"\n" + kFrame,
       "its header names a horizontal component ('090'), given as the vertical"},
      {pair + "[axes]\nincidence = \"fault-normal\"\n", "bad.toml:2: [[records]] #1 h1: incidence = \"fault-normal\" needs the fault's strike"},
      {"[[records]]\nfile = \"h1.txt\"\nunits = \"m/s2\"\n[axes]\nincidence_deg = [10]\n",
       "bad.toml:2: [[records]] #1 file: the study has an incidence axis: record \"h1\" needs its second horizontal component"},
      {pair + "[intensity]\nmeasure = \"pga_g\"\n[axes]\nintensity = [1]\nincidence_deg = [0, 90]\n",
       "[axes] incidence_deg: the records are scaled by their pga_g, which depends on the frame's orientation"},
      {"[[records]]\nfile = \"h1.txt\"\nunits = \"m/s2\"\n[intensity]\nmeasure = \"pga_rotd50_g\"\n[axes]\nintensity = [1]\n",
       "[[records]] #1 file: intensity measure pga_rotd50_g is a measure of a pair"},
      {"[[records]]\nh1 = \"h1.txt\"\nh2 = [\"h2.txt\", \"up.txt\"]\nunits = \"m/s2\"\n" + kFrame,
       "[[records]] #1 h2: 2 files for 1 first components (h1)"},
      {"[[records]]\nfile = \"h1.txt\"\nh2 = \"h2.txt\"\nunits = \"m/s2\"\n" + kFrame, "[[records]] #1 h2: a station's components are h1"},
      {pair + "[axes]\nincidence = \"north-east\"\n", "[axes] incidence: expected \"north\", \"fault-normal\" or \"fault-parallel\""},
  };
  for (const auto& [text, expected] : corpus) {
    const auto r = study(dir, "bad", text);
    EXPECT_EQ(r.exit_code, 2) << text;
    EXPECT_NE(r.err.find(expected), std::string::npos) << text << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

TEST(StationStudy, ADownwardVerticalIsNegatedToPositiveUp) {
  // Synthetic: the component name decides, as a horizontal's name gives its azimuth.
  std::vector<std::string> notes;
  const GroundMotion v = noise(7, 0.3);
  const StationRecord down = make_station({v, "H-DLT262", "h1"}, {}, std::nullopt, {}, StationComponent{v, "H-DLTDWN", "v"}, notes);
  EXPECT_EQ(down.up->samples_m_s2(), v.scaled(-1.0).samples_m_s2());
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("positive down: negated to positive up"), std::string::npos);
  const StationRecord up = make_station({v, "H-E11140", "h1"}, {}, std::nullopt, {}, StationComponent{v, "H-E11-UP", "v"}, notes);
  EXPECT_EQ(up.up->samples_m_s2(), v.samples_m_s2());
  // The real records whose file names say which way is up: RSN169 Delta (H-DLTDWN) and
  // RSN1148 Arcelik (AREDWN) come negated; RSN174 El Centro #11 (H-E11-UP) as recorded.
  PCRF_REQUIRE_RECORDS(records);
  const std::vector<std::tuple<std::string, std::string, std::string, double>> stations = {
      {"vertical_sehyeon9121/RSN169_IMPVALL.H_H-DLT262.AT2", "vertical_sehyeon9121/RSN169_IMPVALL.H_H-DLT352.AT2",
       "vertical_sehyeon9121/RSN169_IMPVALL.H_H-DLTDWN.AT2", -1.0},
      {"vertical_sehyeon9121/RSN1148_KOCAELI_ARE000.AT2", "vertical_sehyeon9121/RSN1148_KOCAELI_ARE090.AT2",
       "vertical_sehyeon9121/RSN1148_KOCAELI_AREDWN.AT2", -1.0},
      {"vertical_sehyeon9121/RSN174_IMPVALL.H_H-E11140.AT2", "vertical_sehyeon9121/RSN174_IMPVALL.H_H-E11230.AT2",
       "vertical_sehyeon9121/RSN174_IMPVALL.H_H-E11-UP.AT2", 1.0}};
  for (const auto& [h1, h2, vertical, sign] : stations) {
    if (!std::filesystem::exists(records / h1) || !std::filesystem::exists(records / h2)) continue;
    study::RecordSource source;
    source.name = "s";
    source.file = RecordFileSpec{records / h1, RecordFormat::kAt2, AccelUnit::kG, 0.0, 0, 0};
    source.h2 = RecordFileSpec{records / h2, RecordFormat::kAt2, AccelUnit::kG, 0.0, 0, 0};
    source.up = RecordFileSpec{records / vertical, RecordFormat::kAt2, AccelUnit::kG, 0.0, 0, 0};
    const study::LoadedRecord loaded = study::load_record(source);
    const GroundMotion as_filed = read_record(*source.up);
    const auto& aligned = loaded.station.up->samples_m_s2();  // padded with zeros where a horizontal is longer
    ASSERT_GE(aligned.size(), as_filed.size());
    EXPECT_EQ(std::vector<double>(aligned.begin(), aligned.begin() + static_cast<std::ptrdiff_t>(as_filed.size())),
              as_filed.scaled(sign).samples_m_s2())
        << vertical;
    const auto sign_notes = std::count_if(loaded.notes.begin(), loaded.notes.end(),
                                          [](const std::string& n) { return n.find("positive down") != std::string::npos; });
    EXPECT_EQ(sign_notes, sign < 0 ? 1 : 0) << vertical;
    EXPECT_TRUE(loaded.station.az1_deg && loaded.station.az2_deg) << h1;
  }
}

test::CommandResult check(const std::filesystem::path& dir, const std::string& name, const std::string& text) {
  const auto file = test::write_file(dir, name + ".toml", text);
  return test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study " + quoted(file) + " --check");
}

// Issue 29: 3.7 meant as 212° ran at 3.7° without a word. Incidences that all look like
// radians warn naming the key and its line; warnings_as_errors stops the study. --check
// also says what the run will cost and how that was measured.
TEST(StationStudy, IncidencesInRadiansWarnAndCheckEstimatesTheCost) {
  const auto dir = station_files("station_radians");
  const std::string records = "[[records]]\nh1 = \"h1.txt\"\nh2 = \"h2.txt\"\nunits = \"m/s2\"\naz1_deg = 0\naz2_deg = 90\n";
  const auto warned = check(dir, "r", records + kFrame + "incidence_deg = [3.7, 1.2]\n");
  ASSERT_EQ(warned.exit_code, 0) << warned.err;
  EXPECT_NE(warned.err.find("r.toml:9: [axes] incidence_deg"), std::string::npos) << warned.err;
  EXPECT_NE(warned.err.find("3.7"), std::string::npos) << warned.err;
  EXPECT_NE(warned.out.find("cost estimate"), std::string::npos) << warned.out;
  EXPECT_NE(warned.out.find("sampled cases"), std::string::npos) << warned.out;
  const auto degrees = check(dir, "d", records + kFrame + "incidence_deg = [212, 30]\n");
  ASSERT_EQ(degrees.exit_code, 0) << degrees.err;
  EXPECT_EQ(degrees.err.find("incidence_deg"), std::string::npos) << degrees.err;
  const auto stopped = check(dir, "e", records + kFrame + "incidence_deg = [3.7]\n[run]\nwarnings_as_errors = true\n");
  EXPECT_EQ(stopped.exit_code, 2) << stopped.err;
  EXPECT_NE(stopped.err.find("warnings_as_errors"), std::string::npos) << stopped.err;
}

// Issue 29: Rinaldi (Northridge 1994) paired with a San Fernando 1971 station was combined
// silently. The AT2 headers name different events and stations: a warning names both.
TEST(StationStudy, ComponentsOfTwoStationsWarnNamingBoth) {
  PCRF_REQUIRE_RECORDS(records);
  const auto rinaldi = records / "nearfault_vacalderon" / "RSN1063_NORTHR_RRS228.AT2";
  const auto pel = records / "vertical_sehyeon9121" / "RSN68_SFERN_PEL090.AT2";
  if (!std::filesystem::exists(rinaldi) || !std::filesystem::exists(pel)) GTEST_SKIP() << "RSN1063 or RSN68 missing";
  const auto dir = test::scratch_dir("station_two_events");
  const auto r = check(dir, "p", "[[records]]\nh1 = \"" + rinaldi.string() + "\"\nh2 = \"" + pel.string() + "\"\n" + kFrame);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("Rinaldi Receiving Sta"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("San Fernando"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("warning"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace pcrf::study_test
