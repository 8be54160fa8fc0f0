// The [ida] table (see study.hpp).
#include "pcrf/metrics/case_result.hpp"
#include "pcrf/study/study.hpp"

namespace pcrf::study {

const SettingTable<IdaOptions>& ida_settings() {
  using I = IdaOptions;
  static const SettingTable<IdaOptions> table = [] {
    SettingTable<IdaOptions> t{"ida", IdaOptions{}, {}};
    auto& s = t.settings;
    s.push_back(number_setting("start", &I::start, "", Bound::kPositive,
                               "first intensity of every curve (the measure's units); required"));
    s.push_back(number_setting("step", &I::step, "", Bound::kNonNegative,
                               "hunt: the first step up after a safe run; 0: `start`"));
    s.push_back(number_setting("step_factor", &I::step_factor, "1", Bound::kAtLeastOne,
                               "hunt: each step is this times the one before (geometric; 1: equal steps)"));
    s.push_back(number_setting("resolution", &I::resolution, "1", Bound::kOpenUnit,
                               "bisect until collapse / last safe − 1 is at most this"));
    s.push_back(number_setting("max_intensity", &I::max_intensity, "", Bound::kPositive,
                               "cap of the hunt (the measure's units); a curve safe there is right-censored; required"));
    s.push_back(integer_setting("max_runs", &I::max_runs, Bound::kAtLeast, "runs per curve: hunt, bracket, then fill"));
    s.back().at_least = ida::kMinIdaRuns;
    std::vector<std::string> statuses;
    for (CaseStatus status : all_final_statuses())
      if (is_collapse(status)) statuses.emplace_back(status_name(status));
    s.push_back(words_setting("collapse", &I::collapse, statuses,
                              "statuses that count as collapse (a solver failure, a time limit or an unresolved run, the frame still "
                              "rocking when its tail ended, always does)"));
    s.push_back(number_setting("theta_limit_rad", &I::theta_limit_rad, "rad", Bound::kNonNegative,
                               "also a collapse: θ_max at or above this; 0: none"));
    return t;
  }();
  return table;
}

}  // namespace pcrf::study
