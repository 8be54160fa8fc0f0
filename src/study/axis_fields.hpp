// Reading the values of an axis and the frame parameters from study-file tables, shared by
// the parser and the plans: "FILE:LINE: dotted.key: problem" errors as toml_fields.hpp.
#pragma once

#include "pcrf/number_text.hpp"

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "pcrf/model/parameters.hpp"
#include "pcrf/model/scene_catalog.hpp"
#include "study/toml_fields.hpp"

namespace pcrf::study::detail {

using pcrf::number_text;

/// The keys of every scene's axis parameters (the prestressed frame's eight first), so that a
/// key of another scene is named as such rather than as unknown.
std::vector<std::string_view> parameter_keys();
/// `keys` followed by parameter_keys().
std::vector<std::string_view> with_parameter_keys(std::vector<std::string_view> keys);
/// Every key of every scene (axis or not).
std::vector<std::string_view> all_scene_keys();
/// `keys` followed by all_scene_keys() ([frame] and a listed case, which may name their model).
std::vector<std::string_view> with_scene_keys(std::vector<std::string_view> keys);

/// A key `fields` gives that belongs to another scene than `model`: "FILE:LINE: t.kappa: does
/// not apply to model "block" (it is a parameter of model "pcrf")".
void refuse_other_scenes(const Fields& fields, const SceneModel& model);

/// An axis' values: a number, a list of numbers, or a range table {from, to, count, spacing}.
std::vector<double> read_values(const Fields& fields, std::string_view key);

/// Axis values must be distinct (they label a dimension) and each valid alone: in the domain
/// of `parameter`, or positive (nullptr: the scale or intensity axis).
void check_axis(const Fields& fields, std::string_view key, const std::vector<double>& values,
                const SceneParameter* parameter);

/// The scene model `fields` names by its key `model`, or nullptr when it names none.
/// \throws UserError "FILE:LINE: t.model: unknown scene 'x' (expected pcrf, block or rocking-frame)".
const SceneModel* read_model(const Fields& fields);

/// Reads every parameter of `model` that `fields` gives into `point` ([frame] or [base]: all;
/// a listed case: the axis parameters only), checking each value against its domain and
/// refusing a key of another scene. Of the model's exclusive keys, at most one may be given.
void read_parameters(const Fields& fields, const SceneModel& model, ScenePoint& point, bool axis_only);

}  // namespace pcrf::study::detail
