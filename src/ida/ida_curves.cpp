// The adaptive IDA as a work source (see ida_curves.hpp).
#include "pcrf/ida/ida_curves.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace pcrf::ida {
namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}

IdaCurves::IdaCurves(std::size_t curves, const IdaSearchSettings& settings, CollapseTest collapsed, int workers)
    : settings_(settings),
      collapsed_(std::move(collapsed)),
      workers_(std::max(workers, 1)),
      searches_(curves, IdaSearch(settings)),
      in_flight_(curves, kNaN),
      queued_(curves, false),
      skipped_(curves, false) {
  for (std::size_t c = 0; c < curves; ++c) refresh(c);
}

void IdaCurves::replay(std::size_t curve, int point, double intensity, RunVerdict verdict) {
  if (point != searches_.at(curve).runs())
    throw std::invalid_argument("IDA replay: curve " + std::to_string(curve) + " point " + std::to_string(point) +
                                " out of order");
  searches_[curve].add(intensity, verdict);
  refresh(curve);
}

void IdaCurves::skip(std::size_t curve) {
  skipped_.at(curve) = true;
  refresh(curve);
}

void IdaCurves::refresh(std::size_t curve) {
  const bool wants = !skipped_[curve] && searches_[curve].next().has_value() && std::isnan(in_flight_[curve]);
  // Constant time whatever the number of curves: a curve leaves the queue by its flag, and
  // take() drops the stale entry when it reaches it.
  if (wants && !queued_[curve]) {
    queued_[curve] = true;
    ++ready_count_;
    ready_.push_back(curve);
  } else if (!wants && queued_[curve]) {
    queued_[curve] = false;
    --ready_count_;
  }
}

parallel::WorkBatch IdaCurves::take(bool) {
  // Guided: a share of the ready curves, so every worker gets some while many are ready.
  const std::size_t share = 4 * static_cast<std::size_t>(workers_);
  const std::size_t n = std::clamp<std::size_t>((ready_count_ + share - 1) / share, 1, 64);
  parallel::WorkBatch batch;
  while (batch.size() < n && ready_count_ > 0) {
    const std::size_t c = ready_.front();
    ready_.pop_front();
    if (!queued_[c]) continue;  // left the queue since it was put there
    queued_[c] = false;
    --ready_count_;
    const double x = *searches_[c].next();
    in_flight_[c] = x;
    ++running_;
    const auto index = ida_case(static_cast<std::int64_t>(c), searches_[c].runs(), settings_.max_runs);
    batch.push_back({index, x});
  }
  return batch;
}

void IdaCurves::completed(const parallel::CaseOutcome& outcome) {
  const auto c = static_cast<std::size_t>(outcome.case_index / settings_.max_runs);
  if (c >= searches_.size() || std::isnan(in_flight_[c])) return;  // not one of ours
  searches_[c].add(in_flight_[c], collapsed_(outcome));
  in_flight_[c] = kNaN;
  --running_;
  refresh(c);
}

bool IdaCurves::exhausted() const { return ready_count_ == 0 && running_ == 0; }

std::size_t IdaCurves::finished_curves() const {
  return static_cast<std::size_t>(std::count_if(searches_.begin(), searches_.end(), [](const IdaSearch& s) { return s.done(); }));
}

}  // namespace pcrf::ida
