// The plan kinds a study file can name, one line each (see plan_support.hpp).
#include "study/plans/plan_support.hpp"

namespace pcrf::study::detail {

// Each in its plan's own file.
std::shared_ptr<const Plan> read_grid_plan(const PlanInput& input);
std::shared_ptr<const Plan> read_one_at_a_time_plan(const PlanInput& input);
std::shared_ptr<const Plan> read_list_plan(const PlanInput& input);
std::shared_ptr<const Plan> read_lhs_plan(const PlanInput& input);
std::shared_ptr<const Plan> read_sobol_plan(const PlanInput& input);
std::shared_ptr<const Plan> read_saltelli_plan(const PlanInput& input);

const std::vector<PlanEntry>& plan_registry() {
  static const std::vector<PlanEntry> entries{
      {"grid", {}, {}, read_grid_plan},
      {"one-at-a-time", {"include_base"}, {}, read_one_at_a_time_plan},
      {"list", {}, {"cases"}, read_list_plan},
      {"lhs", {"samples", "seed"}, {}, read_lhs_plan},
      {"sobol", {"samples", "seed", "scramble"}, {}, read_sobol_plan},
      {"saltelli", {"samples", "seed", "scramble"}, {}, read_saltelli_plan},
  };
  return entries;
}

}  // namespace pcrf::study::detail

namespace pcrf::study {

std::vector<std::string_view> plan_kinds() {
  std::vector<std::string_view> names;
  for (const auto& entry : detail::plan_registry()) names.push_back(entry.name);
  return names;
}

}  // namespace pcrf::study
