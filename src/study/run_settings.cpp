// The [run] table (see study.hpp): how a run behaves, never what it computes.
#include "pcrf/study/study.hpp"

namespace pcrf::study {

const SettingTable<RunOptions>& run_settings() {
  using R = RunOptions;
  static const SettingTable<RunOptions> table = [] {
    SettingTable<RunOptions> t{"run", RunOptions{}, {}};
    auto& s = t.settings;
    s.push_back(number_setting("flush_interval_s", &R::flush_interval_s, "s", Bound::kPositive,
                               "the cube is written to disk at least this often; a killed run loses at most that much work"));
    s.back().aliases = {"--flush-interval"};
    s.push_back(number_setting("progress_interval_s", &R::progress_interval_s, "s", Bound::kNonNegative,
                               "progress line period on stderr; 0: only the closing line"));
    s.back().aliases = {"--progress-interval"};
    s.push_back(integer_setting("batch_size", &R::batch_size, Bound::kNonNegative, "cases per hand-out; 0: guided"));
    s.push_back(integer_setting("lanes", &R::lanes, Bound::kAtLeastOne,
                                "cases under one record a worker integrates together in lockstep vector lanes "
                                "(dopri5 without verdict check; docs/batches.md); 1: one case at a time"));
    s.push_back(flag_setting("warnings_as_errors", &R::warnings_as_errors,
                             "a record whose PGA, PGV/PGA or units look wrong stops the study (exit code 2) "
                             "instead of a warning"));
    for (auto& setting : s) setting.in_fingerprint = false;  // how, not what
    return t;
  }();
  return table;
}

}  // namespace pcrf::study
