// Selection per stripe from the command line, end to end: `pcrf record spectra` makes a
// library, `pcrf study` selects each stripe's records to its target and runs them, the cube
// names them and their factors (read back here and by plain xarray), and `pcrf cube
// fragility` and `pcrf cube risk` run on it unchanged. Bad input: exit 2, file, line and key,
// nothing written. A `pcrf record select` fragment loads into a study as is. On the real
// records of ../shared/records too (skipped without them).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/number_text.hpp"
#include "pcrf/post/cube_fragility.hpp"
#include "pcrf/record/record_library.hpp"
#include "pcrf/record/synthetic.hpp"
#include "pcrf/units.hpp"
#include "study/study_test_support.hpp"

namespace pcrf {
namespace {

namespace fs = std::filesystem;
using study_test::pcrf;
using study_test::quoted;

/// An AT2 file (in g) of a motion.
void write_at2(const fs::path& file, const GroundMotion& motion) {
  std::ofstream out(file);
  out << "PEER NGA STRONG MOTION DATABASE RECORD\nTest, 1/1/2000, Station, 000\nACCELERATION TIME SERIES IN UNITS OF G\n"
      << "NPTS=  " << motion.size() << ", DT=   " << motion.dt_s() << " SEC\n";
  out.precision(17);
  for (std::size_t i = 0; i < motion.size(); ++i) out << motion.samples_m_s2()[i] / kGravity_m_s2 << '\n';
}

SpectraTable read_table(const fs::path& file) {
  std::ifstream in(file);
  return read_spectra_csv(in, file.string());
}

/// Targets for `intensities` at the table's periods: conditioned at `conditioning_s` on each
/// intensity (σ = 0; `conditioning_s` on the table's grid), elsewhere the entries' (of
/// `kind`) mean ln Sa(T) − ln Sa(T*) above it with σ 0.3: t0.csv, t1.csv, … in `dir`.
void write_targets(const fs::path& dir, const SpectraTable& table, const std::string& kind, double conditioning_s,
                   const std::vector<double>& intensities) {
  const auto& periods = table.periods_s;
  std::size_t star = 0;
  while (std::abs(periods[star] - conditioning_s) > 1e-9) ++star;
  std::vector<double> shape(periods.size(), 0.0);
  double n = 0.0;
  for (const auto& e : table.entries) {
    if (e.kind != kind) continue;
    n += 1.0;
    for (std::size_t j = 0; j < periods.size(); ++j) shape[j] += std::log(e.sa_g[j] / e.sa_g[star]);
  }
  for (std::size_t k = 0; k < intensities.size(); ++k) {
    std::ostringstream text;
    text.precision(17);
    text << "period_s,mean_ln_sa,sigma_ln_sa\n";
    for (std::size_t j = 0; j < periods.size(); ++j)
      text << periods[j] << ',' << std::log(intensities[k]) + shape[j] / n << ',' << (j == star ? 0.0 : 0.3) << '\n';
    test::write_file(dir, "t" + std::to_string(k) + ".csv", text.str());
  }
}

test::CommandResult in_folder(const fs::path& dir, const std::string& command) {
  return test::run_command("cd " + quoted(dir) + " && " + command);
}

/// The stripes' cube checked: slots × stripes, each stripe's records named, each factor
/// bringing its record to the stripe's intensity by the study's own measure (`measure`), and
/// the fragility fitting one stripe per return period with one trial per slot.
void expect_stripe_cube(const fs::path& file, std::size_t slots, std::size_t stripes, const std::string& measure,
                        const SpectraTable& library) {
  const cube::CubeReader cube(file);
  const auto& layout = cube.layout();
  ASSERT_EQ(layout.dimensions.at(0).name, "record");
  ASSERT_EQ(layout.dimensions.at(0).size, slots);
  ASSERT_EQ(layout.dimensions.at(1).name, "intensity");
  ASSERT_EQ(layout.dimensions.at(1).size, stripes);
  const auto& intensity = layout.find_coordinate("intensity")->numbers;
  const auto factor = cube.read_side("scale_factor");
  const auto unscaled = cube.read_side("selected_record_" + measure);
  ASSERT_EQ(factor.size(), slots * stripes);
  ASSERT_EQ(unscaled.size(), slots * stripes);
  for (std::size_t k = 0; k < stripes; ++k) {
    const auto* names = layout.find_coordinate("selected_record_" + std::to_string(k));
    ASSERT_NE(names, nullptr) << k;
    ASSERT_TRUE(names->is_text);
    ASSERT_EQ(names->strings.size(), slots);
    for (std::size_t slot = 0; slot < slots; ++slot) {
      const std::string& name = names->strings[slot];
      EXPECT_TRUE(std::any_of(library.entries.begin(), library.entries.end(), [&](const LibraryEntry& e) { return e.name == name; }))
          << name;
      // The engine's measure of the record (the cube's), scaled, is the stripe's intensity.
      EXPECT_NEAR(factor[slot * stripes + k] * unscaled[slot * stripes + k] / intensity[k], 1.0, 1e-6) << name;
    }
  }
  EXPECT_EQ(layout.find_coordinate("selection_target")->strings.size(), stripes);
  const auto status = cube.read_status();
  EXPECT_TRUE(std::none_of(status.begin(), status.end(), [](std::int8_t s) { return s == cube::kStatusNotRun; }));
  const auto frames = post::cube_fragility(cube, {});
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_EQ(frames[0].records, slots);
  ASSERT_EQ(frames[0].stripes.size(), stripes);
  for (std::size_t k = 0; k < stripes; ++k) {
    EXPECT_EQ(frames[0].stripes[k].intensity, intensity[k]);
    EXPECT_LE(frames[0].stripes[k].trials, double(slots));
  }
  EXPECT_EQ(frames[0].cases + frames[0].failed + frames[0].unresolved, slots * stripes);
}

TEST(StripeSelectionCli, ALibraryStudyCubeFragilityAndRisk) {
  const fs::path dir = test::scratch_dir("stripe_selection_cli");
  fs::create_directories(dir / "lib");
  fs::create_directories(dir / "study");
  for (int i = 0; i < 16; ++i) {
    StochasticSpec spec;
    spec.seed = static_cast<std::uint64_t>(i + 1);
    spec.pga_g = 0.2 + 0.05 * i;
    spec.duration_s = 5.0;
    spec.ground_freq_hz = 1.0 + 0.5 * (i % 6);
    write_at2(dir / "lib" / ("RSN" + std::to_string(i + 1) + "_TEST_X000.AT2"), make_stochastic(spec));
  }
  // The table names its files relative to where it was made (here, its own folder).
  const auto spectra = in_folder(dir, pcrf() + " record spectra lib --period 0.2 --period 0.5 --period 1 --period 2 -o lib.csv");
  ASSERT_EQ(spectra.exit_code, 0) << spectra.err;
  const SpectraTable library = read_table(dir / "lib.csv");
  ASSERT_EQ(library.entries.front().file.rfind("lib/", 0), 0u) << library.entries.front().file;
  test::write_file(dir, "hazard.csv", "# period_s = 1\nsa_g,annual_rate_per_yr\n0.05,0.1\n0.2,0.01\n0.6,1e-3\n2,1e-4\n5,1e-5\n");
  write_targets(dir, library, "component", 1.0, {0.2, 0.6, 2.0});
  // The study in another folder: its keys relative to it, the table's files to the table.
  const std::string intensity = "[intensity]\nmeasure = \"sa_g\"\nperiod_s = 1\nhazard = \"../hazard.csv\"\n"
                                "return_periods_yr = [100, 1000, 10000]\n";
  const std::string selection = "[selection]\nlibrary = \"../lib.csv\"\ntargets = [\"../t0.csv\", \"../t1.csv\", \"../t2.csv\"]\n"
                                "count = 4\nscale_min = 0.05\nscale_max = 50\n";
  // A history names a slot: it is the stripe's record there, with its factor.
  test::write_file(dir / "study", "s.toml", "[study]\nname = \"stripes\"\n" + intensity + selection +
                                                "[[outputs.histories]]\nlabel = \"top\"\nrecord = \"slot_2\"\nintensity = 2\n");
  const auto run = in_folder(dir / "study", pcrf() + " study s.toml -o s.h5 --progress-interval 0");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  expect_stripe_cube(dir / "study" / "s.h5", 4, 3, "sa_g", library);
  // Every rank reads the study and selects alike: three ranks write the same cube.
  if (study_test::have_mpirun()) {
    const auto ranks = in_folder(dir / "study", study_test::mpirun(3) + pcrf() + " study s.toml -o m.h5 --progress-interval 0");
    ASSERT_EQ(ranks.exit_code, 0) << ranks.err;
    study_test::expect_same_cube(dir / "study" / "s.h5", dir / "study" / "m.h5");
  }

  // cube fragility and cube risk, unchanged, on it.
  const auto fragility = in_folder(dir / "study", pcrf() + " cube fragility s.h5");
  EXPECT_EQ(fragility.exit_code, 0) << fragility.err;
  EXPECT_NE(fragility.out.find("all    4"), std::string::npos) << fragility.out;
  const auto risk = in_folder(dir / "study", pcrf() + " cube risk s.h5 --hazard ../hazard.csv --csv -");
  EXPECT_EQ(risk.exit_code, 0) << risk.err;
  EXPECT_NE(risk.out.find("lambda_collapse_per_yr"), std::string::npos) << risk.out;

  // Plain xarray reads the selection (skipped where python3 lacks xarray).
  if (test::run_command("/usr/bin/python3 -c 'import xarray, netCDF4'").exit_code == 0) {
    const std::string script =
        "import sys, xarray as xr, numpy as np\n"
        "ds = xr.open_dataset(sys.argv[1])\n"
        "names = np.stack([ds[f'selected_record_{k}'].values for k in range(ds.sizes['intensity'])], axis=1)\n"
        "assert names.shape == (4, 3), names.shape\n"
        "assert all(n.startswith('RSN') for n in names.ravel()), names\n"
        "ratio = (ds.scale_factor * ds.selected_record_sa_g / ds.intensity).values\n"
        "assert np.allclose(ratio, 1.0, rtol=1e-6), ratio\n"
        "assert ds.scale_factor.dims == ('record', 'intensity') and ds.scale_factor.attrs['units'] == '1'\n"
        "assert ds.selected_record_sa_g.attrs['units'] == 'g'\n"
        "assert list(ds.return_period_yr.values) == [100, 1000, 10000]\n"
        "h = xr.open_dataset(sys.argv[1], group='histories/top')\n"
        "assert h.attrs['record'] == ds.selected_record_2.values[1], h.attrs\n"
        "assert h.attrs['scale_factor'] == ds.scale_factor.values[1, 2], h.attrs\n"
        "print('ok')\n";
    test::write_file(dir, "read.py", script);
    const auto read = test::run_command("/usr/bin/python3 " + quoted(dir / "read.py") + " " + quoted(dir / "study" / "s.h5"));
    EXPECT_EQ(read.exit_code, 0) << read.out << read.err;
  }

  // Bad input: exit 2 naming the study file, line and key; nothing written.
  test::write_file(dir / "study", "bad.toml", intensity + "[selection]\nlibrary = \"../lib.csv\"\n"
                                              "targets = [\"../t0.csv\", \"../t1.csv\"]\ncount = 4\n");
  const auto bad = in_folder(dir / "study", pcrf() + " study bad.toml -o bad.h5");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("bad.toml:8: [selection] targets: 2 target(s) for 3 return periods"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir / "study" / "bad.h5"));
  // The output may not be one of the selection's inputs, even with --overwrite.
  const std::string target_before = test::read_file(dir / "t1.csv");
  const auto onto = in_folder(dir / "study", pcrf() + " study s.toml -o ../t1.csv --overwrite");
  EXPECT_EQ(onto.exit_code, 2);
  EXPECT_NE(onto.err.find("the target ../t1.csv of [selection]"), std::string::npos) << onto.err;
  EXPECT_EQ(test::read_file(dir / "t1.csv"), target_before);
  const std::string library_before = test::read_file(dir / "lib.csv");
  const auto onto_library = in_folder(dir / "study", pcrf() + " study s.toml -o ../lib.csv --overwrite");
  EXPECT_EQ(onto_library.exit_code, 2);
  EXPECT_NE(onto_library.err.find("the record library ../lib.csv of [selection]"), std::string::npos) << onto_library.err;
  EXPECT_EQ(test::read_file(dir / "lib.csv"), library_before);

  // A `pcrf record select` fragment is a study as is: its factors run times the scale axis.
  const auto select = in_folder(dir, pcrf() + " record select --target t1.csv --library lib.csv -n 3 --kind component -o frag.toml");
  ASSERT_EQ(select.exit_code, 0) << select.err;
  const auto fragment = in_folder(dir, pcrf() + " study frag.toml -o frag.h5 --progress-interval 0");
  ASSERT_EQ(fragment.exit_code, 0) << fragment.err;
  const cube::CubeReader frag(dir / "frag.h5");
  const auto* scales = frag.layout().find_coordinate("record_scale");
  ASSERT_NE(scales, nullptr);
  const std::string text = test::read_file(dir / "frag.toml");
  for (double scale : scales->numbers)
    EXPECT_NE(text.find("scale = " + number_text(scale) + "\n"), std::string::npos) << scale << "\n" << text;
}

TEST(StripeSelectionCli, RealRecordPairsByTheirRotD50) {
  const auto records = test::records_dir();
  if (!records) GTEST_SKIP() << "no ../shared/records";
  const fs::path folder = *records / "nearfault_vacalderon";
  if (!fs::is_directory(folder)) GTEST_SKIP() << folder << " is missing";
  const fs::path dir = test::scratch_dir("stripe_selection_real");
  const auto spectra = in_folder(dir, pcrf() + " record spectra " + quoted(folder) +
                                          " --period 0.2 --period 0.5 --period 1 --period 2 --period 3 -o lib.csv");
  ASSERT_EQ(spectra.exit_code, 0) << spectra.err;
  const SpectraTable library = read_table(dir / "lib.csv");
  test::write_file(dir, "hazard.csv", "# period_s = 1\nsa_rotd50_g,annual_rate_per_yr\n0.05,0.1\n0.3,0.005\n0.8,5e-4\n3,1e-5\n");
  write_targets(dir, library, "rotd50", 1.0, {0.3, 0.8});
  test::write_file(dir, "s.toml",
                   "[intensity]\nmeasure = \"sa_rotd50_g\"\nperiod_s = 1\nhazard = \"hazard.csv\"\nreturn_periods_yr = [200, 2000]\n"
                   "[selection]\nlibrary = \"lib.csv\"\ntargets = [\"t0.csv\", \"t1.csv\"]\ncount = 3\nscale_min = 0.1\nscale_max = 10\n"
                   "[physics]\nmax_tail_s = 10\n");
  const auto run = in_folder(dir, pcrf() + " study s.toml -o s.h5 --progress-interval 0");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // The engine's RotD50 of each pair (the study's check and the cube's) is the library's.
  expect_stripe_cube(dir / "s.h5", 3, 2, "sa_rotd50_g", library);
  EXPECT_EQ(in_folder(dir, pcrf() + " cube fragility s.h5").exit_code, 0);
  EXPECT_EQ(in_folder(dir, pcrf() + " cube risk s.h5 --hazard hazard.csv").exit_code, 0);
}

}  // namespace
}  // namespace pcrf
