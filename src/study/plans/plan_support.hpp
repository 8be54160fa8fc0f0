// What the plans share (not part of the public interface): what a plan reads from a study
// file, the registry of plans, the canonical text of axes and frames, and PointPlan, the
// plans whose frames are the values of a single `case` dimension.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pcrf/study/plan.hpp"
#include "study/toml_fields.hpp"

namespace pcrf::study::detail {

/// What a plan reads: its own [plan] keys, the parameter keys of [axes], and the study file's
/// top-level tables it claims ([[cases]]). The parser has checked that no other plan's key
/// is given.
struct PlanInput {
  const Fields& plan;          ///< [plan] (an empty table when the file has none)
  const Fields* axes;          ///< [axes], or nullptr; its scale and intensity keys are not the plan's
  const Fields& top;           ///< the whole file
  const SceneModel& model;     ///< the study's scene: its parameters are the plan's (a list case may name another)
  const ScenePoint& base;      ///< [frame] / [base]: every frame starts from it
};

/// A plan kind: its name, the [plan] keys (besides `kind`) and top-level tables it takes,
/// and how it is read. One line per kind in plan_registry.cpp.
struct PlanEntry {
  std::string_view name;
  std::vector<std::string_view> plan_keys;
  std::vector<std::string_view> file_keys;
  std::shared_ptr<const Plan> (*read)(const PlanInput& input);
};

/// Every plan kind, the default (grid) first.
const std::vector<PlanEntry>& plan_registry();

/// The value lists [axes] gives the scene's parameters (one per parameter of its table, empty:
/// not given), each checked by check_axis; a key of another scene is refused.
std::vector<std::vector<double>> read_parameter_axes(const PlanInput& input);

/// The positions of the model's axis parameters in its table.
std::vector<std::size_t> axis_parameters(const SceneModel& model);

/// "axis <parameter> v1 v2 …" for each axis parameter (no values: not an axis of the plan).
void describe_axes(std::ostream& out, const SceneModel& model, const std::vector<std::vector<double>>& axes);
/// " kappa=… … pi_e_c=… h_m=… m_c_kg=…": every parameter of the table (no newline).
void describe_parameters(std::ostream& out, const SceneModel& model, const ScenePoint& frame);

/// A plan whose frames are listed along one dimension, `case`: its coordinates are the case
/// number, `case_label`, where the cases mix scene models `scene_model`, the plan's own
/// (extra_coordinates), the axis parameters of the plan's model and every parameter of any
/// other model present (NaN for a case whose model has no such parameter); a history names
/// its frame by `case` label. The frames are held (a list's, one-at-a-time's) or computed from
/// their numbers by the plan (the sampled plans, which then hold their unit points only):
/// everything here reads them through point_model, point_value and point_label.
class PointPlan : public Plan {
 public:
  struct Point {
    std::string label;
    ScenePoint parameters;              ///< a point of `model`'s table
    const SceneModel* model = nullptr;  ///< nullptr: the plan's model (the study's)
  };

  const std::vector<cube::Dimension>& dimensions() const override { return dimensions_; }
  SceneSpec frame_at(std::span<const std::size_t> coordinates) const override;
  std::vector<SceneSpec> frames() const override;
  std::vector<cube::Coordinate> coordinates() const override;
  std::vector<std::size_t> locate(const HistoryRequest& request) const override;
  std::string history_key_problem(std::string_view key) const override;
  /// A listed frame: its label, parameters and model, its labels and values in the cube.
  double bytes_per_frame() const override { return points_.empty() ? 0.0 : 512.0; }

 protected:
  PointPlan(const SceneModel& model, std::vector<Point> points);
  /// A plan of `count` frames that it computes, every one of `model` (it overrides the
  /// point_* functions).
  PointPlan(const SceneModel& model, std::size_t count);
  const SceneModel& model() const { return *model_; }
  std::size_t point_count() const { return dimensions_[0].size; }
  /// Frame i's model, the value of its model's parameter k, and its label.
  virtual const SceneModel& point_model(std::size_t i) const { return *points_[i].model; }
  virtual double point_value(std::size_t i, std::size_t k) const { return points_[i].parameters[k]; }
  virtual std::string point_label(std::size_t i) const { return points_[i].label; }
  /// point_value(first + m, k) into out[m] for every m, frames [first, first + out.size())
  /// all of the plan's model: a plan that computes its frames overrides it to fill a piece
  /// of a coordinate in a tight loop, the same bits (the sampled plans).
  virtual void point_values(std::size_t first, std::size_t k, std::span<double> out) const;
  /// point_value(i, k) into values[k] for every parameter k of frame i's model: a plan that
  /// computes its frames overrides it to compute a point's coordinates together.
  virtual void frame_values(std::size_t i, std::span<double> values) const;
  /// Auxiliary coordinates along `case` between case_label and the parameters.
  virtual std::vector<cube::Coordinate> extra_coordinates() const { return {}; }
  /// Whether the cube stores each case's label as text (`case_label`). A plan whose labels
  /// its case numbers and other coordinates say (lhs and sobol "s<case>", saltelli
  /// "s<saltelli_sample>:<saltelli_block>") answers false: a string a case cost an LHS cube
  /// about 40 B of its 144 (issue 38). The labels still name a case in a history request.
  virtual bool stores_labels() const { return true; }
  const std::vector<Point>& points() const { return points_; }

 private:
  const SceneModel* model_;
  std::vector<Point> points_;
  std::vector<cube::Dimension> dimensions_;
};

}  // namespace pcrf::study::detail
