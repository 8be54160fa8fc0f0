// Hunt-and-fill search of one IDA curve (see ida_search.hpp).
#include "pcrf/ida/ida_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace pcrf::ida {
namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}

IdaSearch::IdaSearch(const IdaSearchSettings& settings) : settings_(settings) {
  if (!(settings_.start > 0.0)) throw std::invalid_argument("IDA start must be positive");
  if (settings_.step <= 0.0) settings_.step = settings_.start;
  if (!(settings_.step_factor >= 1.0)) throw std::invalid_argument("IDA step_factor must be at least 1");
  if (!(settings_.resolution > 0.0 && settings_.resolution < 1.0))
    throw std::invalid_argument("IDA resolution must be in (0, 1)");
  if (!(settings_.max_intensity >= settings_.start)) throw std::invalid_argument("IDA max_intensity must be ≥ start");
  if (settings_.max_runs < kMinIdaRuns)
    throw std::invalid_argument("IDA max_runs must be at least " + std::to_string(kMinIdaRuns));
}

void IdaSearch::add(double intensity, RunVerdict verdict) {
  runs_.push_back({intensity, verdict != RunVerdict::kSafe, verdict == RunVerdict::kNoVerdict});
}

double IdaSearch::ceiling() const {
  double c = kNaN;
  for (const auto& r : runs_)
    if (r.collapsed && !(r.intensity >= c)) c = r.intensity;
  return c;
}

bool IdaSearch::ceiling_has_no_verdict() const {
  const double c = ceiling();
  return std::any_of(runs_.begin(), runs_.end(), [c](const Run& r) { return r.no_verdict && r.intensity == c; });
}

double IdaSearch::collapse_intensity() const { return ceiling_has_no_verdict() ? kNaN : ceiling(); }

double IdaSearch::last_safe_intensity() const {
  const double c = ceiling();
  double s = kNaN;
  for (const auto& r : runs_)
    if (!r.collapsed && (std::isnan(c) || r.intensity < c) && !(r.intensity <= s)) s = r.intensity;
  return s;
}

bool IdaSearch::bracketed() const {
  const double c = ceiling(), s = last_safe_intensity();
  if (std::isnan(c)) return !std::isnan(s) && s >= settings_.max_intensity;
  return !std::isnan(s) && c / s - 1.0 <= settings_.resolution;
}

CurveState IdaSearch::state() const {
  if (ceiling_has_no_verdict()) return CurveState::kUnresolved;
  if (!bracketed()) return CurveState::kUnbracketed;
  return std::isnan(ceiling()) ? CurveState::kCensored : CurveState::kBracketed;
}

std::optional<double> IdaSearch::hunt() const {
  if (runs_.empty()) return settings_.start;
  const double last = runs_.back().intensity;
  if (last >= settings_.max_intensity) return std::nullopt;  // safe at the cap: censored
  // The k-th step (k runs made): step · f^(k−1), geometric so that wide ranges are bracketed
  // within the run budget.
  const double k = static_cast<double>(runs_.size());
  return std::min(last + settings_.step * std::pow(settings_.step_factor, k - 1.0), settings_.max_intensity);
}

std::optional<double> IdaSearch::fill() const {
  const double s = last_safe_intensity();
  std::vector<double> points;
  for (const auto& r : runs_)
    if (!r.collapsed && r.intensity <= s) points.push_back(r.intensity);
  std::sort(points.begin(), points.end());
  // A fill run may collapse (an IDA curve need not be monotone); the bracket then restarts
  // between the gap's lower end and it. Fill only where the runs left after this one can
  // bisect that bracket down to the resolution, so the curve always ends bracketed. The gap
  // below the first run is left alone: a collapse there has no safe run under it.
  const int left_after = settings_.max_runs - runs() - 1;
  double best_gap = 0.0, at = kNaN;
  for (std::size_t i = 1; i < points.size(); ++i) {
    const double mid = 0.5 * (points[i] + points[i - 1]);
    const double width = mid / points[i - 1] - 1.0;
    const int needed = width > settings_.resolution ? static_cast<int>(std::ceil(std::log2(width / settings_.resolution))) : 0;
    if (needed <= left_after && points[i] - points[i - 1] > best_gap) {
      best_gap = points[i] - points[i - 1];
      at = mid;
    }
  }
  if (std::isnan(at) || best_gap <= settings_.resolution * s) return std::nullopt;  // nothing left worth a run
  return at;
}

std::optional<double> IdaSearch::next() const {
  if (runs() >= settings_.max_runs) return std::nullopt;
  const double c = ceiling();
  if (std::isnan(c)) return hunt();
  const double s = last_safe_intensity();
  if (std::isnan(s)) return 0.5 * c;  // the first collapse came at once: come down
  if (!bracketed()) return 0.5 * (s + c);
  return fill();
}

}  // namespace pcrf::ida
