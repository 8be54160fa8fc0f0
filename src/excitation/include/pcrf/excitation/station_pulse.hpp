/// \file station_pulse.hpp
/// \brief Whether a station's record is pulse-like, and its T_p: the method its components
/// allow (record/pulse_identification.hpp). One rule for `pcrf record pulse`, `pcrf.pulse` and
/// a study's [outputs] record_pulses.
#pragma once

#include "pcrf/excitation/station_record.hpp"
#include "pcrf/record/pulse_identification.hpp"

namespace pcrf {

/// Baker (2007) on the first horizontal alone, or Shahi & Baker (2014) when the station has
/// both horizontals. \throws UserError (key "azimuth_deg") when a pair's azimuths are not
/// known, or as classify_pulse().
PulseClassification classify_station_pulse(const StationRecord& station);

}  // namespace pcrf
