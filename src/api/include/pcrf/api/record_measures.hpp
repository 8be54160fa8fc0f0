/// \file record_measures.hpp
/// \brief What `pcrf record` prints and `pcrf.record_measures` returns: a station's intensity
/// measures (PGA, PGV, PGD, Arias, D5–95, Sa at each period), its header metadata, RotD50 and
/// RotD100 of a horizontal pair, and the measures of the vertical, as one JSON object.
#pragma once

#include <vector>

#include "pcrf/api/record_input.hpp"
#include "pcrf/json.hpp"

namespace pcrf::api {

/// The oscillators of the spectral accelerations.
struct MeasureRequest {
  std::vector<double> periods_s;
  double damping = 0.05;
};

/// \throws UserError for a damping outside [0, 1) or a period that is not positive.
void check_measure_request(const MeasureRequest& request);

/// The measures of `station` (loaded from `input`, which names its files' headers).
/// \throws UserError for values that overflow the measures, a period below 2·dt, or a pair
/// whose azimuths are not known.
JsonObject record_measures(const StationRecord& station, const RecordInput& input, const MeasureRequest& request);

}  // namespace pcrf::api
