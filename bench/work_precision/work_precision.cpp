// pcrf_work_precision: the work-precision study of issue 4.
//
// For every case (frame × ground motion) it computes a reference at the tightest tolerance
// that converges (ARKODE ERK8, rtol 1e-14 by default) and shows that it converged (ERK8 one
// decade looser, and CVODE Adams, must agree with it), measures the case's conditioning
// (the reference again with the record scaled by 1 + 1e-9), and the floor (one evaluation of
// the right-hand side per record sample). Then it runs every contender — CVODE Adams and
// BDF, ARKODE ERK5 (Dormand–Prince) and ERK8 (Fehlberg) over a tolerance sweep with
// stop_at_samples on and off, the fixed-step RK4 sign-change scheme at the record's dt and
// finer, and the three named presets — and writes one CSV row per case × setting: errors
// against the reference (θ_max, t_θmax, ω_max, uplift time, impacts, status) and cost
// (median wall time of N repeats, steps, RHS evaluations, cost as a multiple of the floor).
// A summary per setting goes to stdout. See docs/work_precision.md.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "pcrf/model/eom_table.hpp"
#include "pcrf/model/equation_of_motion.hpp"
#include "pcrf/model/frame.hpp"
#include "pcrf/record/record_readers.hpp"
#include "pcrf/record/synthetic.hpp"
#include "pcrf/solver/integrator_registry.hpp"
#include "pcrf/solver/rocking_solver.hpp"
#include "pcrf/solver/settings.hpp"

namespace fs = std::filesystem;
using namespace pcrf;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

double median(std::vector<double> v) {
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
double quantile(std::vector<double> v, double q) {
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const double pos = q * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  const double f = pos - static_cast<double>(lo);
  if (std::isinf(v[hi]) || std::isinf(v[lo])) return f > 0 ? v[hi] : v[lo];
  return v[lo] + f * (v[hi] - v[lo]);
}

std::vector<std::string> split(const std::string& s, char sep = ',') {
  std::vector<std::string> out;
  if (s == "none") return out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, sep)) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}
std::vector<double> split_doubles(const std::string& s) {
  std::vector<double> v;
  for (const auto& x : split(s)) v.push_back(std::stod(x));
  return v;
}

std::string fmt(double v, int digits = 6) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

// ---- frames ------------------------------------------------------------------
struct FrameVariant {
  std::string name;
  FrameParameters p;
};

std::vector<FrameVariant> all_frames() {
  std::vector<FrameVariant> v;
  const FrameParameters basic;
  v.push_back({"basic", basic});
  auto with = [&](const char* name, auto change) {
    FrameParameters p = basic;
    change(p);
    v.push_back({name, p});
  };
  with("slender", [](FrameParameters& p) { p.tan_alpha = 0.1; });
  with("stocky", [](FrameParameters& p) { p.tan_alpha = 0.35; });
  with("light_beam", [](FrameParameters& p) { p.kappa = 0.5; });
  with("heavy_beam", [](FrameParameters& p) { p.kappa = 5.0; });
  with("weak_prestress", [](FrameParameters& p) {
    p.pi_sigma_b *= 0.2;
    p.pi_sigma_c *= 0.2;
  });
  with("strong_prestress", [](FrameParameters& p) {
    p.pi_sigma_b *= 3.0;
    p.pi_sigma_c *= 3.0;
  });
  return v;
}

// ---- ground motions ------------------------------------------------------------
struct BaseMotion {
  std::string id;     ///< "ER1", "stoch1", ...
  bool real = false;  ///< a paper record (scaled by a factor) or synthetic (scaled to the frame)
  GroundMotion motion;
  double level = 0;   ///< synthetic: PGA as a multiple of the frame's uplift threshold
};

std::vector<BaseMotion> paper_records(const fs::path& dir, const std::vector<std::string>& only) {
  std::vector<BaseMotion> out;
  const fs::path index = dir / "paper" / "INDEX.csv";
  std::ifstream in(index);
  if (!in) return out;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto f = split(line);
    if (f.size() < 2) continue;
    if (!only.empty() && std::find(only.begin(), only.end(), f[0]) == only.end()) continue;
    out.push_back({f[0], true, read_at2(dir / f[1]), 0.0});
  }
  return out;
}

std::vector<BaseMotion> synthetic_motions(bool quick) {
  std::vector<BaseMotion> out;
  auto stochastic = [](std::uint64_t seed, double duration, double dt) {
    StochasticSpec s;
    s.seed = seed;
    s.pga_g = 1.0;  // rescaled per frame
    s.duration_s = duration;
    s.dt_s = dt;
    return make_stochastic(s);
  };
  SinePulseSpec sp;
  sp.amplitude_g = 1.0;
  sp.period_s = 0.5;
  sp.cycles = 3;
  sp.duration_s = 8.0;
  sp.dt_s = 0.005;
  out.push_back({"stoch1", false, stochastic(1, 20.0, 0.01), 2.0});
  out.push_back({"sine3", false, make_sine_pulse_train(sp), 1.5});
  if (!quick) {
    out.push_back({"stoch2", false, stochastic(2, 20.0, 0.01), 2.0});
    out.push_back({"stoch3long", false, stochastic(3, 40.0, 0.005), 3.0});
  }
  return out;
}

// ---- cases -------------------------------------------------------------------------
struct Case {
  std::string id, frame_name, motion_id;
  double scale = 1.0;       ///< factor applied to the base motion
  double nominal = 1.0;     ///< ×2, ×3 (real) or the multiple of the threshold (synthetic)
  Frame frame{};
  GroundMotion motion{"none", 1.0, {0.0}};
  double threshold_g = 0;   ///< the frame's physical uplift threshold [g]
};

// ---- contenders: the solver settings compared -----------------------------------------
struct Contender {
  std::string label;   ///< unique, e.g. "arkode-erk5/stop rtol=1e-06"
  std::string family;  ///< one line in the diagram, e.g. "arkode-erk5/stop"
  double knob = kNaN;  ///< rtol, or the fixed step divisor
  SolverSettings s;
};

SolverSettings tolerance(Integrator integ, double rtol, bool stop, double theta_scale, double omega_scale,
                         double time_limit) {
  SolverSettings s;
  s.integrator = integ;
  s.rtol = rtol;
  s.atol_theta_rad = theta_scale * rtol;
  s.atol_omega_rad_s = omega_scale * rtol;
  s.stop_at_samples = stop;
  s.wall_time_limit_s = time_limit;
  return s;
}

// ---- running and timing --------------------------------------------------------------
struct Timed {
  CaseResult r;
  double wall_median_s = kNaN, wall_min_s = kNaN;
};

Timed run_timed(const Case& c, const GroundMotion& motion, const SolverSettings& s, int repeats) {
  Timed t;
  std::vector<double> walls;
  const OutputRequest request{};
  for (int k = 0; k < std::max(1, repeats); ++k) {
    const auto t0 = Clock::now();
    CaseResult r = solve_case(c.frame, motion, PhysicsOptions{}, s, request);
    walls.push_back(seconds_since(t0));
    if (k == 0) t.r = std::move(r);
    // A setting that hits its time limit once is not repeated (it would only burn time).
    if (t.r.status == CaseStatus::kTimeLimit) break;
  }
  t.wall_median_s = median(walls);
  t.wall_min_s = *std::min_element(walls.begin(), walls.end());
  return t;
}

/// Floor: one right-hand-side evaluation (record interpolation + θ̈₁) per record sample,
/// median over `passes` passes [s]. `tabulated`: through EomTable (what the SUNDIALS
/// flights evaluate since the tabulation commit), else EquationOfMotion::acceleration
/// (exact four-bar closure; what the fixed-step scheme evaluates).
double rhs_floor_s(const Case& c, int passes, bool tabulated) {
  const EquationOfMotion eom(c.frame);
  const EomTable table(eom);
  const auto n = c.motion.size();
  const double dt = c.motion.dt_s();
  std::vector<double> times;
  volatile double sink = 0;
  for (int p = 0; p < passes; ++p) {
    const auto t0 = Clock::now();
    double sum = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double t = (static_cast<double>(i) + 0.37) * dt;
      const double theta = -0.01 - 1e-6 * static_cast<double>(i % 97);
      double acc = 0;
      if (tabulated) {
        table.acceleration(theta, 0.3, c.motion.accel_m_s2(t), -1, acc);
      } else {
        eom.acceleration(theta, 0.3, c.motion.accel_m_s2(t), -1, acc);
      }
      sum += acc;
    }
    sink = sink + sum;
    times.push_back(seconds_since(t0));
  }
  return median(times);
}

double rel_err(double x, double ref) {
  if (std::isnan(x) && std::isnan(ref)) return 0.0;
  if (std::isnan(x) || std::isnan(ref)) return kInf;
  if (ref == 0.0) return x == 0.0 ? 0.0 : kInf;
  return std::abs(x - ref) / std::abs(ref);
}
double abs_err(double x, double ref) {
  if (std::isnan(x) && std::isnan(ref)) return 0.0;
  if (std::isnan(x) || std::isnan(ref)) return kInf;
  return std::abs(x - ref);
}
bool failed(CaseStatus s) { return s == CaseStatus::kSolverFailure || s == CaseStatus::kTimeLimit; }

struct Reference {
  CaseResult ref, check, cross, perturbed;
  double ref_rtol = kNaN, check_rtol = kNaN;
  double floor_s = kNaN, floor_table_s = kNaN;
  double wall_ref_s = kNaN;
};

struct Row {
  std::size_t case_index;
  const Contender* contender;
  Timed t;
};

struct Options {
  bool quick = false;
  std::string frames, records, scales = "2,3", rtols, integrators = "dopri5,arkode-erk5,arkode-erk8,cvode-adams,cvode-bdf";
  std::string stops = "on,off", fixed_divs;
  int repeats = 3;
  bool no_real = false, no_synthetic = false, atol_study = false, no_presets = false;
  double theta_scale = 1e-2, omega_scale = 1e-1;
  double ref_rtol = 1e-14;
  double time_limit_s = 20.0;
  std::string out = "work_precision";
  std::string records_dir;
};

/// What the run produced: the reference of every case and one row per case × contender.
struct Results {
  std::vector<Reference> refs;
  std::vector<Row> rows;
};

void add_options(CLI::App& app, Options& o) {
  app.add_flag("--quick", o.quick, "a short run: basic frame, ER1/ER3/ER7/ER11, 2 synthetic motions, 5 tolerances");
  app.add_option("--frames", o.frames,
                 "comma list of frames: basic, slender, stocky, light_beam, heavy_beam, weak_prestress, "
                 "strong_prestress (default all; --quick: basic)");
  app.add_option("--records", o.records, "comma list of paper record ids (ER1,...,ER20; default all 13)");
  app.add_option("--scales", o.scales, "scale factors of the paper records (times threshold/threshold_basic)")
      ->capture_default_str();
  app.add_option("--rtols", o.rtols, "comma list of rtol (default 1e-3 ... 1e-11, every decade)");
  app.add_option("--integrators", o.integrators, "comma list of integrator contenders: dopri5 (the engine's own) and the SUNDIALS ones (none: no contender)")->capture_default_str();
  app.add_option("--stop-at-samples", o.stops, "on, off or on,off")->capture_default_str();
  app.add_option("--fixed-divs", o.fixed_divs, "fixed-rk4 step = dt/div for each div (default 1,2,4,10,100; none: no fixed-step run)");
  app.add_option("--repeats", o.repeats, "timed repeats per setting (median reported)")->capture_default_str();
  app.add_flag("--no-real", o.no_real, "skip the paper records");
  app.add_flag("--no-synthetic", o.no_synthetic, "skip the synthetic motions");
  app.add_flag("--no-presets", o.no_presets, "do not run the named presets");
  app.add_flag("--atol-study", o.atol_study,
               "also sweep the atol scale (atol_theta = s*rtol, atol_omega = 10*s*rtol, s = 1, 1e-2, 1e-4) for ERK5 "
               "and ERK8 with stop_at_samples on");
  app.add_option("--theta-scale", o.theta_scale, "atol_theta = theta_scale * rtol [rad]")->capture_default_str();
  app.add_option("--omega-scale", o.omega_scale, "atol_omega = omega_scale * rtol [rad/s]")->capture_default_str();
  app.add_option("--ref-rtol", o.ref_rtol, "rtol of the reference (ERK8); checked against 10x and CVODE Adams 1e-12")
      ->capture_default_str();
  app.add_option("--time-limit", o.time_limit_s, "wall-time limit per solve [s]")->capture_default_str();
  app.add_option("--out", o.out, "output prefix: OUT_runs.csv, OUT_cases.csv")->capture_default_str();
  app.add_option("--records-dir", o.records_dir, "shared records folder (default $PCRF_RECORDS_DIR or ../shared/records)");

}

/// The cases: every selected frame × motion (paper records at each scale, synthetic motions
/// at multiples of the frame's threshold). \throws std::invalid_argument for a bad selection.
std::vector<Case> make_cases(Options& o) {
  if (o.rtols.empty()) o.rtols = o.quick ? "1e-3,1e-5,1e-7,1e-9,1e-11" : "1e-3,1e-4,1e-5,1e-6,1e-7,1e-8,1e-9,1e-10,1e-11";
  if (o.fixed_divs.empty()) o.fixed_divs = o.quick ? "1,10" : "1,2,4,10,100";
  if (o.frames.empty()) o.frames = o.quick ? "basic" : "";
  std::vector<std::string> record_ids = split(o.records);
  if (o.quick && record_ids.empty()) record_ids = {"ER1", "ER3", "ER7", "ER11"};

  std::vector<FrameVariant> frames;
  const auto wanted_frames = split(o.frames);
  for (const auto& f : all_frames()) {
    if (wanted_frames.empty() || std::find(wanted_frames.begin(), wanted_frames.end(), f.name) != wanted_frames.end())
      frames.push_back(f);
  }
  if (frames.empty()) throw std::invalid_argument("no frame selected");

  fs::path records_dir = o.records_dir;
  if (records_dir.empty()) {
    const char* env = std::getenv("PCRF_RECORDS_DIR");
    records_dir = env ? fs::path(env) : fs::path(PCRF_DEFAULT_RECORDS_DIR);
  }
  std::vector<BaseMotion> motions;
  if (!o.no_real) {
    if (!fs::exists(records_dir / "paper" / "INDEX.csv")) {
      std::cerr << "note: " << (records_dir / "paper" / "INDEX.csv").string()
                << " not found: the paper records are skipped (synthetic motions only)\n";
    } else {
      try {
        motions = paper_records(records_dir, record_ids);
      } catch (const std::exception& e) {
        std::cerr << "note: cannot read the paper records (" << e.what() << "): skipped\n";
        motions.clear();
      }
    }
  }
  if (!o.no_synthetic) {
    for (auto& m : synthetic_motions(o.quick)) motions.push_back(std::move(m));
  }

  const double thr_basic = EquationOfMotion(basic_frame()).uplift_threshold_m_s2() / kGravity_m_s2;
  std::vector<Case> cases;
  for (const auto& fv : frames) {
    const Frame frame = make_frame(fv.p);
    const double thr = EquationOfMotion(frame).uplift_threshold_m_s2() / kGravity_m_s2;
    for (const auto& m : motions) {
      if (m.real) {
        for (const double f : split_doubles(o.scales)) {
          Case c;
          c.frame_name = fv.name;
          c.motion_id = m.id;
          c.nominal = f;
          c.scale = f * thr / thr_basic;  // same intensity relative to the frame's threshold
          c.frame = frame;
          c.motion = m.motion.scaled(c.scale);
          c.threshold_g = thr;
          c.id = fv.name + ":" + m.id + "x" + fmt(f, 3);
          cases.push_back(std::move(c));
        }
      } else {
        Case c;
        c.frame_name = fv.name;
        c.motion_id = m.id;
        c.nominal = m.level;
        c.scale = m.level * thr * kGravity_m_s2 / m.motion.pga_m_s2();
        c.frame = frame;
        c.motion = m.motion.scaled(c.scale);
        c.threshold_g = thr;
        c.id = fv.name + ":" + m.id + "@" + fmt(m.level, 3) + "thr";
        cases.push_back(std::move(c));
      }
    }
  }

  return cases;
}

/// The solver settings compared: SUNDIALS tolerance sweeps, the atol study, fixed-step RK4
/// and the presets. \throws std::invalid_argument for an unknown integrator.
std::vector<Contender> make_contenders(const Options& o) {
  std::vector<Contender> settings;
  const auto rtols = split_doubles(o.rtols);
  for (const auto& name : split(o.integrators)) {
    // Any stepper of the registry (the fixed-step contender has no tolerance: its own sweep below).
    const Integrator id = parse_integrator(name);
    if (registry_entry(id).make == nullptr) throw std::invalid_argument("integrator " + name + ": no tolerance to sweep");
    for (const auto& stop : split(o.stops)) {
      const bool on = stop == "on";
      const std::string family = name + (on ? "/stop" : "/nostop");
      for (const double rt : rtols) {
        settings.push_back({family + " rtol=" + fmt(rt, 2), family, rt,
                            tolerance(id, rt, on, o.theta_scale, o.omega_scale, o.time_limit_s)});
      }
    }
  }
  if (o.atol_study) {
    for (const auto& [name, integ] : {std::pair{"arkode-erk5", Integrator::kArkodeErk5},
                                      std::pair{"arkode-erk8", Integrator::kArkodeErk8}}) {
      for (const double sc : {1.0, 1e-2, 1e-4}) {
        if (sc == o.theta_scale) continue;  // already in the main sweep
        const std::string family = std::string(name) + "/stop/atol=" + fmt(sc, 1) + "rtol";
        for (const double rt : {1e-4, 1e-6, 1e-8, 1e-10}) {
          settings.push_back({family + " rtol=" + fmt(rt, 2), family, rt,
                              tolerance(integ, rt, true, sc, 10.0 * sc, o.time_limit_s)});
        }
      }
    }
  }
  for (const double div : split_doubles(o.fixed_divs)) {
    SolverSettings s;
    s.integrator = Integrator::kFixedRk4SignChange;
    s.fixed_step_s = -div;  // resolved per case: dt/div (negative marks "relative")
    s.wall_time_limit_s = o.time_limit_s;
    settings.push_back({"fixed-rk4 dt/" + fmt(div, 4), "fixed-rk4", div, s});
  }
  if (!o.no_presets) {
    for (const auto& p : preset_names()) {
      SolverSettings s = preset_settings(p);
      s.wall_time_limit_s = o.time_limit_s;
      settings.push_back({"preset:" + p, "preset", kNaN, s});
    }
    // The presets that dopri5's replaced (commit 3de1910: ARKODE ERK5 with stops), so that
    // the study shows what the change bought at the accuracy each had.
    for (const auto& [name, rtol, atol_theta, atol_omega] :
         {std::tuple{"fast", 1e-4, 1e-6, 1e-5}, std::tuple{"balanced", 1e-6, 1e-10, 1e-9}}) {
      SolverSettings s = preset_settings("reference");
      s.integrator = Integrator::kArkodeErk5;
      s.rtol = rtol;
      s.atol_theta_rad = atol_theta;
      s.atol_omega_rad_s = atol_omega;
      s.wall_time_limit_s = o.time_limit_s;
      settings.push_back({std::string("preset-before:") + name, "preset-before", kNaN, s});
    }
  }

  return settings;
}

/// Runs the reference and every contender on every case; writes OUT_runs.csv, OUT_cases.csv.
Results run_all(const Options& o, const std::vector<Case>& cases, const std::vector<Contender>& settings,
                Clock::time_point start) {
  const std::string runs_path = o.out + "_runs.csv", cases_path = o.out + "_cases.csv";
  std::ofstream runs(runs_path), case_csv(cases_path);
  if (!runs || !case_csv) throw std::runtime_error("cannot write " + runs_path + " / " + cases_path);
  runs << "case,frame,motion,nominal,scale,family,setting,integrator,knob,rtol,atol_theta,atol_omega,stop_at_samples,"
          "fixed_step_s,status,theta_max_rad,t_theta_max_s,omega_max_rad_s,t_uplift_s,impacts,steps,rhs_evals,"
          "wall_median_s,wall_min_s,floor_s,cost_multiple,theta_ref_rad,err_theta_rel,err_t_theta_s,err_omega_rel,"
          "err_uplift_s,d_impacts,status_match,cond_theta_rel,message\n";
  case_csv << "case,frame,motion,nominal,scale,threshold_g,pga_g,dt_s,n_samples,duration_s,ref_rtol,ref_status,"
              "theta_ref_rad,t_theta_ref_s,omega_ref_rad_s,t_uplift_ref_s,impacts_ref,ref_steps,ref_rhs,ref_wall_s,"
              "check_rtol,check_theta_rel,check_t_theta_s,check_omega_rel,check_d_impacts,cross_theta_rel,"
              "cross_d_impacts,cond_theta_rel,cond_t_theta_s,cond_d_impacts,floor_s,floor_ns_per_rhs,floor_table_s,"
              "floor_table_ns_per_rhs\n";

  Results results;
  results.refs.resize(cases.size());
  auto& rows = results.rows;
  auto& refs = results.refs;
  for (std::size_t ci = 0; ci < cases.size(); ++ci) {
    const Case& c = cases[ci];
    Reference& R = refs[ci];
    // Reference at the tightest tolerance that converges.
    for (double rt = o.ref_rtol; rt <= 1e-10; rt *= 10.0) {
      const auto t0 = Clock::now();
      R.ref = solve_case(c.frame, c.motion, {}, tolerance(Integrator::kArkodeErk8, rt, true, o.theta_scale,
                                                          o.omega_scale, 10 * o.time_limit_s));
      R.wall_ref_s = seconds_since(t0);
      R.ref_rtol = rt;
      if (!failed(R.ref.status)) break;
    }
    R.check_rtol = 10.0 * R.ref_rtol;
    R.check = solve_case(c.frame, c.motion, {},
                         tolerance(Integrator::kArkodeErk8, R.check_rtol, true, o.theta_scale, o.omega_scale,
                                   10 * o.time_limit_s));
    R.cross = solve_case(c.frame, c.motion, {},
                         tolerance(Integrator::kCvodeAdams, 1e-12, true, o.theta_scale, o.omega_scale, 10 * o.time_limit_s));
    const GroundMotion perturbed = c.motion.scaled(1.0 + 1e-9);
    R.perturbed = solve_case(c.frame, perturbed, {},
                             tolerance(Integrator::kArkodeErk8, R.ref_rtol, true, o.theta_scale, o.omega_scale,
                                       10 * o.time_limit_s));
    R.floor_s = rhs_floor_s(c, 5, false);
    R.floor_table_s = rhs_floor_s(c, 5, true);
    const double cond = rel_err(R.perturbed.theta_max_rad, R.ref.theta_max_rad);
    case_csv << c.id << ',' << c.frame_name << ',' << c.motion_id << ',' << fmt(c.nominal) << ',' << fmt(c.scale, 10)
             << ',' << fmt(c.threshold_g, 8) << ',' << fmt(c.motion.pga_m_s2() / kGravity_m_s2, 6) << ','
             << fmt(c.motion.dt_s()) << ',' << c.motion.size() << ',' << fmt(c.motion.duration_s()) << ','
             << fmt(R.ref_rtol, 2) << ',' << status_name(R.ref.status) << ',' << fmt(R.ref.theta_max_rad, 17) << ','
             << fmt(R.ref.t_theta_max_s, 17) << ',' << fmt(R.ref.omega_max_rad_s, 17) << ','
             << fmt(R.ref.t_uplift_s, 17) << ',' << R.ref.impacts << ',' << R.ref.counts.steps << ','
             << R.ref.counts.rhs_evals << ',' << fmt(R.wall_ref_s) << ',' << fmt(R.check_rtol, 2) << ','
             << fmt(rel_err(R.check.theta_max_rad, R.ref.theta_max_rad), 4) << ','
             << fmt(abs_err(R.check.t_theta_max_s, R.ref.t_theta_max_s), 4) << ','
             << fmt(rel_err(R.check.omega_max_rad_s, R.ref.omega_max_rad_s), 4) << ','
             << (R.check.impacts - R.ref.impacts) << ','
             << fmt(rel_err(R.cross.theta_max_rad, R.ref.theta_max_rad), 4) << ','
             << (R.cross.impacts - R.ref.impacts) << ',' << fmt(cond, 4) << ','
             << fmt(abs_err(R.perturbed.t_theta_max_s, R.ref.t_theta_max_s), 4) << ','
             << (R.perturbed.impacts - R.ref.impacts) << ',' << fmt(R.floor_s) << ','
             << fmt(1e9 * R.floor_s / static_cast<double>(c.motion.size()), 4) << ',' << fmt(R.floor_table_s) << ','
             << fmt(1e9 * R.floor_table_s / static_cast<double>(c.motion.size()), 4) << '\n';
    case_csv.flush();

    for (const Contender& st : settings) {
      SolverSettings s = st.s;
      if (s.integrator == Integrator::kFixedRk4SignChange) s.fixed_step_s = c.motion.dt_s() / -st.s.fixed_step_s;
      Row row{ci, &st, run_timed(c, c.motion, s, o.repeats)};
      const CaseResult& r = row.t.r;
      const CaseResult& ref = R.ref;
      runs << c.id << ',' << c.frame_name << ',' << c.motion_id << ',' << fmt(c.nominal) << ',' << fmt(c.scale, 10)
           << ',' << st.family << ',' << st.label << ',' << to_string(s.integrator) << ',' << fmt(st.knob) << ','
           << fmt(s.rtol, 3) << ',' << fmt(s.atol_theta_rad, 3) << ',' << fmt(s.atol_omega_rad_s, 3) << ','
           << (s.stop_at_samples ? 1 : 0) << ',' << fmt(s.integrator == Integrator::kFixedRk4SignChange ? s.fixed_step_s : 0.0)
           << ',' << status_name(r.status) << ',' << fmt(r.theta_max_rad, 17) << ',' << fmt(r.t_theta_max_s, 17)
           << ',' << fmt(r.omega_max_rad_s, 17) << ',' << fmt(r.t_uplift_s, 17) << ',' << r.impacts << ','
           << r.counts.steps << ',' << r.counts.rhs_evals << ',' << fmt(row.t.wall_median_s) << ','
           << fmt(row.t.wall_min_s) << ',' << fmt(R.floor_s) << ',' << fmt(row.t.wall_median_s / R.floor_s, 5) << ','
           << fmt(ref.theta_max_rad, 17) << ',' << fmt(rel_err(r.theta_max_rad, ref.theta_max_rad), 4) << ','
           << fmt(abs_err(r.t_theta_max_s, ref.t_theta_max_s), 4) << ','
           << fmt(rel_err(r.omega_max_rad_s, ref.omega_max_rad_s), 4) << ','
           << fmt(abs_err(r.t_uplift_s, ref.t_uplift_s), 4) << ',' << (r.impacts - ref.impacts) << ','
           << (r.status == ref.status ? 1 : 0) << ',' << fmt(cond, 4) << ',';
      std::string msg = r.message;
      std::replace(msg.begin(), msg.end(), ',', ';');
      std::replace(msg.begin(), msg.end(), '\n', ' ');
      runs << '"' << msg.substr(0, 120) << '"' << '\n';
      rows.push_back(std::move(row));
    }
    runs.flush();
    std::cerr << "[" << (ci + 1) << "/" << cases.size() << "] " << c.id << "  theta_ref=" << fmt(R.ref.theta_max_rad, 5)
              << " impacts=" << R.ref.impacts << " " << status_name(R.ref.status)
              << "  check=" << fmt(rel_err(R.check.theta_max_rad, R.ref.theta_max_rad), 2)
              << " cond=" << fmt(cond, 2) << "  elapsed " << fmt(seconds_since(start), 4) << " s\n";
  }

  return results;
}

/// One line per contender on stdout: errors against the reference, failures, cost.
void print_summary(const Options& o, const std::vector<Case>& cases, const std::vector<Contender>& settings,
                   const Results& results) {
  const auto& rows = results.rows;
  const auto& refs = results.refs;
  std::vector<double> floors, floors_table;
  for (const auto& R : refs) {
    floors.push_back(R.floor_s);
    floors_table.push_back(R.floor_table_s);
  }
  std::vector<double> conds, checks, crosses;
  std::size_t rocking = 0;
  for (const auto& R : refs) {
    if (R.ref.theta_max_rad > 0) {
      ++rocking;
      conds.push_back(rel_err(R.perturbed.theta_max_rad, R.ref.theta_max_rad));
      checks.push_back(rel_err(R.check.theta_max_rad, R.ref.theta_max_rad));
      crosses.push_back(rel_err(R.cross.theta_max_rad, R.ref.theta_max_rad));
    }
  }
  std::cout << "# work-precision summary: " << cases.size() << " cases (" << rocking
            << " rock in the reference), medians of " << o.repeats << " timed runs per setting\n";
  std::cout << "# reference convergence (theta_max rel. diff. to the reference), median / worst:\n"
            << "#   ERK8 one decade looser: " << fmt(median(checks), 3) << " / " << fmt(quantile(checks, 1.0), 3)
            << "   CVODE Adams 1e-12: " << fmt(median(crosses), 3) << " / " << fmt(quantile(crosses, 1.0), 3) << "\n"
            << "# conditioning (record scaled by 1+1e-9), median / worst: " << fmt(median(conds), 3) << " / "
            << fmt(quantile(conds, 1.0), 3) << "\n"
            << "# floor (one RHS per record sample) median per case: " << fmt(1e3 * median(floors), 4)
            << " ms exact EquationOfMotion, " << fmt(1e3 * median(floors_table), 4)
            << " ms tabulated (EomTable); cost multiples below are of the exact floor\n";
  std::printf("%-40s %4s %4s %4s %10s %10s %10s %10s %9s %9s %8s %10s %9s %9s\n", "setting", "n", "fail", "stat",
              "med_err", "p90_err", "worst_err", "worst>1mr", "med_dt_s", "med_dimp", "med_ms", "med_xfloor",
              "med_steps", "med_rhs");
  for (const Contender& st : settings) {
    std::vector<double> err, err_big, dt, dimp, wall, mult, steps, rhs;
    int fails = 0, mismatch = 0, n = 0;
    for (const Row& row : rows) {
      if (row.contender != &st) continue;
      const Reference& R = refs[row.case_index];
      const CaseResult& r = row.t.r;
      wall.push_back(row.t.wall_median_s);
      mult.push_back(row.t.wall_median_s / R.floor_s);
      steps.push_back(static_cast<double>(r.counts.steps));
      rhs.push_back(static_cast<double>(r.counts.rhs_evals));
      if (failed(r.status)) ++fails;
      if (r.status != R.ref.status) ++mismatch;
      if (!(R.ref.theta_max_rad > 0)) continue;
      ++n;
      const double e = failed(r.status) ? kInf : rel_err(r.theta_max_rad, R.ref.theta_max_rad);
      err.push_back(e);
      if (R.ref.theta_max_rad >= 1e-3) err_big.push_back(e);
      dt.push_back(abs_err(r.t_theta_max_s, R.ref.t_theta_max_s));
      dimp.push_back(std::abs(static_cast<double>(r.impacts - R.ref.impacts)));
    }
    std::printf("%-40s %4d %4d %4d %10.3g %10.3g %10.3g %10.3g %9.3g %9.3g %8.3g %10.3g %9.3g %9.3g\n",
                st.label.c_str(), n, fails, mismatch, median(err), quantile(err, 0.9), quantile(err, 1.0),
                quantile(err_big, 1.0), median(dt), median(dimp), 1e3 * median(wall), median(mult), median(steps),
                median(rhs));
  }
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  CLI::App app{"Work-precision study of the rocking solver (issue 4). Writes OUT_runs.csv (one row per "
               "case x setting), OUT_cases.csv (one row per case: reference, convergence check, "
               "conditioning, floor) and a summary table on stdout."};
  add_options(app, o);
  CLI11_PARSE(app, argc, argv);
  try {
    const std::vector<Case> cases = make_cases(o);
    const std::vector<Contender> settings = make_contenders(o);
    std::cerr << "pcrf_work_precision: " << cases.size() << " cases x " << settings.size() << " settings, "
              << o.repeats << " timed repeats each\n";
    if (cases.empty()) {
      std::cerr << "no case to run\n";
      return 0;
    }
    const auto start = Clock::now();
    const Results results = run_all(o, cases, settings, start);
    print_summary(o, cases, settings, results);
    std::cerr << "wrote " << o.out << "_runs.csv and " << o.out << "_cases.csv in " << fmt(seconds_since(start), 4)
              << " s\n";
  } catch (const std::invalid_argument& e) {
    std::cerr << "pcrf_work_precision: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "pcrf_work_precision: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
