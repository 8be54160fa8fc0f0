/// \file case_common.hpp
/// \brief Pieces shared by the event-locating solver and the fixed-step contender:
/// scanning the record while the frame rests, and the parts of the result record that
/// do not depend on the integration. Private to the solver.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <string>

#include "pcrf/thread_cpu.hpp"
#include "pcrf/excitation/excitation.hpp"
#include "pcrf/metrics/case_result.hpp"
#include "pcrf/model/scene.hpp"
#include "pcrf/record/ground_motion.hpp"
#include "pcrf/solver/rocking_solver.hpp"

namespace pcrf::detail {

/// First time ≥ t_from at which |ü_g| exceeds `threshold_m_s2`, exact within the linear
/// interpolation of the record; NaN when it never does before `t_end`.
double first_exceedance(const GroundMotion& rec, double t_from, double t_end, double threshold_m_s2);

/// First time ≥ t_from at which the net force at rest opens the joints, i.e. the frame at
/// rest stops being held closed (Scene::holds_closed fails): |ü_h| exceeds the
/// uplift threshold at that instant's ü_v. Exact within the linear interpolation of the
/// components; NaN when it never happens before `t_end`. Without a vertical component it is
/// first_exceedance of the horizontal at the constant threshold.
double first_opening(const Excitation& excitation, const Scene& scene, double t_from, double t_end);

/// First time in [0, t_end] at which g + ü_v ≤ 0, the ground falling at least as fast as
/// gravity (docs/vertical_excitation.md), exact within the linear interpolation of the
/// vertical component; NaN when it never does (always without a vertical component).
double free_fall_time(const Excitation& excitation, double gravity_m_s2, double t_end);

/// When and why a case's simulated time ends: the end of the record plus the tail (an
/// until-rest tail: plus max_tail_s at most), or the ground's free fall if that comes first.
struct CaseEnd {
  CaseEnd(const Excitation& excitation, double gravity_m_s2, const PhysicsOptions& physics);
  double t_end_s;   ///< [s]
  bool free_fall;   ///< t_end_s is the free fall's start
  bool until_rest;  ///< the tail ends when the frame rests after the record
  double record_end_s;
  /// When a case whose frame is at rest at `t_s` and is not opened again ends: with an
  /// until-rest tail as soon as the record is over, else at t_end_s.
  double rest_end_s(double t_s) const { return until_rest ? std::min(std::max(t_s, record_end_s), t_end_s) : t_end_s; }
  /// The status of a case that reached t_end_s without collapsing (`reached`: at rest or
  /// still rocking), and its message.
  CaseStatus status(CaseStatus reached) const { return free_fall ? CaseStatus::kGroundFreeFall : reached; }
  std::string message() const;
};

/// First sample i with |a_i| ≥ λ_g·g, as i·dt (the paper's t_RI) [s]; NaN when none.
double paper_trigger_time(const GroundMotion& rec, double lambda_g);

/// A result record with the frame's properties and the at-rest values filled in (the
/// paper's trigger from the horizontal component: its criterion knows no vertical).
CaseResult initial_result(const Scene& scene, const Excitation& excitation, double restitution,
                          bool omega_peak);

/// Peak strains from the peak rotation (every |θ₁| up to it has been visited).
void set_peak_strains(const Scene& scene, CaseResult& result);

// What the result records at a case's events, for both case loops (the case machine,
// case_run.cpp, which every stepper and the CPU lanes run, and the fixed-step contender's): a
// metric set at an event is one line here (docs/developer.md, "What a new thing costs"). At
// the case's end: set_peak_strains.

/// The frame lifts off at t [s] (its first lift-off is t_uplift_s).
inline void note_uplift(CaseResult& result, double t) {
  if (std::isnan(result.t_uplift_s)) result.t_uplift_s = t;
}
/// An impact at t [s].
inline void note_impact(CaseResult& result, double /*t*/) { ++result.impacts; }

/// Builds a case's history rows and hands them to the sink in strictly increasing time:
/// rows added at the same instant (an impact and the restart after it, an impact and the
/// return to rest) become one row, whose `omega1_after_rad_s` is the last velocity given
/// and whose events are the union. A row is held until a later one arrives or end().
class HistoryRows {
 public:
  HistoryRows(const HistorySink& sink, const Scene& scene, const Excitation& excitation)
      : sink_(sink), scene_(scene), excitation_(excitation) {}
  bool wanted() const { return static_cast<bool>(sink_); }
  /// The state (θ₁, θ̇₁) on `side` at t, with `events` (HistoryEvent bits).
  void add(double t, double theta, double omega, int side, std::uint32_t events = kEventNone);
  /// The last row (at the case's end, with kEventEnd among `events`), then hands over
  /// every held row.
  void end(double t, double theta, double omega, int side, std::uint32_t events);

 private:
  const HistorySink& sink_;
  const Scene& scene_;
  Excitation excitation_;
  /// Hands over the held row.
  void flush();

  bool held_ = false;
  HistorySample row_{};
};

/// Where a case stops on its own: the |θ₁| at which a tendon fractures and the one at which
/// the frame is declared overturned, found once per case.
struct StopAngles {
  double fracture_rad;  ///< 0: a tendon is already broken at rest; +∞: none fractures
  double overturn_rad;

  double stop_rad() const { return std::min(fracture_rad, overturn_rad); }
  bool broken_at_rest() const { return fracture_rad <= 0.0; }
  /// Status and message of a case that reached stop_rad().
  CaseStatus status() const;
  const char* message() const;
};
StopAngles stop_angles(const Scene& scene, const PhysicsOptions& physics);
inline constexpr const char* kBrokenAtRestMessage = "the initial tendon strain already reaches the fracture strain";

/// Branch a frame leaving rest enters: ü_g > 0 pushes it into θ₁ < 0.
/// Seconds of the steady clock since `start` (the wall-time limit).
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// CPU time of the calling thread [s]: what a case's cpu_time_s counts (pcrf/thread_cpu.hpp).
using ::pcrf::thread_cpu_s;

inline int uplift_side(double ground_accel_m_s2) { return ground_accel_m_s2 > 0.0 ? -1 : +1; }
/// Branch of a displaced initial state: the side of θ₁, or of −θ̇₁ when θ₁ = 0.
inline int initial_side(double theta_rad, double omega_rad_s) {
  return theta_rad < 0.0 || (theta_rad == 0.0 && omega_rad_s < 0.0) ? -1 : +1;
}

/// Checks settings shared by every integrator. \throws std::invalid_argument
void validate(const SolverSettings& s, const PhysicsOptions& p);

}  // namespace pcrf::detail
