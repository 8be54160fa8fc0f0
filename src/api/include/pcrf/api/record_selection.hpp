/// \file record_selection.hpp
/// \brief What `pcrf record select --json` prints and `pcrf.select` returns: the target, the
/// selected records (name, kind, files, scale, scaled ln Sa) and the fit, as one JSON object.
#pragma once

#include "pcrf/json.hpp"
#include "pcrf/record/record_library.hpp"
#include "pcrf/record/selection.hpp"

namespace pcrf::api {

JsonObject selection_json(const SelectionTarget& target, const SpectraTable& table, const SelectionResult& result);

}  // namespace pcrf::api
