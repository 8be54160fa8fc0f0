// The one-at-a-time plan: each parameter [axes] sweeps, varied alone from the base point
// (which is a case of its own unless include_base = false). Cases "base", "kappa=1.2", ….
#include <algorithm>
#include <memory>

#include "pcrf/schema/cube_vocabulary.hpp"
#include "study/plans/plan_support.hpp"

namespace pcrf::study::detail {
namespace {

class OneAtATimePlan final : public PointPlan {
 public:
  OneAtATimePlan(const SceneModel& model, std::vector<Point> points, std::vector<std::string> varied,
                 std::vector<std::vector<double>> sweeps, bool include_base)
      : PointPlan(model, std::move(points)), varied_(std::move(varied)), sweeps_(std::move(sweeps)), include_base_(include_base) {}

  std::string_view name() const override { return "one-at-a-time"; }
  std::string canonical_heading() const override { return "include_base=" + std::to_string(include_base_ ? 1 : 0); }
  void describe(std::ostream& out) const override { describe_axes(out, model(), sweeps_); }

 protected:
  std::vector<cube::Coordinate> extra_coordinates() const override {
    return {text_coordinate(schema::kVariedParameter, schema::kCase,
                            "parameter varied from the base point (none: the base point)", varied_)};
  }

 private:
  std::vector<std::string> varied_;  ///< per case: the parameter swept, "none" for the base point
  std::vector<std::vector<double>> sweeps_;
  bool include_base_;
};

}  // namespace

std::shared_ptr<const Plan> read_one_at_a_time_plan(const PlanInput& input) {
  const bool include_base = input.plan.flag("include_base").value_or(true);
  auto sweeps = read_parameter_axes(input);
  if (std::all_of(sweeps.begin(), sweeps.end(), [](const auto& v) { return v.empty(); }))
    input.top.fail("axes", "plan \"one-at-a-time\" needs at least one parameter to sweep in [axes]");
  std::vector<PointPlan::Point> points;
  std::vector<std::string> varied;
  if (include_base) {
    points.push_back({"base", input.base});
    varied.emplace_back("none");
  }
  for (std::size_t p : axis_parameters(input.model)) {
    const auto& parameter = input.model.parameters[p];
    for (double v : sweeps[p]) {
      points.push_back({std::string(parameter.name) + "=" + number_text(v), input.base});
      points.back().parameters[p] = v;
      varied.emplace_back(parameter.name);
    }
  }
  return std::make_shared<OneAtATimePlan>(input.model, std::move(points), std::move(varied), std::move(sweeps), include_base);
}

}  // namespace pcrf::study::detail
