/// \file progress.hpp
/// \brief The progress line of a running study: cases done of total, failures, rate, ETA.
#pragma once

#include <chrono>
#include <cstdint>
#include <ostream>
#include <string>

namespace pcrf::run {

class ProgressMeter {
 public:
  /// \param total        cases in the study
  /// \param already_done cases found done in a resumed cube (not counted in the rate)
  /// \param interval_s   seconds between lines; 0: no periodic lines
  ProgressMeter(std::int64_t total, std::int64_t already_done, double interval_s, std::ostream& out);

  /// Counts finished cases.
  void add(std::int64_t finished, std::int64_t failed);
  /// Prints a line if the interval has passed.
  void tick();
  /// The closing line (always printed).
  void finish(const std::string& output);

  /// "120/400 cases (30.0 %), 2 failed, 45.3 cases/s, ETA 6 s"
  std::string line() const;
  std::int64_t failed() const { return failed_; }
  std::int64_t computed() const { return computed_; }
  double elapsed_s() const;

 private:
  using Clock = std::chrono::steady_clock;
  std::int64_t total_;
  std::int64_t already_done_;
  std::int64_t computed_ = 0;
  std::int64_t failed_ = 0;
  double interval_s_;
  std::ostream& out_;
  Clock::time_point start_ = Clock::now();
  Clock::time_point last_line_ = Clock::now();
};

/// "3.2 s", "4 min 05 s", "2 h 07 min".
std::string format_duration(double seconds);

}  // namespace pcrf::run
