/// \file record_pulse.hpp
/// \brief What `pcrf record pulse` prints and `pcrf.pulse` returns: whether a record is
/// pulse-like and its T_p (record/pulse_identification.hpp), as one JSON object.
#pragma once

#include "pcrf/excitation/station_pulse.hpp"
#include "pcrf/json.hpp"
#include "pcrf/record/pulse_identification.hpp"

namespace pcrf::api {

/// Baker (2007) on the first horizontal alone, or Shahi & Baker (2014) on a pair
/// (excitation/station_pulse.hpp).
using ::pcrf::classify_station_pulse;

/// The classification as JSON: method, pulse_like, period_s, and each candidate's measures;
/// with `series`, the deciding candidate's velocity, pulse and residual [cm/s] as well.
JsonObject pulse_json(const PulseClassification& result, bool series);

}  // namespace pcrf::api
