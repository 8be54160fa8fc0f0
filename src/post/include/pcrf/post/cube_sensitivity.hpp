/// \file cube_sensitivity.hpp
/// \brief Sobol' sensitivity indices of a saltelli cube: the cube's cases turned into the
/// A, B, A_B^(i) outputs that analysis/sobol_indices.hpp takes.
///
/// The output of a frame is a metric, or `collapse` (1 for tendon fracture or overturned,
/// else 0). Across records (the default) it is the mean over the records; `by_record` gives
/// one set of indices per record. A base sample any of whose frames has no value (a failed
/// or invalid frame, a NaN metric) is left out, and counted.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "pcrf/analysis/sobol_indices.hpp"
#include "pcrf/cube/cube_query.hpp"
#include "pcrf/cube/cube_reader.hpp"

namespace pcrf::post {

struct SensitivityGroup {
  std::string record;                       ///< "all" across records, else the record's name
  std::vector<std::string> parameters;      ///< the varied parameters, design order
  std::vector<analysis::SobolIndex> indices;
  std::size_t samples = 0;                  ///< base samples used
  std::size_t dropped = 0;                  ///< base samples left out (a frame without a value)
};

/// \throws cube::CubeError when the cube is not a saltelli design, the metric is unknown, or
/// the selection leaves several values of the scale (or intensity) axis.
std::vector<SensitivityGroup> cube_sensitivity(const cube::CubeReader& cube, const std::string& metric,
                                               const std::vector<cube::Selector>& selectors, bool by_record);

}  // namespace pcrf::post
