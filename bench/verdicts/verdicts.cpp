// pcrf_verdicts: the verdict benchmark of issue 11. An IDA-style grid — the 22 FEMA P-695
// far-field records (NGA-West2, ../shared/records/ngawest2_ff_youtian95) × 3 frames × 48 PGA
// levels from below uplift to beyond collapse — solved by a converged reference (ARKODE ERK8,
// rtol 1e-12) and by each preset and two other integrators. A case is well-conditioned when
// the reference gives the same verdict with the record scaled by 1 ± 1e-9, 1 ± 1e-7 and
// 1 ± 1e-6. Printed: agreement of verdicts (all cases, well-conditioned cases), the error in
// each curve's first collapsing level, θ_max errors, impact-count agreement, time per case,
// where the ill-conditioned cases lie relative to the collapse intensity, and the cost of
// [solver] verdict_check. Writes OUT_cases.csv with one row per case and contender.
//
//   build/bench/verdicts/pcrf_verdicts [--out verdicts] [--levels 48] [--threads 2]
#include <CLI/CLI.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "pcrf/record/intensity.hpp"
#include "pcrf/record/record_readers.hpp"
#include "pcrf/solver/rocking_solver.hpp"

namespace fs = std::filesystem;
using namespace pcrf;

namespace {

using Clock = std::chrono::steady_clock;

struct Contender {
  std::string name;
  SolverSettings settings;
};

struct Case {
  std::size_t record, frame, level;
  double pga_g;
};

/// What one solve reports (time measured around it).
struct Run {
  CaseStatus status = CaseStatus::kNotRun;
  double theta = 0.0;
  long impacts = 0;
  double time_s = 0.0;
  double stable = std::nan(""), fraction = std::nan("");
};


double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}
double quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}

/// Runs `work(i)` for i in [0, n) on `threads` threads.
void parallel_for(std::size_t n, int threads, const std::function<void(std::size_t)>& work) {
  std::atomic<std::size_t> next{0};
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&] {
      for (std::size_t i; (i = next++) < n;) work(i);
    });
  for (auto& t : pool) t.join();
}

SolverSettings reference_settings() {
  SolverSettings s;
  s.integrator = Integrator::kArkodeErk8;
  s.rtol = 1e-12;
  s.atol_theta_rad = 1e-16;
  s.atol_omega_rad_s = 1e-15;
  s.stop_at_samples = true;
  s.preset = "reference-ERK8";
  return s;
}

std::vector<Contender> contenders() {
  std::vector<Contender> c;
  for (const auto& p : preset_names()) c.push_back({p, preset_settings(p)});
  SolverSettings erk8 = preset_settings("balanced");
  erk8.integrator = Integrator::kArkodeErk8;
  c.push_back({"arkode-erk8 rtol=1e-6", erk8});
  SolverSettings bdf = preset_settings("balanced");
  bdf.integrator = Integrator::kCvodeBdf;
  c.push_back({"cvode-bdf rtol=1e-6", bdf});
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Verdict benchmark: presets and integrators against a converged reference on an IDA-style grid"};
  std::string out = "verdicts", records_dir;
  int levels = 48, threads = 2;
  double lo_g = 0.5, hi_g = 5.0;
  app.add_option("--out", out, "output prefix: OUT_cases.csv")->capture_default_str();
  app.add_option("--levels", levels, "PGA levels per curve (geometric)")->capture_default_str();
  app.add_option("--from", lo_g, "lowest PGA [g]")->capture_default_str();
  app.add_option("--to", hi_g, "highest PGA [g]")->capture_default_str();
  app.add_option("--threads", threads, "worker threads")->capture_default_str();
  app.add_option("--records-dir", records_dir, "shared records folder (default $PCRF_RECORDS_DIR or ../shared/records)");
  CLI11_PARSE(app, argc, argv);

  if (records_dir.empty()) {
    const char* env = std::getenv("PCRF_RECORDS_DIR");
    records_dir = env ? env : PCRF_DEFAULT_RECORDS_DIR;
  }
  const fs::path folder = fs::path(records_dir) / "ngawest2_ff_youtian95";
  if (!fs::is_directory(folder)) {
    std::cout << "note: " << folder.string() << " not found: nothing to measure\n";
    return 0;
  }
  std::vector<GroundMotion> records;
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.path().extension() == ".txt" && entry.path().filename() != "MetaData.txt") names.push_back(entry.path().string());
  std::sort(names.begin(), names.end());
  for (const auto& n : names) records.push_back(read_two_column(n, AccelUnit::kG));
  std::vector<std::pair<std::string, FrameParameters>> frames{{"basic", FrameParameters{}}};
  frames.push_back({"stocky", FrameParameters{}});
  frames.back().second.tan_alpha = 0.25;
  frames.push_back({"prestressed", FrameParameters{}});
  frames.back().second.pi_sigma_c *= 1.5;

  std::vector<Case> cases;
  for (std::size_t r = 0; r < records.size(); ++r)
    for (std::size_t f = 0; f < frames.size(); ++f)
      for (int l = 0; l < levels; ++l)
        cases.push_back({r, f, static_cast<std::size_t>(l), lo_g * std::pow(hi_g / lo_g, l / double(levels - 1))});
  std::cerr << "pcrf_verdicts: " << cases.size() << " cases (" << records.size() << " records × " << frames.size()
            << " frames × " << levels << " levels), " << threads << " threads\n";

  auto solve = [&](const Case& c, const SolverSettings& s, double factor) {
    const GroundMotion& rec = records[c.record];
    const GroundMotion scaled = rec.scaled(factor * c.pga_g / peak_acceleration(rec).pga_g);
    const auto t0 = Clock::now();
    const CaseResult r = solve_case(make_frame(frames[c.frame].second), scaled, PhysicsOptions{}, s, OutputRequest{false});
    return Run{r.status, r.theta_max_rad, r.impacts, std::chrono::duration<double>(Clock::now() - t0).count(),
               r.status_stable, r.collapse_fraction};
  };

  // The reference and its six perturbed twins.
  const double perturbations[] = {1e-9, -1e-9, 1e-7, -1e-7, 1e-6, -1e-6};
  std::vector<Run> ref(cases.size());
  std::vector<bool> well(cases.size(), true);
  auto start = Clock::now();
  parallel_for(cases.size(), threads, [&](std::size_t i) {
    ref[i] = solve(cases[i], reference_settings(), 1.0);
    for (double e : perturbations) well[i] = well[i] && verdict_of(solve(cases[i], reference_settings(), 1.0 + e).status) == verdict_of(ref[i].status);
  });
  std::cerr << "reference and twins: " << std::chrono::duration<double>(Clock::now() - start).count() << " s\n";

  const auto all = contenders();
  std::vector<std::vector<Run>> runs(all.size(), std::vector<Run>(cases.size()));
  for (std::size_t k = 0; k < all.size(); ++k) {
    start = Clock::now();
    parallel_for(cases.size(), threads, [&](std::size_t i) { runs[k][i] = solve(cases[i], all[k].settings, 1.0); });
    std::cerr << all[k].name << ": " << std::chrono::duration<double>(Clock::now() - start).count() << " s\n";
  }
  // The cost of the verdict check on the default preset.
  SolverSettings checked = preset_settings("balanced");
  checked.verdict_check = true;
  std::vector<Run> check(cases.size());
  parallel_for(cases.size(), threads, [&](std::size_t i) { check[i] = solve(cases[i], checked, 1.0); });

  // ---- per-case CSV --------------------------------------------------------------------
  std::ofstream csv(out + "_cases.csv");
  csv << "record,frame,pga_g,well_conditioned,ref_status,ref_theta_rad,ref_impacts,contender,status,theta_rad,impacts,time_s\n";
  for (std::size_t i = 0; i < cases.size(); ++i)
    for (std::size_t k = 0; k < all.size(); ++k)
      csv << fs::path(names[cases[i].record]).stem().string() << ',' << frames[cases[i].frame].first << ','
          << cases[i].pga_g << ',' << well[i] << ',' << status_name(ref[i].status) << ',' << ref[i].theta << ','
          << ref[i].impacts << ',' << all[k].name << ',' << status_name(runs[k][i].status) << ',' << runs[k][i].theta
          << ',' << runs[k][i].impacts << ',' << runs[k][i].time_s << '\n';

  // ---- conditioning ---------------------------------------------------------------------
  const auto n_well = std::count(well.begin(), well.end(), true);
  std::printf("\n%zu cases; %zu ill-conditioned (%.2f %%): the reference's verdict changes when the record is "
              "scaled by 1 ± 1e-9, 1e-7 or 1e-6\n", cases.size(), cases.size() - static_cast<std::size_t>(n_well),
              100.0 * double(cases.size() - static_cast<std::size_t>(n_well)) / double(cases.size()));
  // Where: intensity relative to each curve's first collapsing level in the reference.
  std::map<std::pair<std::size_t, std::size_t>, double> first_collapse;  // (record, frame) → PGA
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const auto key = std::make_pair(cases[i].record, cases[i].frame);
    if (is_collapse(ref[i].status) && !first_collapse.count(key)) first_collapse[key] = cases[i].pga_g;
  }
  const double edges[] = {0.0, 0.7, 0.85, 0.95, 1.05, 1.2, 1.5, 1e9};
  std::printf("\nill-conditioned share by PGA / the curve's first collapsing PGA (reference):\n");
  for (int b = 0; b + 1 < 8; ++b) {
    int n = 0, ill = 0;
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const auto it = first_collapse.find({cases[i].record, cases[i].frame});
      if (it == first_collapse.end()) continue;
      const double x = cases[i].pga_g / it->second;
      if (x < edges[b] || x >= edges[b + 1]) continue;
      ++n;
      ill += !well[i];
    }
    std::printf("  [%4.2f, %4.2f): %5d cases, %4d ill-conditioned (%5.1f %%)\n", edges[b], std::min(edges[b + 1], 99.0), n, ill,
                n ? 100.0 * ill / n : 0.0);
  }

  // ---- contenders -------------------------------------------------------------------------
  std::printf("\n%-24s %9s %9s %13s %11s %11s %11s %10s %10s\n", "contender", "verdicts", "on well", "collapse lvl",
              "θmax med", "θmax p90", "impacts =", "|Δimp| med", "ms/case");
  for (std::size_t k = 0; k < all.size(); ++k) {
    int agree = 0, agree_well = 0, impacts_equal = 0;
    std::vector<double> err, dimp, times;
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const Run& r = runs[k][i];
      const bool same = verdict_of(r.status) == verdict_of(ref[i].status);
      agree += same;
      agree_well += same && well[i];
      times.push_back(r.time_s);
      impacts_equal += r.impacts == ref[i].impacts;
      dimp.push_back(std::fabs(double(r.impacts - ref[i].impacts)));
      if (ref[i].theta > 0 && !is_collapse(ref[i].status) && !is_collapse(r.status))
        err.push_back(std::fabs(r.theta - ref[i].theta) / ref[i].theta);
    }
    // First collapsing level of each curve: the contender's against the reference's.
    int curves = 0, same_level = 0;
    for (std::size_t rc = 0; rc < records.size(); ++rc)
      for (std::size_t f = 0; f < frames.size(); ++f) {
        long first_ref = -1, first_k = -1;
        for (std::size_t i = 0; i < cases.size(); ++i) {
          if (cases[i].record != rc || cases[i].frame != f) continue;
          if (first_ref < 0 && is_collapse(ref[i].status)) first_ref = long(cases[i].level);
          if (first_k < 0 && is_collapse(runs[k][i].status)) first_k = long(cases[i].level);
        }
        ++curves;
        same_level += first_ref == first_k;
      }
    char on_well[32], level[32];
    std::snprintf(on_well, sizeof on_well, "%d/%ld", agree_well, long(n_well));
    std::snprintf(level, sizeof level, "%d/%d", same_level, curves);
    std::printf("%-24s %8.2f%% %9s %13s %11.2e %11.2e %10.1f%% %10g %10.3f\n", all[k].name.c_str(),
                100.0 * agree / double(cases.size()), on_well, level, median(err), quantile(err, 0.9),
                100.0 * impacts_equal / double(cases.size()), median(dimp), 1e3 * median(times));
  }
  double t_off = 0, t_on = 0;
  int flagged = 0, flagged_ill = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    t_off += runs[1][i].time_s;  // balanced
    t_on += check[i].time_s;
    if (check[i].stable == 0.0) {
      ++flagged;
      flagged_ill += !well[i];
    }
  }
  std::printf("\nverdict_check on `balanced`: %.2f× the time of the unchecked runs (%.1f s vs %.1f s of solver time); "
              "%d cases flagged unstable, %d of them ill-conditioned in the reference\n",
              t_on / t_off, t_on, t_off, flagged, flagged_ill);
  return 0;
}
