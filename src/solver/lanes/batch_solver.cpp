// Lockstep batches of cases under one excitation (see pcrf/solver/batch_solver.hpp).
//
// Each lane holds a case: the one-case solver's state machine (case_run.hpp) over its dopri5
// integrator in lockstep (dormand_prince.hpp), which stops at every step attempt. The driver
// runs every lane up to its attempt, makes all the attempts with one vector kernel
// (attempt_kernel.hpp) and hands each lane its result. Everything else a lane does is the
// one-case solver's own code, so the answers are the same (tests/solver/batch_solver_test.cpp).
#include "pcrf/solver/batch_solver.hpp"

#include <algorithm>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "../case/case_common.hpp"
#include "../case/case_run.hpp"
#include "lane_arrays.hpp"
#include "lanes.hpp"
#include "pcrf/solver/integrator_registry.hpp"

namespace pcrf {
namespace detail::batch {
namespace {

/// A lane: the case in it, if any.
struct Lane {
  std::optional<CaseRun> run;
  std::size_t case_index = 0;
  double cpu_s = 0.0;  ///< the case's share of the batch's thread CPU time so far [s]
};

/// The batch: lanes, arrays, the kernel, the queue of cases.
class Driver final : public LaneCallbacks {
 public:
  Driver(std::span<PreparedFrame* const> frames, const Excitation& excitation, const SolverSettings& solver,
         const OutputRequest& request, const BatchOptions& options, std::vector<CaseResult>& results,
         std::vector<std::exception_ptr>& refused, BatchStats& stats);
  void run();

  void ground(int lane, double t_s, double& horizontal_m_s2, double& vertical_m_s2) override;
  bool acceleration(int lane, double t_s, double theta_rad, double omega_rad_s, double& acc_rad_s2) override;

 private:
  /// Gives lane l the next case that needs integration, up to its first attempt; false when
  /// none is left. A case that throws while it starts is refused (refused_).
  bool refill(std::size_t l);
  /// Starts case c in lane l: true when it awaits its first attempt there, false when it
  /// ended before (at rest throughout, solved one at a time, or ended at once).
  bool start(std::size_t l, std::size_t c);
  /// Runs lane l's case to its next attempt (true), or ends it and refills the lane.
  bool progress(std::size_t l);
  /// Concludes lane l's attempt from the kernel's outputs, then progress(l).
  bool take_attempt(std::size_t l);
  /// Lane l's pending attempt into the arrays.
  void put_attempt(std::size_t l);
  /// Lane l's record intervals in the arrays: its cursor's, and the one after it.
  void set_interval(std::size_t l);
  void set_next_interval(std::size_t l);
  /// Moves lane l's intervals on by one when its attempt starts at t0 in the next one.
  void follow(std::size_t l, double t0_s);
  void finish(std::size_t l);
  /// Shares the thread CPU time since the last call equally among the cases in lanes: called
  /// whenever a case enters or leaves a lane, so that each interval has one set of cases.
  void share_cpu();
  /// The thread CPU time since the last share_cpu(), for a case solved alone in that time.
  double alone_cpu_s();
  void set_block_parameters(std::size_t l, const Scene& scene);
  static bool all_rigid_rockers(std::span<PreparedFrame* const> frames);

  std::span<PreparedFrame* const> frames_;
  Excitation excitation_;
  SolverSettings solver_;
  OutputRequest request_;
  HistorySink no_history_;
  std::vector<CaseResult>& results_;
  std::vector<std::exception_ptr>& refused_;  ///< each case's: null, or why the lanes refused it
  BatchStats& stats_;
  LaneArrays arrays_;
  bool block_;
  AttemptKernel kernel_;
  std::vector<Lane> lanes_;
  std::vector<ExcitationCursor> cursors_;       ///< each lane's; the arrays hold their intervals
  std::vector<ExcitationCursor> next_cursors_;  ///< each lane's, on the interval after
  std::size_t next_case_ = 0;
  double cpu_mark_s_ = 0.0;  ///< thread CPU time at the last share_cpu() [s]
};

void Driver::ground(int lane, double t_s, double& horizontal_m_s2, double& vertical_m_s2) {
  const auto l = static_cast<std::size_t>(lane);
  const GroundAcceleration g = cursors_[l].at(t_s);
  set_interval(l);
  set_next_interval(l);
  horizontal_m_s2 = g.horizontal_m_s2, vertical_m_s2 = g.vertical_m_s2;
}

void Driver::set_interval(std::size_t l) {
  const ExcitationCursor::Interval& i = cursors_[l].interval();
  LaneArrays& a = arrays_;
  a.lo[l] = i.lo_s, a.hi[l] = i.hi_s, a.inv_dt[l] = i.inv_dt_per_s;
  a.h0[l] = i.h0, a.dh[l] = i.dh, a.v0[l] = i.v0, a.dv[l] = i.dv;
}

void Driver::set_next_interval(std::size_t l) {
  // The sample interval after the lane's; empty where there is none (the record's end, the tail).
  next_cursors_[l] = cursors_[l];
  const bool holds = next_cursors_[l].next_interval();
  const ExcitationCursor::Interval& i = next_cursors_[l].interval();
  LaneArrays& a = arrays_;
  a.nlo[l] = holds ? i.lo_s : 0.0, a.nhi[l] = holds ? i.hi_s : 0.0;
  a.nh0[l] = i.h0, a.ndh[l] = i.dh, a.nv0[l] = i.v0, a.ndv[l] = i.dv;
}

void Driver::follow(std::size_t l, double t0_s) {
  LaneArrays& a = arrays_;
  if (!(t0_s >= a.hi[l] && t0_s >= a.nlo[l] && t0_s < a.nhi[l])) return;  // where it is, or for the callbacks
  // The attempt starts in the next interval: it becomes the lane's, and the one after it the next.
  std::swap(cursors_[l], next_cursors_[l]);
  a.lo[l] = a.nlo[l], a.hi[l] = a.nhi[l];
  a.h0[l] = a.nh0[l], a.dh[l] = a.ndh[l], a.v0[l] = a.nv0[l], a.dv[l] = a.ndv[l];
  set_next_interval(l);
}

bool Driver::acceleration(int lane, double t_s, double theta_rad, double omega_rad_s, double& acc_rad_s2) {
  std::optional<CaseRun>& run = lanes_[static_cast<std::size_t>(lane)].run;
  if (!run) {  // an idle lane in a kernel call: any finite number
    acc_rad_s2 = 0.0;
    return true;
  }
  const double y[2] = {theta_rad, omega_rad_s};
  double ydot[2] = {0.0, 0.0};
  const bool ok = run->flight().rhs(t_s, y, ydot) == 0;
  acc_rad_s2 = ydot[1];
  return ok;
}

bool Driver::refill(std::size_t l) {
  while (next_case_ < frames_.size()) {
    const std::size_t c = next_case_++;
    try {
      if (start(l, c)) return true;
    } catch (const std::exception&) {
      // A case the lanes refuse (settings or an initial state no case can have, a frame its
      // set-up rejects): its own answer, the other cases go on.
      lanes_[l].run.reset();
      refused_[c] = std::current_exception();
    }
  }
  return false;
}

bool Driver::start(std::size_t l, std::size_t c) {
  Lane& lane = lanes_[l];
  PreparedFrame& frame = *frames_[c];
  share_cpu();  // up to here the lanes' cases; a case solved alone below is its own
  validate(solver_, frame.physics());
  check_initial_state(frame.scene(), frame.physics());
  ++stats_.cases;
  if (auto rest = rest_throughout(frame, excitation_, request_, no_history_)) {
    ++stats_.rest_cases;
    results_[c] = std::move(*rest);
    results_[c].cpu_time_s = alone_cpu_s();
    return false;
  }
  if (!entry_for_scene(solver_.integrator, frame.scene()).can.lockstep) {
    // A stepper without lockstep (Taylor steps): one case at a time, the checks and the
    // rest scan above already made.
    ++stats_.scalar_cases;
    results_[c] = CaseRun(frame, excitation_, solver_, request_, no_history_).run();
    results_[c].cpu_time_s = alone_cpu_s();
    return false;
  }
  lane.run.emplace(frame, excitation_, solver_, request_, no_history_, true);
  lane.case_index = c;
  lane.cpu_s = 0.0;
  set_block_parameters(l, frame.scene());
  lane.run->begin();
  if (lane.run->progress()) return true;
  finish(l);
  return false;
}

bool Driver::progress(std::size_t l) {
  if (lanes_[l].run->progress()) return true;
  finish(l);
  return refill(l);
}

bool Driver::take_attempt(std::size_t l) {
  const LaneArrays& a = arrays_;
  Dopri5Attempt& attempt = lanes_[l].run->lockstep()->attempt();
  attempt.out.y1[0] = a.theta1[l], attempt.out.y1[1] = a.omega1[l];
  attempt.out.k7[0] = a.k7_theta[l], attempt.out.k7[1] = a.k7_omega[l];
  attempt.out.err = a.err[l];
  for (std::size_t j = 0; j < 5; ++j)
    for (std::size_t i = 0; i < 2; ++i) attempt.out.cont[j][i] = a.cont[j][i][l];
  attempt.ok = a.ok[l] != 0.0;
  attempt.evals = static_cast<long>(a.evals[l]);
  ++(attempt.ok && attempt.out.err <= 1.0 ? stats_.accepted : stats_.rejected);
  DormandPrinceIntegrator& integrator = *lanes_[l].run->lockstep();
  integrator.take_attempt();
  // Most steps hold nothing for the case: the integrator goes on to its next attempt alone.
  if (integrator.continue_alone()) return true;
  return progress(l);
}

void Driver::put_attempt(std::size_t l) {
  LaneArrays& a = arrays_;
  CaseRun& run = *lanes_[l].run;
  const Dopri5Attempt& attempt = run.lockstep()->attempt();
  follow(l, attempt.t0);
  a.t0[l] = attempt.t0, a.h[l] = attempt.h;
  a.theta0[l] = attempt.y0[0], a.omega0[l] = attempt.y0[1];
  a.k1_theta[l] = attempt.k1[0], a.k1_omega[l] = attempt.k1[1];
  a.side[l] = run.flight().side;
}

void Driver::finish(std::size_t l) {
  Lane& lane = lanes_[l];
  CaseResult& result = results_[lane.case_index];
  result = lane.run->end();
  share_cpu();
  result.cpu_time_s = lane.cpu_s;
  const DormandPrinceIntegrator::Tally& tally = lane.run->lockstep()->tally();
  stats_.root_searches += tally.root_searches;
  stats_.events += tally.roots;
  stats_.flights += result.counts.reinits + (result.counts.rhs_evals > 0 ? 1 : 0);
  lane.run.reset();
}

void Driver::share_cpu() {
  const double now_s = thread_cpu_s();
  const auto busy = std::count_if(lanes_.begin(), lanes_.end(), [](const Lane& lane) { return lane.run.has_value(); });
  if (busy > 0) {
    const double share_s = (now_s - cpu_mark_s_) / static_cast<double>(busy);
    for (Lane& lane : lanes_)
      if (lane.run) lane.cpu_s += share_s;
  }
  cpu_mark_s_ = now_s;
}

double Driver::alone_cpu_s() {
  const double now_s = thread_cpu_s();
  const double spent_s = now_s - cpu_mark_s_;
  cpu_mark_s_ = now_s;
  return spent_s;
}

bool Driver::all_rigid_rockers(std::span<PreparedFrame* const> frames) {
  return std::all_of(frames.begin(), frames.end(),
                     [](PreparedFrame* f) { return f->scene().rocker_coefficients().has_value(); });
}

int capacity_for(int lanes, int register_lanes) {
  return (lanes + register_lanes - 1) / register_lanes * register_lanes;
}

AttemptKernel kernel_of(const KernelSet& set, const std::string& trig) {
  if (trig.empty()) return set.exact_trig;
  if (trig == "scalar") return set.scalar_trig;
  if (trig == "xsimd") return set.xsimd_trig;
  if (trig == "sleef") {
    if (set.sleef_trig == nullptr) throw std::invalid_argument("batch trig 'sleef': not built with SLEEF");
    return set.sleef_trig;
  }
  throw std::invalid_argument("unknown batch trig '" + trig + "' (expected scalar, sleef or xsimd, or none)");
}

/// What BatchStats::trig says.
std::string trig_label(const KernelSet& set, const std::string& trig) {
  if (trig.empty()) return set.register_lanes == 1 ? "exact" : "exact vector";
  return trig == "scalar" || set.register_lanes == 1 ? "exact lane by lane" : trig;
}

Driver::Driver(std::span<PreparedFrame* const> frames, const Excitation& excitation, const SolverSettings& solver,
               const OutputRequest& request, const BatchOptions& options, std::vector<CaseResult>& results,
               std::vector<std::exception_ptr>& refused, BatchStats& stats)
    : frames_(frames),
      excitation_(excitation),
      solver_(solver),
      request_(request),
      results_(results),
      refused_(refused),
      stats_(stats),
      arrays_(capacity_for(options.lanes, choose_kernels(options.lanes, options.kernels).register_lanes)),
      block_(all_rigid_rockers(frames)) {
  const KernelSet set = choose_kernels(options.lanes, options.kernels);
  kernel_ = kernel_of(set, options.trig);
  stats_.kernels = set.name;
  stats_.trig = trig_label(set, options.trig);
  stats_.lanes = arrays_.capacity();
  arrays_.rtol = solver.rtol;
  arrays_.atol_theta = solver.atol_theta_rad;
  arrays_.atol_omega = solver.atol_omega_rad_s;
  lanes_.resize(static_cast<std::size_t>(arrays_.capacity()));
  cursors_.assign(static_cast<std::size_t>(arrays_.capacity()), ExcitationCursor(excitation_));
  next_cursors_ = cursors_;
}

void Driver::set_block_parameters(std::size_t l, const Scene& scene) {
  const std::optional<RockerCoefficients> rocker = scene.rocker_coefficients();
  if (!rocker) return;
  arrays_.alpha[l] = rocker->slenderness_rad;
  arrays_.moment_over_inertia[l] = rocker->moment_over_inertia_per_m;
  arrays_.gravity[l] = rocker->gravity_m_s2;
}

void Driver::run() {
  cpu_mark_s_ = thread_cpu_s();
  // Every lane up to its first attempt.
  for (std::size_t l = 0; l < lanes_.size(); ++l)
    if (refill(l)) put_attempt(l);
  for (;;) {
    int pending = 0;
    for (const Lane& lane : lanes_) pending += lane.run ? 1 : 0;
    if (pending == 0) return;
    kernel_(arrays_, *this, block_);
    ++stats_.kernel_calls;
    stats_.busy_lane_attempts += pending;
    for (std::size_t l = 0; l < lanes_.size(); ++l)
      if (lanes_[l].run && take_attempt(l)) put_attempt(l);
  }
}

}  // namespace
}  // namespace detail::batch

bool batch_integrates(const SolverSettings& solver) {
  return registry_entry(solver.integrator).can.in_lanes && !solver.verdict_check;
}

namespace detail {

std::vector<CaseResult> solve_in_lanes(std::span<PreparedFrame* const> frames, const Excitation& excitation,
                                       const SolverSettings& solver, const OutputRequest& request,
                                       const BatchOptions& options, std::vector<std::exception_ptr>& refused,
                                       BatchStats* stats) {
  if (options.lanes < 1) throw std::invalid_argument("batch lanes: must be at least 1, got " + std::to_string(options.lanes));
  std::vector<CaseResult> results(frames.size());
  refused.assign(frames.size(), nullptr);
  BatchStats local;
  BatchStats& s = stats != nullptr ? *stats : local;
  s = {};
  if (!batch_integrates(solver)) {
    s.scalar_cases = static_cast<long>(frames.size());
    for (std::size_t i = 0; i < frames.size(); ++i) {
      try {
        results[i] = solve_case(*frames[i], excitation, solver, request);
      } catch (const std::exception&) {
        refused[i] = std::current_exception();
      }
    }
    return results;
  }
  batch::Driver(frames, excitation, solver, request, options, results, refused, s).run();
  return results;
}

}  // namespace detail

std::vector<CaseResult> solve_batch(std::span<PreparedFrame* const> frames, const Excitation& excitation,
                                    const SolverSettings& solver, const OutputRequest& request,
                                    const BatchOptions& options, BatchStats* stats) {
  std::vector<std::exception_ptr> refused;
  std::vector<CaseResult> results = detail::solve_in_lanes(frames, excitation, solver, request, options, refused, stats);
  for (const std::exception_ptr& why : refused)
    if (why) std::rethrow_exception(why);
  return results;
}

}  // namespace pcrf
