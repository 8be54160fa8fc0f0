// [run] device (pcrf/run/run_device.hpp): the setting as the one table describes it; a GPU
// that cannot be used is the user's error (exit code 2, nothing written) on the command line
// and in process; the GPU's path of a run — groups of one excitation, at least 10⁴ cases
// each, into the cube as any rank's — with a stand-in backend where no device is.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/parallel/mpi_session.hpp"
#include "pcrf/run/case_runner.hpp"
#include "pcrf/run/run_device.hpp"
#include "pcrf/run/study_run.hpp"
#include "pcrf/solver/case_group.hpp"
#include "pcrf/study/case_space.hpp"
#include "pcrf/study/record_source.hpp"
#include "pcrf/study/settings_doc.hpp"
#include "pcrf/study/study_parser.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study_test {
namespace {
using namespace pcrf::study;

parallel::MpiSession& mpi() {
  static parallel::MpiSession session;  // one rank, no launcher
  return session;
}

/// Blocks of an LHS under one short pulse at about twice their uplift threshold: `frames`
/// cases of one excitation.
std::string block_study(int frames) {
  return "[study]\nname = \"device\"\n[plan]\nkind = \"lhs\"\nsamples = " + std::to_string(frames) +
         "\nseed = 3\n[frame]\nmodel = \"block\"\ngiven_restitution = 0.9\n"
         "[axes]\nslenderness_rad = {from = 0.15, to = 0.25}\nfrequency_parameter_rad_s = {from = 1.5, to = 3.0}\n"
         "[[records]]\nsynthetic = \"sine:amplitude_g=0.45,period_s=0.5,cycles=2,duration_s=2\"\n"
         "[physics]\ntail_s = 0.5\n[outputs]\nmetrics = [\"theta_max_rad\", \"impacts\", \"t_uplift_s\"]\n";
}

/// The GPU's stand-in: `inner` (the CPU engine, or a backend refusing some cases), counting
/// the cases of each group it is handed.
class Recording final : public CaseGroupSolver {
 public:
  Recording(std::unique_ptr<CaseGroupSolver> inner, std::vector<std::size_t>* groups, std::mutex* mutex)
      : inner_(std::move(inner)), groups_(groups), mutex_(mutex) {}
  std::string_view name() const override { return "recording"; }
  std::vector<GroupCase> solve(std::span<PreparedFrame* const> frames, const Excitation& excitation,
                               const SolverSettings& solver, const OutputRequest& request,
                               const HistorySink& history) const override {
    auto answers = inner_->solve(frames, excitation, solver, request, history);
    std::lock_guard lock(*mutex_);
    groups_->push_back(frames.size());
    for (const auto& a : answers) refused += a.outcome == GroupOutcome::kRefused ? 1 : 0;
    return answers;
  }
  static inline std::size_t refused = 0;  ///< answers refused, every instance together

 private:
  std::unique_ptr<CaseGroupSolver> inner_;
  std::vector<std::size_t>* groups_;
  std::mutex* mutex_;
};

/// A backend that solves the even cases of a group (one at a time) and refuses the odd ones,
/// as the kernel refuses a case it does not cover.
class RefusingOdd final : public CaseGroupSolver {
 public:
  std::string_view name() const override { return "refusing-odd"; }
  std::vector<GroupCase> solve(std::span<PreparedFrame* const> frames, const Excitation& excitation,
                               const SolverSettings& solver, const OutputRequest& request,
                               const HistorySink& history) const override {
    std::vector<GroupCase> answers = one_at_a_time_group()->solve(frames, excitation, solver, request, history);
    for (std::size_t i = 1; i < answers.size(); i += 2) {
      answers[i] = GroupCase{};
      answers[i].outcome = GroupOutcome::kRefused;
      answers[i].result.message = "not covered (test)";
    }
    return answers;
  }
};

const Setting<RunOptions>* device_setting() { return run_settings().find("device"); }

run::StudyRunOptions options_for(const std::filesystem::path& dir, const std::string& text, const std::string& device) {
  run::StudyRunOptions options;
  options.study_file = test::write_file(dir, "device.toml", text);
  options.study = parse_study(text, options.study_file.string(), dir);
  options.output = dir / ("cube_" + device + ".h5");
  if (!device.empty()) options.run_overrides.emplace_back(device_setting(), std::string(device));
  return options;
}

TEST(DeviceSetting, IsAChoiceOfTheRunTableListedWithTheOthers) {
  const auto* s = device_setting();
  ASSERT_NE(s, nullptr) << "[run] device is missing from run_settings()";
  EXPECT_EQ(s->type, SettingType::kChoice);
  EXPECT_EQ(s->choices, (std::vector<std::string>{"cpu", "gpu"}));
  EXPECT_EQ(setting_text(s->get(run_settings().defaults)), "cpu");
  EXPECT_FALSE(s->in_fingerprint) << "where the cases are solved is how, not what";
  const std::string listed = all_settings_markdown();  // `pcrf settings`, studies/README.md
  EXPECT_NE(listed.find("| `device` | \"cpu\" or \"gpu\" | `cpu` |"), std::string::npos) << listed;

  const auto dir = test::scratch_dir("device_setting");
  const Study gpu = parse_study(block_study(4) + "[run]\ndevice = \"gpu\"\n", "s.toml", dir);
  EXPECT_EQ(gpu.run.device, Device::kGpu);
  EXPECT_EQ(parse_study(block_study(4), "s.toml", dir).run.device, Device::kCpu);
  try {
    (void)parse_study(block_study(4) + "[run]\ndevice = \"tpu\"\n", "s.toml", dir);
    FAIL() << "device = \"tpu\" was accepted";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("[run] device: unknown value \"tpu\""), std::string::npos) << e.what();
  }
}

/// The command line, where this build or machine has no usable GPU (the case here and in CI):
/// --device gpu and [run] device = "gpu" stop with exit code 2 before anything is written,
/// naming the setting and gpu_group's reason.
TEST(DeviceSetting, GpuWithoutAUsableDeviceStopsTheCommandLineWritingNothing) {
  std::string why_not;
  if (gpu_group(why_not) != nullptr) GTEST_SKIP() << "a usable GPU is here: the error cannot be provoked";
  ASSERT_FALSE(why_not.empty());
  const auto dir = test::scratch_dir("device_cli");
  const auto study = test::write_file(dir, "s.toml", block_study(4));
  const auto flag = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study s.toml -o out.h5 --device gpu");
  EXPECT_EQ(flag.exit_code, 2) << flag.err;
  EXPECT_NE(flag.err.find("--device: \"gpu\" cannot be used here: " + why_not), std::string::npos) << flag.err;
  EXPECT_EQ(std::count(flag.err.begin(), flag.err.end(), '\n'), 1) << flag.err;

  test::write_file(dir, "f.toml", block_study(4) + "[run]\ndevice = \"gpu\"\n");
  const auto file = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study f.toml -o out.h5");
  EXPECT_EQ(file.exit_code, 2) << file.err;
  EXPECT_NE(file.err.find("f.toml:20: [run] device: \"gpu\" cannot be used here"), std::string::npos) << file.err;
  const auto check = test::run_command("cd " + quoted(dir) + " && " + pcrf() + " study s.toml --check --device gpu");
  EXPECT_EQ(check.exit_code, 2) << check.err;

  std::vector<std::string> left;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) left.push_back(entry.path().filename().string());
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{"f.toml", "s.toml"})) << "no cube, lock or journal may be written";
}

/// In process, whatever the build: a backend with no device is a UserError at `device`,
/// with its reason, and nothing is written.
TEST(DeviceRun, ABackendWithoutADeviceIsAUserErrorAndWritesNothing) {
  const auto dir = test::scratch_dir("device_none");
  auto options = options_for(dir, block_study(4), "gpu");
  options.gpu_backend = [](std::string& why_not) -> std::unique_ptr<CaseGroupSolver> {
    why_not = "no CUDA device (test)";
    return nullptr;
  };
  try {
    (void)run::run_study(options, mpi());
    FAIL() << "a GPU run without a device ran";
  } catch (const UserError& e) {
    EXPECT_EQ(e.where().keys, (std::vector<std::string>{"device"}));
    EXPECT_NE(std::string(e.what()).find("\"gpu\" cannot be used here: no CUDA device (test)"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(options.output));
  EXPECT_FALSE(std::filesystem::exists(options.output.string() + ".lock"));
}

/// The GPU's path on one rank with the CPU engine standing in for the device: the master
/// hands the rank its 12 000 cases of one record as groups of at least 10⁴ (here one), and
/// the cube equals a CPU run's bit for bit.
TEST(DeviceRun, AGpuRankSolvesLargeGroupsOfOneRecordIntoTheCube) {
  const auto dir = test::scratch_dir("device_groups");
  const std::string text = block_study(12000);
  std::vector<std::size_t> groups;
  std::mutex mutex;
  auto gpu = options_for(dir, text, "gpu");
  gpu.gpu_backend = [&](std::string&) -> std::unique_ptr<CaseGroupSolver> {
    return std::make_unique<Recording>(one_at_a_time_group(), &groups, &mutex);
  };
  const auto summary = run::run_study(gpu, mpi());
  ASSERT_TRUE(summary.has_value());
  EXPECT_EQ(summary->computed, 12000);
  ASSERT_FALSE(groups.empty());
  std::size_t cases = 0;
  for (const std::size_t g : groups) cases += g;
  EXPECT_EQ(cases, 12000u);
  EXPECT_GE(*std::min_element(groups.begin(), groups.end()), 10000u) << "groups: " << groups.size();

  const auto cpu = options_for(dir, text, "cpu");
  ASSERT_TRUE(run::run_study(cpu, mpi()).has_value());
  const cube::CubeReader a(gpu.output), b(cpu.output);
  EXPECT_EQ(a.read_status(), b.read_status());
  for (const char* metric : {"theta_max_rad", "impacts", "t_uplift_s"}) {
    const auto x = a.read_metric(metric), y = b.read_metric(metric);
    ASSERT_EQ(x.size(), y.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < x.size(); ++i) differ += (x[i] == y[i] || (std::isnan(x[i]) && std::isnan(y[i]))) ? 0 : 1;
    EXPECT_EQ(differ, 0u) << metric;
  }
  const auto status = a.read_status();
  const auto impacts = a.read_metric("impacts");
  EXPECT_GT(std::count_if(impacts.begin(), impacts.end(), [](double n) { return n > 0.0; }), 1000)
      << "too few cases rock: the test sees too little";
  EXPECT_EQ(std::count(status.begin(), status.end(), cube::kStatusNotRun), 0);
}

/// The same path with the host build of the case kernel behind it (dopri5, which it steps):
/// its answers reach the cube equal to the CPU engine's bit for bit.
TEST(DeviceRun, TheHostKernelBehindTheGpuPathFillsTheCubeAsTheCpuEngine) {
  const auto dir = test::scratch_dir("device_host_kernel");
  const std::string text = block_study(2000) + "[solver]\nintegrator = \"dopri5\"\n";
  std::vector<std::size_t> groups;
  std::mutex mutex;
  auto gpu = options_for(dir, text, "gpu");
  gpu.gpu_backend = [&](std::string&) -> std::unique_ptr<CaseGroupSolver> {
    return std::make_unique<Recording>(kernel_host_group(), &groups, &mutex);
  };
  Recording::refused = 0;
  ASSERT_TRUE(run::run_study(gpu, mpi()).has_value());
  EXPECT_EQ(groups, (std::vector<std::size_t>{2000}));
  EXPECT_EQ(Recording::refused, 0u) << "the kernel refused cases: the CPU engine answered them";
  const auto cpu = options_for(dir, text, "cpu");
  ASSERT_TRUE(run::run_study(cpu, mpi()).has_value());
  const cube::CubeReader a(gpu.output), b(cpu.output);
  EXPECT_EQ(a.read_status(), b.read_status());
  EXPECT_TRUE(a.read_notes().empty()) << a.read_notes().front().second;
  for (const char* metric : {"theta_max_rad", "impacts", "t_uplift_s"}) {
    const auto x = a.read_metric(metric), y = b.read_metric(metric);
    std::size_t differ = 0;
    for (std::size_t i = 0; i < x.size(); ++i) differ += (x[i] == y[i] || (std::isnan(x[i]) && std::isnan(y[i]))) ? 0 : 1;
    EXPECT_EQ(differ, 0u) << metric;
  }
}

/// Cases the kernel refuses (a scene, integrator or output it does not cover) are the CPU
/// engine's to solve: every case of the group gets the engine's answer.
TEST(DeviceRun, CasesTheKernelRefusesAreSolvedByTheCpuEngine) {
  const auto dir = test::scratch_dir("device_refused");
  auto study = parse_study(block_study(64) + "[run]\ndevice = \"gpu\"\n", "s.toml", dir);
  const auto group = run::device_group_solver(study, Where{}, [](std::string&) -> std::unique_ptr<CaseGroupSolver> {
    return std::make_unique<RefusingOdd>();
  });
  auto cpu_study = study;
  cpu_study.run.device = Device::kCpu;
  const auto cpu = run::device_group_solver(cpu_study, Where{});
  CaseSpace space(study);
  RecordCache records(study.records);
  run::CaseRunner on_gpu(study, space, records, group), on_cpu(cpu_study, space, records, cpu);
  std::vector<parallel::WorkItem> items;
  for (std::int64_t i = 0; i < space.size(); ++i) items.push_back({i, 0.0});
  const auto a = on_gpu.run(items), b = on_cpu.run(items);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].status, b[i].status) << "case " << i;
    EXPECT_EQ(a[i].note, b[i].note) << "case " << i;
    for (std::size_t m = 0; m < a[i].row.size(); ++m)
      EXPECT_TRUE(a[i].row[m] == b[i].row[m] || (std::isnan(a[i].row[m]) && std::isnan(b[i].row[m]))) << "case " << i;
  }
}

/// A run whose kernel refuses cases says so once at its end: how many, and the first reason.
TEST(DeviceRun, ARunSaysHowManyCasesTheKernelLeftToTheCpuEngine) {
  const auto dir = test::scratch_dir("device_refusal_note");
  auto options = options_for(dir, block_study(64), "gpu");
  options.gpu_backend = [](std::string&) -> std::unique_ptr<CaseGroupSolver> { return std::make_unique<RefusingOdd>(); };
  std::vector<std::string> notes;
  options.notes = &notes;
  ASSERT_TRUE(run::run_study(options, mpi()).has_value());
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("rank 0: 32 cases of this rank went to the CPU engine"), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find("(the first: not covered (test))"), std::string::npos) << notes[0];
  EXPECT_EQ(cube::CubeReader(options.output).read_status().size(), 64u);
}

}  // namespace
}  // namespace pcrf::study_test
