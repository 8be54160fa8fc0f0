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
#include "study/toml_fields.hpp"

namespace pcrf::study::detail {

using pcrf::number_text;

/// The keys of the eight frame parameters.
std::vector<std::string_view> parameter_keys();
/// `keys` followed by the eight parameter keys.
std::vector<std::string_view> with_parameter_keys(std::vector<std::string_view> keys);

/// An axis' values: a number, a list of numbers, or a range table {from, to, count, spacing}.
std::vector<double> read_values(const Fields& fields, std::string_view key);

/// Axis values must be distinct (they label a dimension) and each valid alone: in the domain
/// of parameter `parameter`, or positive (kParameterCount: the scale or intensity axis).
void check_axis(const Fields& fields, std::string_view key, const std::vector<double>& values, std::size_t parameter);

/// Reads every parameter of `parameters` that `fields` gives into `frame` ([base], a listed
/// case), checking each value against its domain.
template <std::size_t N>
void read_parameters(const Fields& fields, const std::array<ParameterInfo, N>& parameters, FrameParameters& frame) {
  for (const auto& info : parameters) {
    if (!fields.has(info.name)) continue;
    const double value = *fields.number(info.name);
    if (const auto problem = parameter_problem(info, value); !problem.empty())
      fields.fail(info.name, "value " + number_text(value) + " " + problem);
    frame.*info.member = value;
  }
}

}  // namespace pcrf::study::detail
