// Batch bench (see bench/batch/CMakeLists.txt and bench/batch_cost.py).
//
//   pcrf_batch_bench --scene block|frame --cases N --lanes W [--one-case] [--trig T]
//                    [--kernels K] [--level 2] [--integrator dopri5|taylor] RECORD.AT2 ...
//
// Builds an N-point Latin hypercube of the scene (the block: α, R; the prestressed frame:
// tan α, Π_σc, κ), scales each record to `level` times the design's median uplift
// threshold, and solves every case under every record with the balanced preset (its
// integrator, `taylor`, unless --integrator names another; the lanes step dopri5, and take
// a rigid rocker under `taylor` one case at a time): with
// --one-case by solve_case one case after the other, else by solve_batch in W lanes. Prints
// one JSON line: cases, seconds (the process's CPU time: the machine may be shared), wall
// seconds, cases/s (per CPU second), and the batch's statistics.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "pcrf/model/frame.hpp"
#include "pcrf/model/rigid_rocker.hpp"
#include "pcrf/record/record_readers.hpp"
#include "pcrf/solver/batch_solver.hpp"
#include "solver/case/prepared_frame.hpp"

namespace {

using namespace pcrf;

/// CPU time of this process [s].
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

std::vector<std::shared_ptr<PreparedFrame>> design(const std::string& scene, std::size_t n) {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<std::vector<double>> x(n, std::vector<double>(3));
  for (std::size_t j = 0; j < 3; ++j) {
    std::vector<std::size_t> order(n);
    for (std::size_t i = 0; i < n; ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), rng);
    for (std::size_t i = 0; i < n; ++i) x[i][j] = (static_cast<double>(order[i]) + u(rng)) / static_cast<double>(n);
  }
  auto between = [](double lo, double hi, double v) { return lo + (hi - lo) * v; };
  std::vector<std::shared_ptr<PreparedFrame>> frames;
  for (const auto& p : x) {
    if (scene == "frame") {
      FrameParameters f;
      f.tan_alpha = between(0.15, 0.25, p[0]);
      f.pi_sigma_c = between(2.0, 10.0, p[1]);
      f.kappa = between(1.0, 2.5, p[2]);
      frames.push_back(prepare_frame(make_frame(f), PhysicsOptions{}));
    } else {
      RockerParameters r;
      r.slenderness_rad = between(0.15, 0.25, p[0]);
      r.size_m = between(0.5, 3.0, p[1]);
      frames.push_back(prepare_scene(std::make_unique<RigidRocker>(r), PhysicsOptions{}));
    }
  }
  return frames;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"cases per second, one case at a time or in lockstep lanes"};
  std::string scene = "block", trig, kernels, integrator;
  std::size_t cases = 1000;
  int lanes = 4;
  bool one_case = false;
  double level = 2.0;
  std::vector<std::string> records;
  app.add_option("--scene", scene)->check(CLI::IsMember({"block", "frame"}));
  app.add_option("--cases", cases);
  app.add_option("--lanes", lanes);
  app.add_flag("--one-case", one_case);
  app.add_option("--trig", trig);
  app.add_option("--kernels", kernels);
  app.add_option("--level", level, "record PGA over the design's median uplift threshold");
  app.add_option("--integrator", integrator, "the balanced preset's tolerances with this integrator");
  app.add_option("records", records)->required()->check(CLI::ExistingFile);
  CLI11_PARSE(app, argc, argv);

  const auto frames = design(scene, cases);
  std::vector<PreparedFrame*> views;
  std::vector<double> thresholds;
  for (const auto& f : frames) views.push_back(f.get()), thresholds.push_back(f->scene().uplift_threshold_m_s2());
  std::nth_element(thresholds.begin(), thresholds.begin() + static_cast<long>(cases / 2), thresholds.end());
  const double target_m_s2 = level * thresholds[cases / 2];
  std::vector<GroundMotion> motions;
  for (const auto& r : records) {
    const GroundMotion raw = read_at2(r);
    motions.push_back(raw.scaled(target_m_s2 / raw.pga_m_s2()));
  }
  SolverSettings solver = preset_settings("balanced");
  if (!integrator.empty()) solver.integrator = parse_integrator(integrator);
  BatchOptions options;
  options.lanes = lanes;
  options.trig = trig;
  options.kernels = kernels;
  BatchStats total, stats;
  long impacts = 0, lifted = 0;
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start_s = cpu_seconds();
  for (const GroundMotion& m : motions) {
    std::vector<CaseResult> results;
    if (one_case) {
      for (PreparedFrame* f : views) results.push_back(solve_case(*f, m, solver));
    } else {
      results = solve_batch(views, m, solver, OutputRequest{}, options, &stats);
      total.kernels = stats.kernels, total.trig = stats.trig, total.lanes = stats.lanes;
      total.kernel_calls += stats.kernel_calls, total.busy_lane_attempts += stats.busy_lane_attempts;
      total.accepted += stats.accepted, total.rejected += stats.rejected, total.root_searches += stats.root_searches;
      total.events += stats.events, total.flights += stats.flights, total.rest_cases += stats.rest_cases;
    }
    for (const CaseResult& r : results) impacts += r.impacts, lifted += r.impacts > 0 ? 1 : 0;
  }
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double seconds = cpu_seconds() - cpu_start_s;
  const double n = static_cast<double>(cases * motions.size());
  std::printf(
      "{\"scene\": \"%s\", \"mode\": \"%s\", \"lanes\": %d, \"kernels\": \"%s\", \"trig\": \"%s\", \"cases\": %.0f, "
      "\"rocking_cases\": %ld, \"impacts\": %ld, \"seconds\": %.4f, \"wall_s\": %.4f, \"cases_per_s\": %.1f, "
      "\"occupancy\": %.4f, "
      "\"kernel_calls\": %ld, \"accepted\": %ld, \"rejected\": %ld, \"root_searches\": %ld, \"events\": %ld, "
      "\"flights\": %ld, \"rest_cases\": %ld}\n",
      scene.c_str(), one_case ? "one-case" : "batch", one_case ? 1 : lanes, total.kernels.c_str(), total.trig.c_str(), n,
      lifted, impacts, seconds, wall_s, n / seconds, total.occupancy(), total.kernel_calls, total.accepted, total.rejected,
      total.root_searches, total.events, total.flights, total.rest_cases);
  return 0;
}
