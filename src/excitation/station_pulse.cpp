// Pulse identification of a station's record (see station_pulse.hpp).
#include "pcrf/excitation/station_pulse.hpp"

#include "pcrf/user_error.hpp"

namespace pcrf {

PulseClassification classify_station_pulse(const StationRecord& station) {
  if (!station.h2) return classify_pulse(station.h1);
  if (!station.az1_deg || !station.az2_deg)
    throw UserError("azimuth_deg",
                    "the azimuths of the two horizontals are not known (their files state none): give {} and {}",
                    {"azimuth_deg", "h2_azimuth_deg"});
  return classify_pulse(HorizontalPair{station.h1, *station.az1_deg, *station.h2, *station.az2_deg});
}

}  // namespace pcrf
