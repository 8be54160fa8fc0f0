// GPU bench (not a test; bench/gpu/gpu_measure.sh runs it, docs/gpu.md):
//
//   pcrf_gpu_bench STUDY.toml --backend gpu|cpu|host-kernel [--cases N] [--group G]
//                  [--seconds-limit S]
//   pcrf_gpu_bench STUDY.toml --median-threshold-g
//
// Solves the first N cases of a study (its storage order: one record and one level, an LHS
// of frames) through one group-of-cases backend, G cases a group (the group a GPU rank is
// handed in a study: run_device.hpp's kGpuGroupCases), and prints one JSON line: cases,
// the wall and CPU seconds spent in the backend's solve (the frames' set-up is timed apart,
// as `prepare_s`), cases per wall second of the solve, and the statuses. A backend the
// machine lacks: {"backend": ..., "unavailable": "why"} and exit code 3.
//
// Under mpirun (OMPI_COMM_WORLD_RANK / _SIZE) each process takes its share of the N cases;
// the script sums the processes' rates (they run side by side, one core each). With
// --seconds-limit a process stops after the first group that ends past S seconds of solve:
// its rate is then over the cases it did, a random subset of the LHS.
//
// --median-threshold-g: the median uplift threshold of the study's frames [g] (the first N,
// or all), for a study at twice it.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "pcrf/excitation/station_record.hpp"
#include "pcrf/run/run_device.hpp"
#include "pcrf/solver/case_group.hpp"
#include "pcrf/solver/rocking_solver.hpp"
#include "pcrf/study/case_space.hpp"
#include "pcrf/study/record_source.hpp"
#include "pcrf/study/study_parser.hpp"

namespace {

using namespace pcrf;

constexpr double kStandardGravity_m_s2 = 9.80665;

/// CPU time of this process [s].
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// This process's place under mpirun (rank, ranks); (0, 1) alone.
std::pair<long, long> launcher_rank() {
  const char* rank = std::getenv("OMPI_COMM_WORLD_RANK");
  const char* size = std::getenv("OMPI_COMM_WORLD_SIZE");
  if (rank == nullptr || size == nullptr) return {0, 1};
  return {std::strtol(rank, nullptr, 10), std::max(1L, std::strtol(size, nullptr, 10))};
}

std::unique_ptr<CaseGroupSolver> backend_of(const std::string& name, const study::Study& study, std::string& why_not) {
  if (name == "gpu") return gpu_group(why_not);
  if (name == "host-kernel") return kernel_host_group();
  return make_group_solver(study.solver, static_cast<int>(study.run.lanes));  // the CPU engine
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"cases per second of a study's cases through one group-of-cases backend"};
  std::string file, backend = "cpu";
  long cases = 0;
  long group = static_cast<long>(run::kGpuGroupCases);
  double seconds_limit = 0.0;
  bool median_threshold = false;
  app.add_option("study", file)->required()->check(CLI::ExistingFile);
  app.add_option("--backend", backend)->check(CLI::IsMember({"gpu", "cpu", "host-kernel"}));
  app.add_option("--cases", cases, "the study's first N cases (0: all)");
  app.add_option("--group", group, "cases a group");
  app.add_option("--seconds-limit", seconds_limit, "stop after the group that passes this much solve time [s]; 0: none");
  app.add_flag("--median-threshold-g", median_threshold, "print the frames' median uplift threshold [g]");
  CLI11_PARSE(app, argc, argv);

  const study::Study study = study::load_study(file);
  const study::CaseSpace space(study);
  const long total = cases > 0 ? std::min<long>(cases, space.size()) : static_cast<long>(space.size());
  if (median_threshold) {
    std::vector<double> g;
    for (long i = 0; i < total; ++i) g.push_back(space.case_at(i).frame.make()->uplift_threshold_m_s2() / kStandardGravity_m_s2);
    std::nth_element(g.begin(), g.begin() + static_cast<long>(g.size() / 2), g.end());
    std::printf("{\"median_uplift_threshold_g\": %.6f, \"frames\": %ld}\n", g[g.size() / 2], total);
    return 0;
  }
  std::string why_not;
  const auto solver = backend_of(backend, study, why_not);
  if (solver == nullptr) {
    std::printf("{\"backend\": \"%s\", \"unavailable\": \"%s\"}\n", backend.c_str(), why_not.c_str());
    return 3;
  }
  const auto [rank, ranks] = launcher_rank();
  const long first = total * rank / ranks, last = total * (rank + 1) / ranks;
  study::RecordCache records(study.records);
  OutputRequest request;
  request.omega_peak = false;
  std::map<int, long> statuses;
  long done = 0, rocking = 0;
  double solve_s = 0.0, solve_cpu_s = 0.0, prepare_s = 0.0;
  std::shared_ptr<const ScaledExcitation> motion;
  std::int64_t motion_of = -1;
  for (long from = first; from < last; from += group) {
    const long to = std::min(last, from + group);
    const double prepare_start = wall_seconds();
    std::vector<std::shared_ptr<PreparedFrame>> frames;
    std::vector<PreparedFrame*> views;
    for (long i = from; i < to; ++i) {
      const study::CaseSpec spec = space.case_at(i);
      if (space.excitation_of(i) != motion_of) {  // one record and level in these studies; else a group per excitation
        motion_of = space.excitation_of(i);
        const double factor = records.scale_factor(spec.record, spec.level, study.intensity);
        motion = std::make_shared<const ScaledExcitation>(frame_excitation(records.station(spec.record), spec.incidence_deg, factor));
      }
      frames.push_back(prepare_scene(spec.frame.make(), study.physics));
      views.push_back(frames.back().get());
    }
    prepare_s += wall_seconds() - prepare_start;
    const double start = wall_seconds(), cpu_start = cpu_seconds();
    const auto answers = solver->solve(views, motion->view(), study.solver, request);
    solve_s += wall_seconds() - start;
    solve_cpu_s += cpu_seconds() - cpu_start;
    for (const GroupCase& a : answers) {
      ++statuses[a.outcome == GroupOutcome::kRefused ? -1 : static_cast<int>(a.result.status)];
      rocking += a.outcome == GroupOutcome::kSolved && a.result.impacts > 0 ? 1 : 0;
    }
    done += to - from;
    if (seconds_limit > 0.0 && solve_s > seconds_limit) break;
  }
  std::string counts;
  for (const auto& [status, n] : statuses)
    counts += (counts.empty() ? "" : ", ") + std::string("\"") +
              (status < 0 ? std::string("refused") : std::string(status_name(static_cast<CaseStatus>(status)))) +
              "\": " + std::to_string(n);
  std::printf(
      "{\"backend\": \"%s\", \"name\": \"%s\", \"rank\": %ld, \"ranks\": %ld, \"cases\": %ld, \"rocking\": %ld, "
      "\"solve_s\": %.4f, \"solve_cpu_s\": %.4f, \"prepare_s\": %.4f, \"cases_per_s\": %.1f, \"group\": %ld, "
      "\"statuses\": {%s}}\n",
      backend.c_str(), solver->name().data(), rank, ranks, done, rocking, solve_s, solve_cpu_s, prepare_s,
      solve_s > 0.0 ? static_cast<double>(done) / solve_s : 0.0, group, counts.c_str());
  return 0;
}
