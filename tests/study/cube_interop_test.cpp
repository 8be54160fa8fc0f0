// A study's cube read by others: xarray (netCDF4 and, if present, h5netcdf engines) and h5py
// with no custom code; and by `pcrf cube info|export|stats`.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <regex>
#include <sstream>

#include "pcrf/cube/cube_query.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/solver/history.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study_test {
namespace {

const char* kPython = "/usr/bin/python3";

/// The name of the running test: ctest runs tests in parallel processes, so each makes its
/// own cube in its own folder.
std::string test_name() { return ::testing::UnitTest::GetInstance()->current_test_info()->name(); }

/// Runs the grid study (with one history) and returns the cube's folder.
std::filesystem::path grid_cube() {
  static const std::filesystem::path dir = [] {
    const auto d = test::scratch_dir("cube_interop_grid_" + test_name());
    const std::string extra = "[[outputs.histories]]\nlabel = \"pulse\"\nrecord = \"" + std::string(kPulse) +
                              "\"\nscale = 0.9\nkappa = 2.4\ntan_alpha = 0.22\n";
    const auto study = test::write_file(d, "grid.toml", small_grid_study(extra));
    const auto r = test::run_command("cd " + quoted(d) + " && " + pcrf() + " study grid.toml -o grid.h5 --progress-interval 0");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return d;
  }();
  return dir;
}

std::filesystem::path oat_cube() {
  static const std::filesystem::path dir = [] {
    const auto d = test::scratch_dir("cube_interop_oat_" + test_name());
    const std::string text = std::string("[plan]\nkind = \"one-at-a-time\"\n[[records]]\nsynthetic = [\"") + kPulse +
                             "\", \"" + kPulse2 + "\", \"" + kNoise + "\"]\n[axes]\nkappa = [1.2, 2.4]\n"
                             "lambda = [1.8, 2.2]\n[outputs]\nmetrics = [\"theta_max_rad\", \"impacts\"]\n";
    test::write_file(d, "oat.toml", text);
    const auto r = test::run_command("cd " + quoted(d) + " && " + pcrf() + " study oat.toml -o oat.h5 --progress-interval 0");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return d;
  }();
  return dir;
}

bool python_has(const std::string& module) {
  if (!std::filesystem::exists(kPython)) return false;
  return test::run_command(std::string(kPython) + " -c 'import " + module + "'").exit_code == 0;
}

/// Runs a Python script; returns stdout (the test fails on a non-zero exit).
std::string python(const std::filesystem::path& dir, const std::string& script) {
  const auto file = test::write_file(dir, "check.py", script);
  const auto r = test::run_command("cd " + quoted(dir) + " && " + std::string(kPython) + " " + quoted(file));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return r.out;
}

/// Whitespace-separated numbers printed by Python's repr (shortest round-trip).
std::vector<double> numbers(const std::string& text) {
  std::istringstream in(text);
  std::vector<double> values;
  for (std::string word; in >> word;) values.push_back(word == "nan" ? std::nan("") : std::stod(word));
  return values;
}

TEST(CubeInterop, XarrayOpensTheGridCubeWithAxesAndMetrics) {
  if (!python_has("xarray") || !python_has("netCDF4")) GTEST_SKIP() << "python3-xarray or python3-netcdf4 missing";
  const auto dir = grid_cube();
  std::vector<std::string> engines = {"netcdf4"};
  if (python_has("h5netcdf")) engines.push_back("h5netcdf");
  cube::CubeReader cube(dir / "grid.h5");
  const auto theta = cube.read_metric("theta_max_rad");
  for (const auto& engine : engines) {
    const std::string out = python(dir, R"(
import xarray as xr
ds = xr.open_dataset("grid.h5", engine=")" + engine + R"(")
assert list(ds.theta_max_rad.dims) == ["record", "scale", "kappa", "lambda", "tan_alpha", "lambda_h",
                                       "pi_sigma_b", "pi_sigma_c", "pi_e_b", "pi_e_c"], ds.theta_max_rad.dims
assert list(ds.scale.values) == [0.9, 1.2] and list(ds.kappa.values) == [1.2, 2.4]
assert list(ds.tan_alpha.values) == [0.18, 0.22]
assert str(ds.record.values[2]).startswith("stochastic:seed=4"), ds.record.values
assert ds.theta_max_rad.attrs["units"] == "rad"
assert "at_rest" in ds.status.attrs["flag_meanings"]
assert ds.attrs["plan"] == "grid" and "[axes]" in ds.attrs["study_text"]
one = ds.theta_max_rad.sel(record=ds.record.values[1], scale=1.2, kappa=2.4, tan_alpha=0.18).squeeze()
print(repr(float(one)))
print(" ".join(repr(float(v)) for v in ds.theta_max_rad.values.ravel()))
h = xr.open_dataset("grid.h5", group="histories/pulse", engine=")" + engine + R"(")
assert h.theta1_rad.dims == ("t_s",) and h.attrs["kappa"] == 2.4
)");
    const auto values = numbers(out);
    ASSERT_EQ(values.size(), theta.size() + 1) << out;
    // record 1, scale 1.2, κ 2.4, tan α 0.18: coordinates (1, 1, 1, 0, 0, 0, 0, 0, 0, 0)
    EXPECT_EQ(values[0], theta[static_cast<std::size_t>(1 * 8 + 1 * 4 + 1 * 2 + 0)]) << engine;
    for (std::size_t i = 0; i < theta.size(); ++i) EXPECT_EQ(values[i + 1], theta[i]) << engine << " case " << i;
  }
}

TEST(CubeInterop, H5pyAndXarrayReadTheOneAtATimeCube) {
  if (!python_has("xarray") || !python_has("h5py")) GTEST_SKIP() << "python3-xarray or python3-h5py missing";
  const auto dir = oat_cube();
  const std::string out = python(dir, R"(
import h5py, xarray as xr
f = h5py.File("oat.h5", "r")
assert f["theta_max_rad"].shape == (3, 1, 5) and "impacts" in f and "t_uplift_s" not in f
ds = xr.open_dataset("oat.h5")
assert list(ds.theta_max_rad.dims) == ["record", "scale", "case"]
assert list(ds.varied_parameter.values) == ["none", "kappa", "kappa", "lambda", "lambda"], ds.varied_parameter.values
assert list(ds.kappa.values) == [1.8, 1.2, 2.4, 1.8, 1.8]
sweep = ds.theta_max_rad.where(ds.varied_parameter == "kappa", drop=True)
print(sweep.sizes["case"])
)");
  EXPECT_EQ(out, "2\n");
}

TEST(CubeInterop, InfoShowsAxesCompletionAndStatus) {
  const auto dir = grid_cube();
  const auto r = test::run_command(pcrf() + " cube info " + quoted(dir / "grid.h5"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* text : {"plan grid", "kappa (2): 1.2, 2.4", "completion: 24/24 cases (100.0 %)", "theta_max_rad [rad]",
                           "status:", "histories: pulse"})
    EXPECT_NE(r.out.find(text), std::string::npos) << text << "\n" << r.out;
}

TEST(CubeInterop, ExportWritesOneRowPerSelectedCase) {
  const auto dir = grid_cube();
  const auto r = test::run_command(pcrf() + " cube export " + quoted(dir / "grid.h5") +
                                   " -m theta_max_rad -m impacts --where kappa=1.2 --where scale=0.9");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream in(r.out);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "record,scale,kappa,lambda,tan_alpha,lambda_h,pi_sigma_b,pi_sigma_c,pi_e_b,pi_e_c,record_source,record_title,"
                    "status,theta_max_rad,impacts");
  int rows = 0;
  for (std::string line; std::getline(in, line); ++rows) EXPECT_NE(line.find(",0.9,1.2,2,"), std::string::npos) << line;
  EXPECT_EQ(rows, 3 * 2);  // records × tan α
  const auto bad = test::run_command(pcrf() + " cube export " + quoted(dir / "grid.h5") + " --where kappa=7");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("kappa=7: no such value (values: 1.2, 2.4)"), std::string::npos) << bad.err;
}

TEST(CubeInterop, ExportsAStoredHistoryAsTheRunCommandsCsv) {
  const auto dir = grid_cube();
  const auto r = test::run_command(pcrf() + " cube export " + quoted(dir / "grid.h5") + " --history pulse");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream in(r.out);
  std::string header;
  std::getline(in, header);
  std::string expected;
  for (const auto& c : history_columns()) expected += (expected.empty() ? "" : ",") + std::string(c.name);
  EXPECT_EQ(header, expected);
  double last_t = -1.0;
  int rows = 0;
  for (std::string line; std::getline(in, line); ++rows) {
    const double t = std::stod(line.substr(0, line.find(',')));
    EXPECT_GT(t, last_t);
    last_t = t;
  }
  EXPECT_GT(rows, 100);
  const auto missing = test::run_command(pcrf() + " cube export " + quoted(dir / "grid.h5") + " --history nope");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("nope"), std::string::npos) << missing.err;
}

TEST(CubeInterop, StatsGivesMedianAndPercentilesAcrossRecords) {
  const auto dir = grid_cube();
  const auto r = test::run_command(pcrf() + " cube stats " + quoted(dir / "grid.h5") +
                                   " --by kappa -m theta_max_rad --where scale=0.9 --where tan_alpha=0.18");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  cube::CubeReader cube(dir / "grid.h5");
  const auto theta = cube.read_metric("theta_max_rad");
  std::vector<double> across;  // κ = 1.2, scale 0.9, tan α 0.18: one value per record
  for (std::size_t record = 0; record < 3; ++record) across.push_back(theta[record * 8]);
  std::sort(across.begin(), across.end());
  std::istringstream in(r.out);
  std::string header, first;
  std::getline(in, header);
  std::getline(in, first);
  EXPECT_EQ(header, "kappa,cases,collapses,values,median,p16,p84,unresolved");
  EXPECT_EQ(first.rfind("1.2,3,0,3,", 0), 0u) << first;
  const auto fields = numbers(std::regex_replace(first, std::regex(","), " "));
  ASSERT_EQ(fields.size(), 8u);
  EXPECT_EQ(fields[7], 0.0);  // every frame came to rest or collapsed
  EXPECT_EQ(fields[4], across[1]);  // median of three
  EXPECT_DOUBLE_EQ(fields[5], across[0] + 0.32 * (across[1] - across[0]));  // h = (3 − 1) × 0.16
  const auto oat = test::run_command(pcrf() + " cube stats " + quoted(oat_cube() / "oat.h5") + " --by kappa -m impacts");
  ASSERT_EQ(oat.exit_code, 0) << oat.err;
  EXPECT_EQ(std::count(oat.out.begin(), oat.out.end(), '\n'), 3) << oat.out;  // header + the kappa sweep's 2 values
}

TEST(CubeInterop, StatsCountCollapsesApart) {
  // Strong pulses: at the larger scales the frame collapses, and a collapsed case's θ_max
  // (the angle where it stopped) must not enter the percentiles.
  const auto dir = test::scratch_dir("stats_collapses");
  const auto file = test::write_file(dir, "c.toml", std::string("[[records]]\nsynthetic = [\"") + kPulse + "\", \"" + kPulse2 +
                                                       "\"]\n[axes]\nscale = [1.0, 3.0, 6.0]\n");
  ASSERT_EQ(test::run_command(pcrf() + " study " + quoted(file) + " -o " + quoted(dir / "c.h5") + " --progress-interval 0").exit_code, 0);
  cube::CubeReader cube(dir / "c.h5");
  const auto status = cube.read_status();
  const auto theta = cube.read_metric("theta_max_rad");
  const auto r = test::run_command(pcrf() + " cube stats " + quoted(dir / "c.h5") + " --by scale -m theta_max_rad");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream in(r.out);
  std::string line;
  std::getline(in, line);
  int total_collapses = 0;
  for (std::size_t level = 0; std::getline(in, line); ++level) {
    const auto fields = numbers(std::regex_replace(line, std::regex(","), " "));
    std::vector<double> kept;
    int collapses = 0;
    for (std::size_t record = 0; record < 2; ++record) {
      const auto k = record * 3 + level;
      const bool collapsed = status[k] == 2 || status[k] == 3;
      collapses += collapsed;
      if (!collapsed) kept.push_back(theta[k]);
    }
    total_collapses += collapses;
    EXPECT_EQ(fields[2], collapses) << line;
    EXPECT_EQ(fields[3], static_cast<double>(kept.size())) << line;
  }
  EXPECT_GT(total_collapses, 0) << "no case collapsed: make the pulses stronger";
}

}  // namespace
}  // namespace pcrf::study_test

namespace pcrf::study_test {
namespace {

TEST(CubeInterop, InfoFindsAVariableThatNoLongerDecompresses) {
  if (!python_has("h5py")) GTEST_SKIP() << "python3-h5py missing";
  const auto dir = grid_cube();
  const auto copy = dir / "damaged.h5";
  std::filesystem::copy_file(dir / "grid.h5", copy, std::filesystem::copy_options::overwrite_existing);
  const auto whole = test::run_command(pcrf() + " cube info " + quoted(copy));
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_EQ(whole.out.find("DAMAGED"), std::string::npos);
  // Flip bytes inside the first compressed chunk of theta_max_rad, as a kill during a write
  // or a bad disk would leave it.
  python(dir, "import h5py\n"
              "f = h5py.File('damaged.h5', 'r')\n"
              "offset = f['theta_max_rad'].id.get_chunk_info(0).byte_offset\n"
              "f.close()\n"
              "data = bytearray(open('damaged.h5', 'rb').read())\n"
              "for i in range(offset + 8, offset + 120): data[i] ^= 0x5A\n"
              "open('damaged.h5', 'wb').write(data)\n");
  const auto damaged = test::run_command(pcrf() + " cube info " + quoted(copy));
  EXPECT_EQ(damaged.exit_code, 2);
  EXPECT_NE(damaged.out.find("DAMAGED: theta_max_rad"), std::string::npos) << damaged.out;
  EXPECT_NE(damaged.err.find("damaged: 1 variables cannot be read"), std::string::npos) << damaged.err;
}

}  // namespace
}  // namespace pcrf::study_test
