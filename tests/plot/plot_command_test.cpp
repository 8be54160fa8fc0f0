// `pcrf plot`: every kind draws a valid file with the expected number of panels (counted
// in the SVG, one <g id="axes_N"> per panel), from small studies of synthetic records; bad
// input fails with one line, exit code 2, and writes nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "study/study_test_support.hpp"

namespace pcrf {
namespace {

using study_test::kNoise;
using study_test::kPulse;
using study_test::kPulse2;
using study_test::pcrf;
using study_test::quoted;

bool have_matplotlib() {
  return test::run_command(std::string("'") + PCRF_PYTHON + "' -c 'import matplotlib, numpy'").exit_code == 0;
}

#define PCRF_REQUIRE_MATPLOTLIB() \
  if (!have_matplotlib()) GTEST_SKIP() << PCRF_PYTHON << " has no matplotlib"

std::string records_line() {
  return std::string("[[records]]\nsynthetic = [\"") + kPulse + "\", \"" + kPulse2 + "\", \"" + kNoise + "\"]\n";
}

/// Runs a study file's text in `dir`, returns the cube's path.
std::filesystem::path study(const std::filesystem::path& dir, const std::string& name, const std::string& text) {
  test::write_file(dir, name + ".toml", text);
  const auto r = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study " + name + ".toml -o " + name +
                                   ".h5 --progress-interval 0");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return dir / (name + ".h5");
}

/// Panels of an SVG written by matplotlib.
int panels(const std::filesystem::path& svg) {
  std::ifstream in(svg);
  std::stringstream text;
  text << in.rdbuf();
  const std::string s = text.str();
  EXPECT_NE(s.find("<svg"), std::string::npos) << svg;
  int count = 0;
  const std::regex axes("<g id=\"axes_[0-9]+\">");
  for (auto it = std::sregex_iterator(s.begin(), s.end(), axes); it != std::sregex_iterator(); ++it) ++count;
  return count;
}

/// `pcrf plot ARGS -o OUT.svg`; the panels drawn (−1 when it failed).
int plot(const std::filesystem::path& out, const std::string& args) {
  const auto r = test::run_command(pcrf() + " plot " + args + " -o " + quoted(out));
  EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
  return r.exit_code == 0 ? panels(out) : -1;
}

TEST(PlotCommand, HistoryOfARunAndOfACubeGroupHasFourPanels) {
  PCRF_REQUIRE_MATPLOTLIB();
  const auto dir = test::scratch_dir("plot_history");
  const auto csv = dir / "h.csv";
  ASSERT_EQ(test::run_command(pcrf() + " run --synthetic '" + kNoise + "' --history " + quoted(csv) +
                              " --history-dt-s 0.002").exit_code, 0);
  EXPECT_EQ(plot(dir / "run.svg", "history " + quoted(csv)), 4);
  const auto cube = study(dir, "grid", records_line() + "[axes]\nkappa = [1.2, 2.4]\n[[outputs.histories]]\n"
                                       "label = \"noise\"\nrecord = \"" + kNoise + "\"\nkappa = 2.4\ndt_s = 0.002\n");
  EXPECT_EQ(plot(dir / "cube.svg", "history " + quoted(cube)), 4);
  EXPECT_EQ(plot(dir / "group.svg", "history " + quoted(cube) + " --group noise"), 4);
}

TEST(PlotCommand, SweepHasOnePanelPerVariedParameterAndStatusOneMap) {
  PCRF_REQUIRE_MATPLOTLIB();
  const auto dir = test::scratch_dir("plot_sweep");
  const auto cube = study(dir, "oat", records_line() + "[plan]\nkind = \"one-at-a-time\"\ninclude_base = true\n"
                                      "[axes]\nscale = [1.0, 1.3]\nkappa = [1.2, 2.4]\nlambda = [1.8, 2.2]\n"
                                      "tan_alpha = [0.16, 0.18, 0.22]\n");
  EXPECT_EQ(plot(dir / "sweep.svg", "sweep " + quoted(cube) + " -w scale=1.3"), 3);
  EXPECT_EQ(plot(dir / "impacts.svg", "sweep " + quoted(cube) + " -w scale=1.3 -m impacts"), 3);
  EXPECT_EQ(plot(dir / "status.svg", "status " + quoted(cube) + " -w scale=1.3"), 1);
  EXPECT_EQ(plot(dir / "status_xy.svg", "status " + quoted(cube) + " --x case --y scale -w record=" + kPulse), 1);
}

TEST(PlotCommand, IdaHasOnePanelPerFrameAndFragilityOne) {
  PCRF_REQUIRE_MATPLOTLIB();
  const auto dir = test::scratch_dir("plot_ida");
  std::string records = "[[records]]\nsynthetic = [";
  for (int seed = 1; seed <= 4; ++seed)
    records += std::string(seed > 1 ? ", " : "") + "\"stochastic:seed=" + std::to_string(seed) + ",pga_g=1,duration_s=6\"";
  const auto cube = study(dir, "ida", records + "]\n[axes]\nkappa = [1.4, 2.2]\n[intensity]\nmeasure = \"pga_g\"\n"
                                      "[ida]\nstart = 0.5\nmax_intensity = 8\nmax_runs = 10\n");
  EXPECT_EQ(plot(dir / "ida.svg", "ida " + quoted(cube)), 2);
  EXPECT_EQ(plot(dir / "ida1.svg", "ida " + quoted(cube) + " -w kappa=1.4"), 1);
  EXPECT_EQ(plot(dir / "fragility.svg", "fragility " + quoted(cube)), 1);
  // risk: the hazard curve, the fragilities and the deaggregation, three panels on one figure.
  test::write_file(dir, "hazard.csv", "pga_g,annual_rate_per_yr\n0.05,0.178885\n0.3,0.00202837\n3,6.415e-06\n");
  EXPECT_EQ(plot(dir / "risk.svg", "risk " + quoted(cube) + " --hazard " + quoted(dir / "hazard.csv")), 3);
  const auto no_hazard = test::run_command(pcrf() + " plot risk " + quoted(cube) + " -o " + quoted(dir / "none.svg"));
  EXPECT_EQ(no_hazard.exit_code, 2);
  EXPECT_NE(no_hazard.err.find("risk needs --hazard FILE"), std::string::npos) << no_hazard.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "none.svg"));
  const auto stripes = study(dir, "stripes", records + "]\n[intensity]\nmeasure = \"pga_g\"\n"
                                             "[axes]\nintensity = [1, 1.5, 2, 2.5, 3, 4]\n");
  EXPECT_EQ(plot(dir / "stripes.svg", "fragility " + quoted(stripes)), 1);
}

TEST(PlotCommand, SpectrumHasOnePanelPerFrame) {
  PCRF_REQUIRE_MATPLOTLIB();
  const auto dir = test::scratch_dir("plot_spectrum");
  const auto cube = study(dir, "spectrum",
                          "[[records]]\npulse = [\"pulse-sine\", \"ricker\"]\n[frame]\nmodel = \"block\"\nsize_m = 1\n"
                          "[axes]\nslenderness_rad = [0.15, 0.25]\n"
                          "pulse_period_s = {from = 0.3, to = 2, count = 4, spacing = \"log\"}\n"
                          "[intensity]\nmeasure = \"pga_g\"\n[ida]\nstart = 0.2\nmax_intensity = 20\nmax_runs = 14\n"
                          "resolution = 0.05\n[physics]\ntail_s = 5\n");
  EXPECT_EQ(plot(dir / "spectrum.svg", "spectrum " + quoted(cube)), 2);
  EXPECT_EQ(plot(dir / "spectrum1.svg", "spectrum " + quoted(cube) + " -w slenderness_rad=0.15"), 1);
  const auto r = test::run_command(pcrf() + " plot spectrum " + quoted(study(dir, "noise", records_line() +
                                   "[intensity]\nmeasure = \"pga_g\"\n[ida]\nstart = 0.5\nmax_intensity = 4\nmax_runs = 4\n")) +
                                   " -o " + quoted(dir / "no.svg"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("not a rocking-spectrum cube (no omega_p_over_p)"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "no.svg"));
}

TEST(PlotCommand, ReducedKindsDrawOnePanelPerFrameWithoutTheReducedAxis) {
  PCRF_REQUIRE_MATPLOTLIB();
  const auto dir = test::scratch_dir("plot_reduce");
  const std::string records =
      study_test::station_pair(dir, "a") +
      "[[records]]\nh1 = \"h2.txt\"\nh2 = \"h1.txt\"\nunits = \"m/s2\"\naz1_deg = 30\naz2_deg = 120\nname = \"b\"\n";
  const auto ida = study(dir, "ida", records + "[intensity]\nmeasure = \"pga_rotd50_g\"\n"
                                              "[ida]\nstart = 1.0\nstep = 1.0\nmax_intensity = 16\nmax_runs = 8\n"
                                              "[axes]\nkappa = [1.4, 2.2]\nincidence_deg = [0, 90]\n");
  EXPECT_EQ(plot(dir / "ida.svg", "ida " + quoted(ida)), 4);  // a frame per κ and incidence
  EXPECT_EQ(plot(dir / "ida_min.svg", "ida " + quoted(ida) + " --reduce-over incidence_deg"), 2);  // per κ
  EXPECT_EQ(plot(dir / "ida_med.svg", "ida " + quoted(ida) + " --reduce-over incidence_deg --reduce median -w kappa=1.4"), 1);
  EXPECT_EQ(plot(dir / "frag.svg", "fragility " + quoted(ida) + " --reduce-over incidence_deg"), 1);
  EXPECT_EQ(plot(dir / "frag3.svg", "fragility " + quoted(ida) + " -w kappa=2.2 --reduce-over incidence_deg "
                                    "--reduce min --reduce median --compare-where incidence_deg=0"), 1);
  const auto grid = study(dir, "grid", records + "[axes]\nscale = [1.4]\nkappa = [1.2, 2.4]\n"
                                                 "incidence_deg = [0, 60, 120]\n");
  EXPECT_EQ(plot(dir / "sweep.svg", "sweep " + quoted(grid) + " --reduce-over incidence_deg --reduce median"), 1);
  // The engine refuses a reduction it does not know; kinds that draw cases one by one take none.
  for (const std::string& args : {"fragility " + quoted(ida) + " --reduce-over incidence_deg --reduce mean",
                                 "sweep " + quoted(grid) + " --reduce-over incidence_deg --reduce mean",
                                 "status " + quoted(grid) + " --reduce-over incidence_deg",
                                 "ida " + quoted(ida) + " --reduce-over incidence_deg --reduce min --reduce max"}) {
    const auto r = test::run_command(pcrf() + " plot " + args + " -o " + quoted(dir / "bad.svg"));
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "bad.svg")) << args;
  }
  const auto r = test::run_command(pcrf() + " plot fragility " + quoted(ida) + " --reduce-over incidence_deg --reduce mean -o " +
                                   quoted(dir / "bad.svg"));
  EXPECT_NE(r.err.find("reduce with max, min or median, not 'mean'"), std::string::npos) << r.err;
}

TEST(PlotCommand, SensitivityHasOnePanelOfBars) {
  PCRF_REQUIRE_MATPLOTLIB();
  const auto dir = test::scratch_dir("plot_sensitivity");
  const auto cube = study(dir, "sal", records_line() + "[plan]\nkind = \"saltelli\"\nsamples = 16\n[axes]\nscale = 1.3\n"
                                      "kappa = {from = 1.2, to = 2.4}\ntan_alpha = {from = 0.15, to = 0.25}\n"
                                      "lambda_h = {from = 0.15, to = 0.25}\n");
  EXPECT_EQ(plot(dir / "sens.svg", "sensitivity " + quoted(cube) + " -m impacts"), 1);
  // PNG and PDF: the format's signature at the start of the file.
  for (const auto& [file, signature] : {std::pair{"sens.png", "\x89PNG"}, std::pair{"sens.pdf", "%PDF"}}) {
    const auto r = test::run_command(pcrf() + " plot sensitivity " + quoted(cube) + " -o " + quoted(dir / file));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::ifstream in(dir / file, std::ios::binary);
    std::string head(4, '\0');
    in.read(head.data(), 4);
    EXPECT_EQ(head, signature) << file;
  }
}

TEST(PlotCommand, Table3DrawsTheCommittedComparisonInFourPanels) {
  PCRF_REQUIRE_MATPLOTLIB();
  const auto dir = test::scratch_dir("plot_table3");
  EXPECT_EQ(plot(dir / "t3.svg", "table3 " + quoted(test::source_dir() / "docs" / "paper_comparison.csv")), 4);
}

TEST(PlotCommand, APartialCubeIsNamed) {
  PCRF_REQUIRE_MATPLOTLIB();
  const auto dir = test::scratch_dir("plot_partial");
  test::write_file(dir, "p.toml", records_line() + "[axes]\nscale = [0.9, 1.2]\nkappa = [1.2, 2.4]\n");
  ASSERT_EQ(test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study p.toml -o p.h5 --shard 1/2 --progress-interval 0")
                .exit_code, 0);
  const auto r = test::run_command(pcrf() + " plot sweep " + quoted(dir / "p.h5") + " -o " + quoted(dir / "p.svg"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("pcrf plot: " + (dir / "p.h5").string() + ": 6 of 12 cases not run (a partial cube)"), std::string::npos)
      << r.err;
}

struct BadPlot {
  std::string args;
  std::string message;
};

TEST(PlotCommand, BadInputFailsWithOneLineAndWritesNothing) {
  PCRF_REQUIRE_MATPLOTLIB();
  const auto dir = test::scratch_dir("plot_bad");
  const auto grid = study(dir, "grid", records_line() + "[axes]\nscale = [0.9, 1.2]\nkappa = [1.2, 2.4]\n");
  const auto existing = test::write_file(dir, "existing.svg", "keep me");
  std::filesystem::create_symlink(grid, dir / "grid_link.svg");  // the input under a figure's name
  const std::vector<BadPlot> cases = {
      {"history nowhere.csv -o x.svg", "nowhere.csv: no such file"},
      {"bogus " + quoted(grid) + " -o x.svg", "argument KIND: invalid choice: 'bogus'"},
      {"sweep " + quoted(grid) + " -o x.gif", "x.gif: the output must end in .png, .pdf or .svg"},
      {"sweep " + quoted(grid) + " -o " + quoted(existing), "existing.svg: already exists; use --overwrite to replace it"},
      {"sweep " + quoted(grid) + " -o grid_link.svg --overwrite", "grid_link.svg: resolves to the input"},
      {"ida " + quoted(grid) + " -o x.svg", "not an IDA cube"},
      {"history " + quoted(grid) + " -o x.svg", "the cube holds no history"},
      {"sensitivity " + quoted(grid) + " -o x.svg", "saltelli"},
      {"status " + quoted(grid) + " -o x.svg", "kappa: several values left; select one of each, e.g. -w kappa=1.2"},
      {"sweep " + quoted(grid) + " -m no_such_metric -o x.svg", "needs the metric no_such_metric"},
      {"sweep " + quoted(grid) + " -w kappa=7 -o x.svg", "kappa=7: no such value"},
      {"sweep " + quoted(grid) + " -o x.svg --metrik impacts", "unrecognized arguments: --metrik impacts (did you mean --metric?)"},
  };
  for (const auto& c : cases) {
    const auto r = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " plot " + c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.args << "\n" << r.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "x.svg"));
  EXPECT_FALSE(std::filesystem::exists(dir / "x.gif"));
  std::ifstream kept(existing);
  std::string text;
  std::getline(kept, text);
  EXPECT_EQ(text, "keep me");
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    EXPECT_NE(entry.path().filename().string().front(), '.') << entry.path();  // no temporary left
  EXPECT_TRUE(std::filesystem::is_symlink(dir / "grid_link.svg"));
}

TEST(PlotCommand, AComparisonWithoutTheProcedureColumnsIsOneLine) {
  // It once ended in a KeyError traceback: the procedure's columns were read unchecked.
  PCRF_REQUIRE_MATPLOTLIB();
  const auto dir = test::scratch_dir("plot_table3_short");
  std::ifstream in(test::source_dir() / "docs" / "paper_comparison.csv");
  std::string out, line;
  while (std::getline(in, line)) {  // every column but proc*: the procedure's
    std::vector<std::string> cells;
    std::stringstream fields(line);
    for (std::string cell; std::getline(fields, cell, ',');) cells.push_back(cell);
    static std::vector<bool> keep;
    if (keep.empty())
      for (const auto& c : cells) keep.push_back(c.rfind("proc", 0) != 0);
    std::string kept;
    for (std::size_t i = 0; i < cells.size(); ++i)
      if (i < keep.size() && keep[i]) kept += (kept.empty() ? "" : ",") + cells[i];
    out += kept + "\n";
  }
  test::write_file(dir, "short.csv", out);
  const auto r = test::run_command(pcrf() + " plot table3 " + quoted(dir / "short.csv") + " -o " + quoted(dir / "t.svg"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("not a paper comparison table (no column proc5ms_theta_max_rad"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "t.svg"));
}

TEST(PlotCommand, AnIdaInWhichEveryRunCollapsedIsDrawn) {
  // It once ended in a ValueError traceback: the panel's edge was the largest safe response.
  PCRF_REQUIRE_MATPLOTLIB();
  const auto dir = test::scratch_dir("plot_ida_collapsed");
  std::string records = "[[records]]\nsynthetic = [";
  for (int seed = 1; seed <= 3; ++seed)
    records += std::string(seed > 1 ? ", " : "") + "\"stochastic:seed=" + std::to_string(seed) + ",pga_g=1,duration_s=6\"";
  const auto cube = study(dir, "ida", records + "]\n[intensity]\nmeasure = \"pga_g\"\n"
                                      "[ida]\nstart = 30\nmax_intensity = 40\nmax_runs = 2\n");
  const auto status = test::run_command(pcrf() + " cube info --json " + quoted(cube));
  ASSERT_EQ(status.exit_code, 0) << status.err;
  EXPECT_EQ(status.out.find("\"at_rest\""), std::string::npos) << "a run survived: raise start\n" << status.out;
  EXPECT_EQ(status.out.find("\"rocking_at_end\""), std::string::npos) << "a run survived: raise start\n" << status.out;
  EXPECT_EQ(plot(dir / "ida.svg", "ida " + quoted(cube)), 1);
  EXPECT_EQ(plot(dir / "fragility.svg", "fragility " + quoted(cube)), 1);
}

TEST(PlotCommand, AnUnexpectedErrorIsOneLineNamingItsKindAndInput) {
  PCRF_REQUIRE_MATPLOTLIB();
  const auto dir = test::scratch_dir("plot_unexpected");
  const auto csv = test::write_file(dir, "h.csv",
                                    "t_s,theta1_rad,omega1_rad_s,omega1_after_rad_s,ground_accel_g,event\n0,zero,0,0,0,0\n");
  const auto r = test::run_command(pcrf() + " plot history " + quoted(csv) + " -o " + quoted(dir / "h.svg"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("pcrf plot: error: history " + csv.string() + ": unexpected ValueError: "), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "h.svg"));
}

TEST(PlotCommand, AMissingMatplotlibIsNamedWithItsPackage) {
  const auto dir = test::scratch_dir("plot_no_matplotlib");
  // A matplotlib that cannot be imported shadows the real one.
  std::filesystem::create_directories(dir / "fake" / "matplotlib");
  test::write_file(dir / "fake" / "matplotlib", "__init__.py", "raise ImportError(\"No module named 'matplotlib'\", name='matplotlib')\n");
  const auto csv = test::write_file(dir, "h.csv", "t_s\n0\n");
  const auto r = test::run_command("cd " + quoted(dir) + " && PYTHONPATH=" + quoted(dir / "fake") + " " + pcrf() +
                                   " plot history h.csv -o h.png");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("matplotlib not found: apt-get install python3-matplotlib"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "h.png"));
}

TEST(PlotCommand, AModuleThatIsMissingOrDoesNotImportIsOneLine) {
  const auto dir = test::scratch_dir("plot_no_module");
  // A folder whose pcrf package lacks the figures' code: Python cannot import it.
  std::filesystem::create_directories(dir / "broken" / "pcrf" / "plot");
  test::write_file(dir / "broken" / "pcrf", "__init__.py", "");
  test::write_file(dir / "broken" / "pcrf" / "plot", "__main__.py", "");
  const auto csv = test::write_file(dir, "h.csv", "t_s\n0\n");
  for (const auto& [folder, message] : {std::pair{dir / "nowhere", "the Python module's figures are missing"},
                                        std::pair{dir / "broken", "cannot import the Python module pcrf from "}}) {
    const auto r = test::run_command("cd " + quoted(dir) + " && PCRF_MODULE_DIR=" + quoted(folder) + " " + pcrf() +
                                     " plot history h.csv -o h.png");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "h.png"));
  }
}

}  // namespace
}  // namespace pcrf
