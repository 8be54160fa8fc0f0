/// \file record_pulse.hpp
/// \brief What `pcrf record pulse` prints and `pcrf.pulse` returns: whether a record is
/// pulse-like and its T_p (record/pulse_identification.hpp), as one JSON object.
#pragma once

#include "pcrf/excitation/station_record.hpp"
#include "pcrf/json.hpp"
#include "pcrf/record/pulse_identification.hpp"

namespace pcrf::api {

/// Baker (2007) on the first horizontal alone, or Shahi & Baker (2014) when the station has
/// both horizontals. \throws UserError when a pair's azimuths are not known.
PulseClassification classify_station_pulse(const StationRecord& station);

/// The classification as JSON: method, pulse_like, period_s, and each candidate's measures;
/// with `series`, the deciding candidate's velocity, pulse and residual [cm/s] as well.
JsonObject pulse_json(const PulseClassification& result, bool series);

}  // namespace pcrf::api
