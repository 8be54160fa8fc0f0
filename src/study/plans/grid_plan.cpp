// The grid plan: every combination of the parameter axes, one cube dimension per parameter
// (a parameter [axes] does not give has one value, the base point's), over the scene's axis
// parameters.
#include <memory>

#include "pcrf/schema/cube_vocabulary.hpp"
#include "study/plans/plan_support.hpp"

namespace pcrf::study::detail {
namespace {

class GridPlan final : public Plan {
 public:
  GridPlan(const SceneModel& model, const ScenePoint& base, std::vector<std::vector<double>> axes)
      : model_(&model), base_(base), given_(std::move(axes)), swept_(axis_parameters(model)) {
    for (std::size_t p : swept_) {
      values_.push_back(given_[p].empty() ? std::vector<double>{base_[p]} : given_[p]);
      dimensions_.push_back({std::string(model.parameters[p].name), values_.back().size()});
    }
  }

  std::string_view name() const override { return "grid"; }
  const std::vector<cube::Dimension>& dimensions() const override { return dimensions_; }

  SceneSpec frame_at(std::span<const std::size_t> coordinates) const override {
    SceneSpec frame{model_, base_};
    for (std::size_t d = 0; d < swept_.size(); ++d) frame.values[swept_[d]] = values_[d][coordinates[d]];
    return frame;
  }

  std::vector<SceneSpec> frames() const override {
    std::vector<SceneSpec> frames{{model_, base_}};
    for (std::size_t d = 0; d < swept_.size(); ++d) {
      std::vector<SceneSpec> next;
      next.reserve(frames.size() * values_[d].size());
      for (const auto& f : frames)
        for (double v : values_[d]) {
          next.push_back(f);
          next.back().values[swept_[d]] = v;
        }
      frames = std::move(next);
    }
    return frames;
  }

  std::vector<cube::Coordinate> coordinates() const override {
    std::vector<cube::Coordinate> coords;
    for (std::size_t d = 0; d < swept_.size(); ++d) {
      const auto& parameter = model_->parameters[swept_[d]];
      coords.push_back(number_coordinate(std::string(parameter.name), std::string(parameter.name), std::string(parameter.units),
                                         std::string(parameter.long_name), values_[d]));
    }
    return coords;
  }

  std::vector<std::size_t> locate(const HistoryRequest& request) const override {
    std::vector<std::size_t> coords(swept_.size());
    for (std::size_t d = 0; d < swept_.size(); ++d) {
      const std::string key(model_->parameters[swept_[d]].name);
      const auto value = swept_[d] < request.parameters.size() ? request.parameters[swept_[d]] : std::nullopt;
      if (!value) {
        coords[d] = pick_single(request, values_[d].size(), key);
        continue;
      }
      coords[d] = find_value(values_[d], *value);
      if (coords[d] == std::string::npos) fail_history(request, key + " " + number_text(*value) + " is not on the " + key + " axis");
    }
    return coords;
  }

  std::string history_key_problem(std::string_view key) const override {
    return key == schema::kCase ? "plan \"grid\" selects cases by parameter values" : "";
  }

  void describe(std::ostream& out) const override { describe_axes(out, *model_, given_); }

 private:
  const SceneModel* model_;
  ScenePoint base_;
  std::vector<std::vector<double>> given_;   ///< as [axes] gives them, per parameter of the table
  std::vector<std::size_t> swept_;           ///< the table's axis parameters: one dimension each
  std::vector<std::vector<double>> values_;  ///< the dimensions' values
  std::vector<cube::Dimension> dimensions_;
};

}  // namespace

std::shared_ptr<const Plan> read_grid_plan(const PlanInput& input) {
  return std::make_shared<GridPlan>(input.model, input.base, read_parameter_axes(input));
}

}  // namespace pcrf::study::detail
