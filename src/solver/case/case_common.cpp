// Record scanning at rest and record-independent parts of the result record.
#include "case_common.hpp"

#include "pcrf/user_error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "pcrf/units.hpp"

namespace pcrf::detail {
namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}  // namespace

double first_exceedance(const GroundMotion& rec, double t_from, double t_end, double threshold_m_s2) {
  // Most cases of a study never lift their frame: a record whose peak stays below the
  // threshold (by far more than the rounding of an interpolation between samples) is not scanned.
  if (rec.pga_m_s2() < threshold_m_s2 * (1.0 - 1e-9)) return kNaN;
  if (std::abs(rec.accel_m_s2(t_from)) > threshold_m_s2) return t_from;
  if (threshold_m_s2 < 0.0) return t_from;
  const auto& a = rec.samples_m_s2();
  const double dt = rec.dt_s();
  // Sample a1 ends an interval that crosses `level` (upwards for +threshold, downwards for
  // −threshold).
  auto crosses = [](double level, double a1) { return level > 0 ? a1 > level : a1 < level; };
  auto exceeds = [&](double a1) { return crosses(threshold_m_s2, a1) || crosses(-threshold_m_s2, a1); };
  std::size_t i = static_cast<std::size_t>(std::max(0.0, std::floor(t_from / dt)));
  // The first interval whose end exceeds the threshold, by a plain scan (no interval before
  // it crosses, so the loop below would pass them all by).
  std::size_t end = i + 1;
  while (end < a.size() && !exceeds(a[end])) ++end;
  if (end >= a.size()) return kNaN;
  i = end - 1;
  const double t0 = static_cast<double>(i) * dt;
  if (t0 > t_end) return kNaN;
  const double a0 = a[i], a1 = a[i + 1];
  double best = kNaN;
  for (const double level : {threshold_m_s2, -threshold_m_s2}) {
    if (!crosses(level, a1)) continue;
    const double s = std::clamp((level - a0) / (a1 - a0), 0.0, 1.0);
    const double tc = std::max(t0 + s * dt, t_from);
    if (std::isnan(best) || tc < best) best = tc;
  }
  return best <= t_end ? best : kNaN;
}

namespace {

/// The uplift threshold as a line in ü_v, a_up(0) + λ_g ü_v (docs/vertical_excitation.md), and
/// how far that line may lie above the threshold's formula (G(g + ü_v) + K)/S as rounded, for
/// every ü_v of a vertical component: a bound on the rounding of both, 1e-9 of the size of the
/// terms the threshold sums (|G g/S| + |G ü_v/S| + |K/S|; K/S = threshold(0) − λ_g g), far
/// above it. Samples where |ü_h| stays below the line less the bound cannot open the frame.
struct ThresholdLine {
  ThresholdLine(const Scene& scene, const GroundMotion& up)
      : at_rest_m_s2(scene.uplift_threshold_m_s2()), lambda(scene.lambda_g()) {
    const double g = scene.gravity_m_s2(), v_abs = std::max(-up.min_m_s2(), up.max_m_s2());
    rounding_m_s2 = 1e-9 * (std::abs(lambda) * (g + v_abs) + std::abs(at_rest_m_s2 - lambda * g));
  }
  /// The line less the rounding bound at ü_v [m/s²]: below it a horizontal cannot open.
  double floor_m_s2(double vertical_m_s2) const { return at_rest_m_s2 + lambda * vertical_m_s2 - rounding_m_s2; }

  double at_rest_m_s2;  ///< a_up(0)
  double lambda;        ///< λ_g = d a_up / d ü_v [-]
  double rounding_m_s2 = 0.0;
};

/// True when the horizontal peak stays below the uplift threshold at every ü_v the vertical
/// component takes (and at 0, after the record): then no sample, and no point between
/// samples, opens the frame. The threshold is affine in ü_v, so its lowest value over that
/// range is at one end (for λ_g > 0: the largest horizontal against the smallest g + ü_v).
bool never_opens(const Excitation& excitation, const ThresholdLine& line) {
  const GroundMotion& up = *excitation.vertical();
  const double v_lo = std::min(up.min_m_s2(), 0.0), v_hi = std::max(up.max_m_s2(), 0.0);
  return excitation.horizontal().pga_m_s2() < std::min(line.floor_m_s2(v_lo), line.floor_m_s2(v_hi));
}

/// The first sample index j > i_from, below `j_end`, at which the frame may open: |ü_h|
/// reaches ThresholdLine::floor_m_s2 at that sample's ü_v (a sample below it opens neither
/// side, whatever the rounding of the threshold's formula); `j_end` when none does. Reads
/// the samples directly: one multiply-add and one comparison per sample.
std::size_t next_candidate(const std::vector<double>& h, const std::vector<double>& v, const ThresholdLine& line,
                           std::size_t i_from, std::size_t j_end) {
  const double base = line.at_rest_m_s2 - line.rounding_m_s2, lambda = line.lambda;
  std::size_t j = i_from + 1;
  while (j < j_end && !(std::abs(h[j]) >= base + lambda * v[j])) ++j;
  return j;
}

}  // namespace

double first_opening(const Excitation& excitation, const Scene& scene, double t_from, double t_end) {
  if (!excitation.has_vertical())
    return first_exceedance(excitation.horizontal(), t_from, t_end, scene.uplift_threshold_m_s2());
  const ThresholdLine line(scene, *excitation.vertical());
  if (never_opens(excitation, line)) return kNaN;
  // The margin ±ü_h − threshold(ü_v) of each sign is linear between samples (the threshold is
  // affine in ü_v): the first sample interval where one turns positive holds the crossing.
  auto margin = [&](GroundAcceleration a, double sign) {
    return sign * a.horizontal_m_s2 - scene.uplift_threshold_m_s2(a.vertical_m_s2);
  };
  const GroundAcceleration at_from = excitation.at(t_from);
  if (!scene.holds_closed(at_from)) return t_from;
  const double dt = excitation.dt_s();
  const auto& h = excitation.horizontal().samples_m_s2();
  const auto& v = excitation.vertical()->samples_m_s2();
  const std::size_t n = h.size();
  // Intervals up to the one holding t_end, and one more against the rounding of t_end/dt (the
  // exact test below stops at the first interval that starts after t_end).
  const std::size_t j_end = static_cast<std::size_t>(std::min(static_cast<double>(n), std::floor(t_end / dt) + 3.0));
  const auto i_from = static_cast<std::size_t>(std::max(0.0, std::floor(t_from / dt)));
  // Samples at which the frame cannot open are passed over (their margins are negative on
  // both sides); the interval i = j − 1 that ends at a candidate sample j is then tested as
  // every interval was before: the ground at its ends through Excitation::at (sample j
  // exactly at t1), the margins from the threshold's formula.
  for (std::size_t j = next_candidate(h, v, line, i_from, j_end); j < j_end; j = next_candidate(h, v, line, j, j_end)) {
    const std::size_t i = j - 1;
    const double t0 = std::max(static_cast<double>(i) * dt, t_from);
    if (t0 > t_end) break;
    const double t1 = static_cast<double>(i + 1) * dt;
    const GroundAcceleration a0 = excitation.at(t0), a1 = excitation.at(t1);
    double best = kNaN;
    for (const double sign : {1.0, -1.0}) {
      const double m0 = margin(a0, sign), m1 = margin(a1, sign);
      if (!(m1 > 0.0)) continue;
      const double s = m0 >= 0.0 ? 0.0 : std::clamp(m0 / (m0 - m1), 0.0, 1.0);
      const double tc = t0 + s * (t1 - t0);
      if (std::isnan(best) || tc < best) best = tc;
    }
    if (!std::isnan(best)) return best <= t_end ? best : kNaN;
  }
  return kNaN;
}

double free_fall_time(const Excitation& excitation, double gravity_m_s2, double t_end) {
  const GroundMotion* vertical = excitation.vertical();
  if (vertical == nullptr || vertical->min_m_s2() > -gravity_m_s2) return kNaN;  // never falls
  const auto& a = vertical->samples_m_s2();
  const double level = -gravity_m_s2, dt = vertical->dt_s();
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!(a[i] <= level)) continue;
    const double t = i == 0 ? 0.0 : (static_cast<double>(i - 1) + (level - a[i - 1]) / (a[i] - a[i - 1])) * dt;
    return t <= t_end ? t : kNaN;
  }
  return kNaN;
}

CaseEnd::CaseEnd(const Excitation& excitation, double gravity_m_s2, const PhysicsOptions& physics)
    : t_end_s(longest_case_s(excitation.duration_s(), physics)),
      free_fall(false),
      until_rest(physics.tail_s == kTailUntilRest),
      record_end_s(excitation.duration_s()) {
  const double t_fall = free_fall_time(excitation, gravity_m_s2, t_end_s);
  if (!std::isnan(t_fall)) t_end_s = t_fall, free_fall = true;
}

std::string CaseEnd::message() const {
  if (!free_fall) return {};
  char text[160];
  std::snprintf(text, sizeof text,
                "the ground fell faster than gravity (g + vertical acceleration <= 0) at t = %.6g s: the frame "
                "leaves its supports, which the model does not describe",
                t_end_s);
  return text;
}

double paper_trigger_time(const GroundMotion& rec, double lambda_g) {
  const auto& a = rec.samples_m_s2();
  const double level = lambda_g * kGravity_m_s2;
  if (rec.pga_m_s2() < level) return kNaN;  // no sample reaches it
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::abs(a[i]) >= level) return static_cast<double>(i) * rec.dt_s();
  }
  return kNaN;
}

namespace {

/// Every value that determines results, checked against its description.
template <class Target>
void validate_table(const SettingTable<Target>& table, const Target& values) {
  for (const auto& setting : table.settings) {
    if (!setting.in_fingerprint) continue;  // the preset name only says where the values came from
    SettingValue value = setting.get(values);
    if (const auto problem = check_setting(setting, value); !problem.empty())
      throw UserError(std::string(setting.key), problem);
  }
}

}  // namespace

void validate(const SolverSettings& s, const PhysicsOptions& p) {
  // A study solves millions of cases with the same settings: check a pair once per thread.
  thread_local std::optional<std::pair<SolverSettings, PhysicsOptions>> last_valid;
  if (last_valid && last_valid->first == s && last_valid->second == p) return;
  validate_table(solver_settings(), s);
  validate_table(physics_settings(), p);
  if (p.uplift == UpliftCriterion::kPaperProcedure && s.integrator != Integrator::kFixedRk4SignChange)
    throw UserError(
        "physics setting uplift = \"paper-procedure\" reproduces the paper's fixed-step procedure: it needs solver "
        "setting integrator = \"fixed-rk4\" (and a fixed_step_s)");
  last_valid.emplace(s, p);
}

StopAngles stop_angles(const Scene& scene, const PhysicsOptions& physics) {
  return {scene.fracture_angle_rad(physics.fracture_strain), scene.overturn_angle_rad()};
}

CaseStatus StopAngles::status() const {
  return fracture_rad <= overturn_rad ? CaseStatus::kTendonFracture : CaseStatus::kOverturned;
}

const char* StopAngles::message() const {
  return fracture_rad <= overturn_rad ? "tendon strain reached the fracture strain"
                                      : "rotation reached the mechanism's closing limit";
}

CaseResult initial_result(const Scene& scene, const Excitation& excitation, double restitution,
                          bool omega_peak) {
  const GroundMotion& rec = excitation.horizontal();
  CaseResult r;
  r.lambda_g = scene.lambda_g();
  r.uplift_threshold_g = scene.uplift_threshold_m_s2() / kGravity_m_s2;
  r.restitution = restitution;
  r.t_trigger_paper_s = paper_trigger_time(rec, scene.lambda_g());
  r.t_uplift_s = kNaN;
  r.t_theta_max_s = kNaN;
  r.t_omega_max_s = kNaN;
  r.theta_max_rad = 0.0;
  r.omega_max_rad_s = omega_peak ? 0.0 : kNaN;
  const TendonState rest = scene.tendons(0.0, -1);
  r.strain_column_max = rest.strain_column_max();
  r.strain_beam_max = rest.strain_beam;
  return r;
}

void set_peak_strains(const Scene& scene, CaseResult& result) {
  // The trajectory starts at θ₁ = 0 and is continuous, so it has visited every |θ₁| up
  // to the peak: peak strains are the maxima over that range.
  if (!(result.theta_max_rad > 0.0)) return;
  const TendonState peak = scene.peak_tendon_strains(result.theta_max_rad);
  result.strain_column_max = peak.strain_column_max();
  result.strain_beam_max = peak.strain_beam;
}

void HistoryRows::add(double t, double theta, double omega, int side, std::uint32_t events) {
  if (!sink_) return;
  if (held_ && t == row_.t_s) {
    row_.omega1_after_rad_s = omega;
    row_.event = static_cast<double>(static_cast<std::uint32_t>(row_.event) | events);
    return;
  }
  flush();
  HistorySample& s = row_;
  s.t_s = t;
  s.theta1_rad = theta;
  s.omega1_rad_s = omega;
  s.omega1_after_rad_s = omega;
  scene_.configuration(theta, side, s.theta2_rad, s.theta3_rad);
  const TendonState ts = scene_.tendons(theta, side);
  s.strain_column_left = ts.strain_column_left;
  s.strain_column_right = ts.strain_column_right;
  s.strain_beam = ts.strain_beam;
  s.ground_accel_m_s2 = excitation_.at(t).horizontal_m_s2;
  s.ground_accel_g = s.ground_accel_m_s2 / kGravity_m_s2;
  s.event = static_cast<double>(events);
  held_ = true;
}

void HistoryRows::end(double t, double theta, double omega, int side, std::uint32_t events) {
  if (!sink_) return;
  add(t, theta, omega, side, events | kEventEnd);
  flush();
}

void HistoryRows::flush() {
  if (held_) sink_(row_);
  held_ = false;
}

}  // namespace pcrf::detail
