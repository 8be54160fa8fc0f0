// The list plan: the frames [[cases]] gives, each starting from the base point, or, for a case
// that names another scene model (`model = "block"`), from that model's defaults.
#include <memory>
#include <set>

#include "study/axis_fields.hpp"
#include "study/plans/plan_support.hpp"

namespace pcrf::study::detail {
namespace {

class ListPlan final : public PointPlan {
 public:
  ListPlan(const SceneModel& model, std::vector<Point> cases) : PointPlan(model, std::move(cases)) {}

  std::string_view name() const override { return "list"; }
  void describe(std::ostream& out) const override {
    describe_axes(out, model(), {});
    for (const auto& c : points()) {
      out << "case " << c.label;
      if (c.model != &model()) out << " model=" << c.model->name;  // one model: the fingerprints as before
      describe_parameters(out, *c.model, c.parameters);
      out << '\n';
    }
  }
};

}  // namespace

std::shared_ptr<const Plan> read_list_plan(const PlanInput& input) {
  for (auto key : parameter_keys())
    if (input.axes != nullptr && input.axes->has(key))
      input.axes->fail(key, "plan \"list\" takes its parameters from [[cases]], not from [axes]");
  const auto* array = input.top.array("cases");
  if (array == nullptr) input.top.fail("cases", "plan \"list\" needs at least one [[cases]] table");
  if (array->empty()) input.top.fail("cases", "empty list");
  std::vector<PointPlan::Point> cases;
  std::set<std::string> labels;
  const auto keys = with_scene_keys({"label", "model"});
  for (std::size_t i = 0; i < array->size(); ++i) {
    const std::vector<std::string> path{"cases", key_index(i)};
    const auto* table = (*array)[i].as_table();
    if (table == nullptr) Fields::fail_at(input.top.file(), &(*array)[i], path, "expected a table");
    Fields f(*table, path, input.top.file(), keys);
    const SceneModel* model = read_model(f);
    if (model == nullptr) model = &input.model;
    const bool own = model == &input.model;  // another model's cases set all its parameters: it has no base point
    PointPlan::Point c{f.text("label").value_or("case" + std::to_string(i)), own ? input.base : model->defaults(), model};
    if (c.label.empty()) f.fail("label", "must not be empty");
    if (!labels.insert(c.label).second) f.fail("label", "\"" + c.label + "\" is used by another case");
    read_parameters(f, *model, c.parameters, own);
    cases.push_back(std::move(c));
  }
  return std::make_shared<ListPlan>(input.model, std::move(cases));
}

}  // namespace pcrf::study::detail
