// A station's components put together for a frame (see station_record.hpp).
#include "pcrf/excitation/station_record.hpp"

#include <algorithm>
#include <stdexcept>

#include "pcrf/record/horizontal_pair.hpp"

namespace pcrf {

std::vector<std::string> StationRecord::align() {
  std::vector<GroundMotion*> parts{&h1};
  if (h2) parts.push_back(&*h2);
  if (up) parts.push_back(&*up);
  std::size_t longest = 0;
  for (const GroundMotion* g : parts) {
    if (g->dt_s() != h1.dt_s())
      throw std::invalid_argument("components '" + h1.name() + "' and '" + g->name() + "' are sampled at different intervals (" +
                                  std::to_string(h1.dt_s()) + " s and " + std::to_string(g->dt_s()) + " s)");
    longest = std::max(longest, g->size());
  }
  std::vector<std::string> notes;
  for (GroundMotion* g : parts) {
    if (g->size() == longest) continue;
    notes.push_back("component '" + g->name() + "' has " + std::to_string(g->size()) + " samples, padded with zeros to " +
                    std::to_string(longest) + " to match the longest");
    *g = padded(*g, longest);
  }
  return notes;
}

GroundMotion in_plane_motion(const StationRecord& record, std::optional<double> incidence_deg) {
  if (!incidence_deg) return record.h1;
  if (!record.h2 || !record.az1_deg || !record.az2_deg)
    throw std::invalid_argument("an incidence needs both horizontal components and their azimuths ('" + record.h1.name() +
                                "' " + (record.h2 ? "has no azimuth" : "has no second component") + ")");
  if (record.h2->size() != record.h1.size())
    throw std::invalid_argument("the components of '" + record.h1.name() + "' are not aligned");
  return project(HorizontalPair{record.h1, *record.az1_deg, *record.h2, *record.az2_deg}, *incidence_deg);
}

FrameExcitation::FrameExcitation(const StationRecord& record, std::optional<double> incidence_deg, double factor)
    : horizontal_(in_plane_motion(record, incidence_deg).scaled(factor)) {
  if (record.up) {
    if (record.up->size() != horizontal_.size())
      throw std::invalid_argument("the vertical component '" + record.up->name() + "' is not aligned with '" +
                                  record.h1.name() + "'");
    vertical_.emplace(record.up->scaled(factor));
  }
}

}  // namespace pcrf
