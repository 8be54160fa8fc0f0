// Progress line of a running study (see progress.hpp).
#include "pcrf/run/progress.hpp"

#include <cmath>
#include <cstdio>

namespace pcrf::run {

std::string format_duration(double seconds) {
  char buffer[48];
  if (!std::isfinite(seconds)) return "?";
  if (seconds < 60.0)
    std::snprintf(buffer, sizeof buffer, "%.1f s", seconds);
  else if (seconds < 3600.0)
    std::snprintf(buffer, sizeof buffer, "%d min %02d s", int(seconds / 60), int(std::fmod(seconds, 60.0)));
  else
    std::snprintf(buffer, sizeof buffer, "%d h %02d min", int(seconds / 3600), int(std::fmod(seconds, 3600.0) / 60));
  return buffer;
}

ProgressMeter::ProgressMeter(std::int64_t total, std::int64_t already_done, double interval_s, std::ostream& out)
    : total_(total), already_done_(already_done), interval_s_(interval_s), out_(out) {}

void ProgressMeter::add(std::int64_t finished, std::int64_t failed) {
  computed_ += finished;
  failed_ += failed;
}

double ProgressMeter::elapsed_s() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

std::string ProgressMeter::line() const {
  const std::int64_t done = already_done_ + computed_;
  const double elapsed = elapsed_s();
  const double rate = elapsed > 0.0 ? static_cast<double>(computed_) / elapsed : 0.0;
  const double eta = rate > 0.0 ? static_cast<double>(total_ - done) / rate : NAN;
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, "%lld/%lld cases (%.1f %%), %lld failed, %.1f cases/s, ETA %s",
                static_cast<long long>(done), static_cast<long long>(total_),
                total_ > 0 ? 100.0 * static_cast<double>(done) / static_cast<double>(total_) : 100.0,
                static_cast<long long>(failed_), rate, format_duration(eta).c_str());
  return buffer;
}

void ProgressMeter::tick() {
  if (interval_s_ <= 0.0) return;
  const auto now = Clock::now();
  if (std::chrono::duration<double>(now - last_line_).count() < interval_s_) return;
  last_line_ = now;
  out_ << "pcrf study: " << line() << std::endl;
}

void ProgressMeter::finish(const std::string& output) {
  out_ << "pcrf study: " << computed_ << " cases computed";
  if (already_done_ > 0) out_ << " (" << already_done_ << " already done)";
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%.3f s", elapsed_s());  // exact enough for benchmarks
  out_ << ", " << failed_ << " failed, in " << seconds << "; cube: " << output << std::endl;
}

}  // namespace pcrf::run
