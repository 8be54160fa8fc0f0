// The grid plan: every combination of the parameter axes, one cube dimension per parameter
// (a parameter [axes] does not give has one value, the base point's).
#include <memory>

#include "pcrf/study/cube_vocabulary.hpp"
#include "study/plans/plan_support.hpp"

namespace pcrf::study::detail {
namespace {

class GridPlan final : public Plan {
 public:
  GridPlan(const FrameParameters& base, std::array<std::vector<double>, kParameterCount> axes)
      : base_(base), given_(std::move(axes)) {
    for (std::size_t p = 0; p < kParameterCount; ++p) {
      const auto& info = all_parameters()[p];
      values_[p] = given_[p].empty() ? std::vector<double>{base_.*info.member} : given_[p];
      dimensions_.push_back({std::string(info.name), values_[p].size()});
    }
  }

  std::string_view name() const override { return "grid"; }
  const std::vector<cube::Dimension>& dimensions() const override { return dimensions_; }

  FrameParameters frame_at(std::span<const std::size_t> coordinates) const override {
    FrameParameters frame = base_;
    for (std::size_t p = 0; p < kParameterCount; ++p) frame.*all_parameters()[p].member = values_[p][coordinates[p]];
    return frame;
  }

  std::vector<FrameParameters> frames() const override {
    std::vector<FrameParameters> frames{base_};
    for (std::size_t p = 0; p < kParameterCount; ++p) {
      std::vector<FrameParameters> next;
      next.reserve(frames.size() * values_[p].size());
      for (const auto& f : frames)
        for (double v : values_[p]) {
          next.push_back(f);
          next.back().*all_parameters()[p].member = v;
        }
      frames = std::move(next);
    }
    return frames;
  }

  std::vector<cube::Coordinate> coordinates() const override {
    std::vector<cube::Coordinate> coords;
    for (std::size_t p = 0; p < kParameterCount; ++p) {
      const auto& info = all_parameters()[p];
      coords.push_back(number_coordinate(std::string(info.name), std::string(info.name), "1", std::string(info.long_name), values_[p]));
    }
    return coords;
  }

  std::vector<std::size_t> locate(const HistoryRequest& request) const override {
    std::vector<std::size_t> coords(kParameterCount);
    for (std::size_t p = 0; p < kParameterCount; ++p) {
      const std::string key(all_parameters()[p].name);
      const auto& value = request.parameters[p];
      if (!value) {
        coords[p] = pick_single(request, values_[p].size(), key);
        continue;
      }
      coords[p] = find_value(values_[p], *value);
      if (coords[p] == std::string::npos) fail_history(request, key + " " + number_text(*value) + " is not on the " + key + " axis");
    }
    return coords;
  }

  std::string history_key_problem(std::string_view key) const override {
    return key == vocabulary::kCase ? "plan \"grid\" selects cases by parameter values" : "";
  }

  void describe(std::ostream& out) const override { describe_axes(out, given_); }

 private:
  FrameParameters base_;
  std::array<std::vector<double>, kParameterCount> given_;   ///< as [axes] gives them
  std::array<std::vector<double>, kParameterCount> values_;  ///< the dimensions' values
  std::vector<cube::Dimension> dimensions_;
};

}  // namespace

std::shared_ptr<const Plan> read_grid_plan(const PlanInput& input) {
  return std::make_shared<GridPlan>(input.base, read_parameter_axes(input));
}

}  // namespace pcrf::study::detail
