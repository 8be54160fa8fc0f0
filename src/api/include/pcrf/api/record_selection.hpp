/// \file record_selection.hpp
/// \brief What `pcrf record select --json` prints and `pcrf.select` returns: the target, the
/// selected records (name, kind, files, scale, scaled ln Sa) and the fit, as one JSON object.
#pragma once

#include "pcrf/json.hpp"
#include "pcrf/record/record_library.hpp"
#include "pcrf/record/selection.hpp"

namespace pcrf::api {

/// A selection target (read_selection_target) and a spectra table (read_spectra_csv) read from
/// their files, as both front ends read them: regular files only, so a FIFO, a folder or a
/// device is refused at once, naming the file (issue 41: no read blocks).
/// \throws UserError naming the file and the problem.
SelectionTarget read_selection_target_file(const std::string& path);
SpectraTable read_spectra_table_file(const std::string& path);

JsonObject selection_json(const SelectionTarget& target, const SpectraTable& table, const SelectionResult& result);

}  // namespace pcrf::api
