// `pcrf record spectra`, `pcrf record select` and `pcrf record pulse` from the command line:
// a library of two AT2 files scanned into a table, a selection from it as a [[records]]
// fragment, bad targets refused with exit 2 naming file, line and key (nothing written), and a
// pulse record classified.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "support/test_support.hpp"

namespace {

namespace fs = std::filesystem;
using pcrf::test::run_command;

/// An AT2 file of `n` samples every 0.01 s: a decaying sine of period `period_s`.
std::string at2(const std::string& component, double period_s, double amplitude_g, int n = 2000) {
  std::ostringstream out;
  out << "PEER NGA STRONG MOTION DATABASE RECORD\nTest, 1/1/2000, Station, " << component
      << "\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS=  " << n << ", DT=   .0100 SEC\n";
  for (int i = 0; i < n; ++i) {
    const double t = 0.01 * i;
    out << amplitude_g * std::exp(-0.2 * t) * std::sin(2 * M_PI * t / period_s) << ((i % 5 == 4) ? "\n" : " ");
  }
  out << "\n";
  return out.str();
}

std::string pcrf_command(const std::string& args) { return pcrf::test::pcrf_executable().string() + " " + args; }

TEST(RecordLibraryCommands, SpectraThenSelectWritesATableAndAFragment) {
  const fs::path dir = pcrf::test::scratch_dir("record_library_cli");
  const fs::path lib = dir / "lib";
  fs::create_directories(lib);
  for (int i = 0; i < 4; ++i) {
    pcrf::test::write_file(lib, "RSN" + std::to_string(i) + "_TEST_A000.AT2", at2("000", 0.3 + 0.2 * i, 0.3));
    pcrf::test::write_file(lib, "RSN" + std::to_string(i) + "_TEST_A090.AT2", at2("090", 0.5 + 0.1 * i, 0.2));
  }
  const fs::path table = dir / "lib.csv";
  const auto spectra = run_command(pcrf_command("record spectra " + lib.string() + " --period 0.1 --period 0.5 --period 1 -o " + table.string()));
  ASSERT_EQ(spectra.exit_code, 0) << spectra.err;
  EXPECT_NE(spectra.err.find("8 components, 4 pairs (RotD50), 3 periods"), std::string::npos) << spectra.err;
  // Not replaced without --overwrite.
  EXPECT_EQ(run_command(pcrf_command("record spectra " + lib.string() + " -o " + table.string())).exit_code, 2);

  pcrf::test::write_file(dir, "target.csv", "period_s,mean_ln_sa,sigma_ln_sa\n0.1,-1.5,0.3\n0.5,-1.0,0.3\n1,-1.6,0.3\n");
  const auto select = run_command(pcrf_command("record select --target " + (dir / "target.csv").string() + " --library " +
                                               table.string() + " -n 3"));
  ASSERT_EQ(select.exit_code, 0) << select.err;
  std::size_t entries = 0;
  for (std::size_t at = select.out.find("[[records]]"); at != std::string::npos; at = select.out.find("[[records]]", at + 1)) ++entries;
  EXPECT_EQ(entries, 3u);
  EXPECT_NE(select.out.find("h2 = \""), std::string::npos);
  EXPECT_NE(select.out.find("scale = "), std::string::npos);

  // Bad targets: exit 2, the file, line and key named, nothing written.
  const fs::path out = dir / "fragment.toml";
  auto refused = [&](const std::string& name, const std::string& text, const std::string& expected) {
    pcrf::test::write_file(dir, name, text);
    const auto r = run_command(pcrf_command("record select --target " + (dir / name).string() + " --library " +
                                            table.string() + " -n 3 -o " + out.string()));
    EXPECT_EQ(r.exit_code, 2) << name;
    EXPECT_NE(r.err.find((dir / name).string() + expected), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << name;
  };
  const std::string head = "period_s,mean_ln_sa,sigma_ln_sa\n";
  refused("decreasing.csv", head + "0.5,-1,0.3\n0.1,-1,0.3\n", ":3: period_s: periods must increase");
  refused("negative.csv", head + "0.5,-1,-0.3\n", ":2: sigma_ln_sa: must not be negative");
  refused("nan.csv", head + "0.5,nan,0.3\n", ":2: mean_ln_sa: 'nan' is not a finite number");
  refused("outside.csv", head + "0.5,-1,0.3\n3,-2,0.3\n", ":3: period_s: 3 s is outside the library's periods");
}

TEST(RecordLibraryCommands, PulseClassifiesARecordAsJson) {
  const fs::path dir = pcrf::test::scratch_dir("record_pulse_cli");
  // One long-period cycle of 2 s: a velocity pulse; PGV = 0.8 g · 2 s / π ≈ 500 cm/s.
  std::ostringstream text;
  text << "PEER\nTest, 1/1/2000, Station, 000\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS=  3000, DT=   .0100 SEC\n";
  for (int i = 0; i < 3000; ++i) {
    const double t = 0.01 * i - 5.0;
    text << (t >= 0 && t <= 2.0 ? 0.8 * std::sin(M_PI * t) : 0.0) << "\n";
  }
  pcrf::test::write_file(dir, "pulse_000.AT2", text.str());
  const auto r = run_command(pcrf_command("record pulse " + (dir / "pulse_000.AT2").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"method\": \"baker-2007\", \"pulse_like\": true"), std::string::npos) << r.out;
  EXPECT_EQ(run_command(pcrf_command("record pulse " + (dir / "missing.AT2").string())).exit_code, 2);
}

}  // namespace
