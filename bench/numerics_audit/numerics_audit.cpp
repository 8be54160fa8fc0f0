// pcrf_numerics_audit: what does each integration scheme predict after the strong motion?
//
// The paper (Sect. 6) reports a "pseudo-steady-state vibration": small, high-frequency
// rocking that persists after the strong motion. This bench runs the basic frame under the
// paper's records (scaled so that they rock; default ×2.5) plus a free-vibration tail, with
//   - exact event location (ARKODE ERK8 rtol 1e-12 and the `balanced` preset), and
//   - the fixed-step RK4 scheme with impacts found only as sign changes (record dt, dt/10,
//     dt/100),
// and reports, after the strong motion (from t95, the time at which 95 % of the Arias
// intensity is reached, to the end of the record) and in the tail (no ground motion):
// RMS and peak |θ₁|, impacts, and an envelope of |θ₁| (peak per 0.1 s) for the figure.
//
//   pcrf_numerics_audit [--out PREFIX] [--scale 2.5] [--tail 10] [--records ER1,ER3]
//                       [--divs 1,10,100] [--records-dir DIR] [--no-synthetic]
//
// Writes PREFIX_summary.csv (one row per record × method) and PREFIX_envelope.csv.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "pcrf/model/equation_of_motion.hpp"
#include "pcrf/model/frame.hpp"
#include "pcrf/record/record_readers.hpp"
#include "pcrf/record/synthetic.hpp"
#include "pcrf/solver/rocking_solver.hpp"

namespace fs = std::filesystem;
using namespace pcrf;

namespace {

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

std::string fmt(double v, int digits = 6) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

/// Time at which `fraction` of the Arias intensity (∫ a² dt) is reached [s].
double arias_time(const GroundMotion& rec, double fraction) {
  const auto& a = rec.samples_m_s2();
  double total = 0;
  for (const double x : a) total += x * x;
  double run = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    run += a[i] * a[i];
    if (run >= fraction * total) return static_cast<double>(i) * rec.dt_s();
  }
  return rec.duration_s();
}

/// The record cut at time t (samples up to and including the one at or before t).
GroundMotion truncated(const GroundMotion& rec, double t) {
  const auto n = static_cast<std::size_t>(std::floor(t / rec.dt_s() + 1e-9)) + 1;
  std::vector<double> a(rec.samples_m_s2().begin(), rec.samples_m_s2().begin() + static_cast<long>(std::min(n, rec.size())));
  return GroundMotion(rec.name(), rec.dt_s(), std::move(a));
}

/// Time-weighted statistics of |θ₁| over [t0, t1) from a history (trapezoid on θ²).
struct Window {
  double t0, t1;
  double sq = 0, peak = 0, last_motion = -1;
  double t_prev = NAN, th_prev = 0;
  void add(double t, double th) {
    if (!std::isnan(t_prev)) {
      const double a = std::max(t_prev, t0), b = std::min(t, t1);
      if (b > a) sq += 0.5 * (th_prev * th_prev + th * th) * (b - a);
    }
    if (t >= t0 && t < t1) {
      peak = std::max(peak, std::abs(th));
      if (th != 0.0) last_motion = t;
    }
    t_prev = t;
    th_prev = th;
  }
  double rms() const { return t1 > t0 ? std::sqrt(sq / (t1 - t0)) : 0.0; }
};

struct Method {
  std::string name;
  SolverSettings s;
  double div = 0;  ///< fixed-step divisor (0: not fixed-step)
};

}  // namespace

int main(int argc, char** argv) {
  std::string out = "numerics_audit", records_arg, divs_arg = "1,10,100", records_dir_arg;
  double scale = 2.5, tail = 10.0;
  bool synthetic = true;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::cerr << a << " needs a value\n";
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--out") out = next();
    else if (a == "--scale") scale = std::stod(next());
    else if (a == "--tail") tail = std::stod(next());
    else if (a == "--records") records_arg = next();
    else if (a == "--divs") divs_arg = next();
    else if (a == "--records-dir") records_dir_arg = next();
    else if (a == "--no-synthetic") synthetic = false;
    else {
      std::cerr << "usage: pcrf_numerics_audit [--out PREFIX] [--scale 2.5] [--tail 10] [--records ER1,ER3] "
                   "[--divs 1,10,100] [--records-dir DIR] [--no-synthetic]\n";
      return a == "--help" || a == "-h" ? 0 : 2;
    }
  }

  // Records: the paper's, scaled; plus a synthetic one at twice the uplift threshold.
  fs::path dir = records_dir_arg;
  if (dir.empty()) {
    const char* env = std::getenv("PCRF_RECORDS_DIR");
    dir = env ? fs::path(env) : fs::path(PCRF_DEFAULT_RECORDS_DIR);
  }
  const Frame frame = basic_frame();
  const double thr = EquationOfMotion(frame).uplift_threshold_m_s2();
  std::vector<std::pair<std::string, GroundMotion>> records;
  const auto wanted = split(records_arg);
  std::ifstream index(dir / "paper" / "INDEX.csv");
  if (!index) {
    std::cerr << "note: " << (dir / "paper" / "INDEX.csv").string() << " not found: paper records skipped\n";
  } else {
    std::string line;
    std::getline(index, line);
    while (std::getline(index, line)) {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      const auto f = split(line);
      if (f.size() < 2) continue;
      if (!wanted.empty() && std::find(wanted.begin(), wanted.end(), f[0]) == wanted.end()) continue;
      records.emplace_back(f[0] + "x" + fmt(scale, 3), read_at2(dir / f[1]).scaled(scale));
    }
  }
  if (synthetic) {
    StochasticSpec sp;
    sp.seed = 11;
    sp.pga_g = 2.0 * thr / kGravity_m_s2;
    sp.duration_s = 30.0;
    sp.dt_s = 0.01;
    records.emplace_back("stoch11@2thr", make_stochastic(sp));
  }

  std::vector<Method> methods;
  {
    SolverSettings exact;
    exact.integrator = Integrator::kArkodeErk8;
    exact.rtol = 1e-12;
    exact.atol_theta_rad = 1e-14;
    exact.atol_omega_rad_s = 1e-13;
    exact.stop_at_samples = true;
    methods.push_back({"exact-erk8-1e-12", exact, 0});
    methods.push_back({"exact-balanced", preset_settings("balanced"), 0});
    for (const auto& d : split(divs_arg)) {
      SolverSettings s;
      s.integrator = Integrator::kFixedRk4SignChange;
      methods.push_back({"fixed-rk4-dt/" + d, s, std::stod(d)});
    }
  }

  std::ofstream summary(out + "_summary.csv"), envelope(out + "_envelope.csv");
  summary << "record,pga_g,dt_s,duration_s,t95_s,tail_s,method,step_s,status,theta_max_rad,impacts_total,"
             "impacts_after_t95,impacts_tail,rms_after_t95_rad,peak_after_t95_rad,rms_tail_rad,peak_tail_rad,"
             "last_motion_s,wall_s\n";
  envelope << "record,method,t_s,peak_abs_theta_rad\n";
  const double bin = 0.1;
  PhysicsOptions physics;
  physics.tail_s = tail;
  for (const auto& [name, rec] : records) {
    const double t95 = arias_time(rec, 0.95);
    const double t_rec = rec.duration_s();
    const GroundMotion head = truncated(rec, t95);
    PhysicsOptions no_tail;
    for (const Method& m : methods) {
      SolverSettings s = m.s;
      if (m.div > 0) s.fixed_step_s = rec.dt_s() / m.div;
      Window after{t95, t_rec}, in_tail{t_rec, t_rec + tail};
      std::vector<double> env(static_cast<std::size_t>(std::ceil((t_rec + tail) / bin)) + 1, 0.0);
      double last_motion = 0;
      const HistorySink sink = [&](const HistorySample& h) {
        after.add(h.t_s, h.theta1_rad);
        in_tail.add(h.t_s, h.theta1_rad);
        const auto k = static_cast<std::size_t>(std::max(0.0, h.t_s / bin));
        if (k < env.size()) env[k] = std::max(env[k], std::abs(h.theta1_rad));
        if (h.theta1_rad != 0.0) last_motion = h.t_s;
      };
      const auto t0 = std::chrono::steady_clock::now();
      const CaseResult r = solve_case(frame, rec, physics, s, {}, sink);
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const CaseResult r_head = solve_case(frame, head, no_tail, s);
      const CaseResult r_rec = solve_case(frame, rec, no_tail, s);
      const double step = m.div > 0 ? s.fixed_step_s : 0.0;
      summary << name << ',' << fmt(rec.pga_m_s2() / kGravity_m_s2) << ',' << fmt(rec.dt_s()) << ',' << fmt(t_rec)
              << ',' << fmt(t95) << ',' << fmt(tail) << ',' << m.name << ',' << fmt(step) << ','
              << status_name(r.status) << ',' << fmt(r.theta_max_rad, 10) << ',' << r.impacts << ','
              << (r_rec.impacts - r_head.impacts) << ',' << (r.impacts - r_rec.impacts) << ','
              << fmt(after.rms(), 4) << ',' << fmt(after.peak, 4) << ',' << fmt(in_tail.rms(), 4) << ','
              << fmt(in_tail.peak, 4) << ',' << fmt(last_motion) << ',' << fmt(wall, 4) << '\n';
      for (std::size_t k = 0; k < env.size(); ++k) {
        envelope << name << ',' << m.name << ',' << fmt(static_cast<double>(k) * bin, 6) << ',' << fmt(env[k], 4)
                 << '\n';
      }
      std::cerr << name << "  " << m.name << ": status " << status_name(r.status) << ", theta_max "
                << fmt(r.theta_max_rad, 4) << ", impacts after t95 " << (r_rec.impacts - r_head.impacts)
                << ", in tail " << (r.impacts - r_rec.impacts) << ", rms after t95 " << fmt(after.rms(), 3)
                << ", rms tail " << fmt(in_tail.rms(), 3) << "\n";
    }
  }
  std::cerr << "wrote " << out << "_summary.csv and " << out << "_envelope.csv\n";
  return 0;
}
