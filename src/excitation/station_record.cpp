// A station's components put together for a frame (see station_record.hpp).
#include "pcrf/excitation/station_record.hpp"

#include "pcrf/user_error.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>

#include "pcrf/number_text.hpp"
#include "pcrf/record/horizontal_pair.hpp"
#include "pcrf/record/rotd.hpp"

namespace pcrf {

std::vector<std::string> StationRecord::align() {
  std::vector<GroundMotion*> parts{&h1};
  if (h2) parts.push_back(&*h2);
  if (up) parts.push_back(&*up);
  std::size_t longest = 0;
  for (GroundMotion* g : parts) {
    if (!same_sample_interval(g->dt_s(), h1.dt_s()))
      throw UserError("components '" + h1.name() + "' and '" + g->name() + "' are sampled at different intervals (" +
                                  number_text(h1.dt_s()) + " s and " + number_text(g->dt_s()) + " s)");
    // The same interval up to rounding (19.9 s / 1990 steps against 0.01 s): h1's, bit for bit.
    if (g->dt_s() != h1.dt_s()) *g = GroundMotion(g->name(), h1.dt_s(), g->samples_m_s2());
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

bool is_downward_component(const std::string& component) {
  if (component.size() < 3) return false;
  std::string tail = component.substr(component.size() - 3);
  for (char& c : tail) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return tail == "DWN";
}

namespace {

std::optional<double> stated_azimuth(const StationComponent& part, const char* role) {
  if (is_vertical_component(part.component))
    throw UserError(part.label + ": its header names a vertical component ('" + part.component + "'), given as " +
                                role);
  return azimuth_of_component(part.component);
}

}  // namespace

StationRecord make_station(StationComponent h1, std::optional<double> az1_deg, std::optional<StationComponent> h2,
                           std::optional<double> az2_deg, std::optional<StationComponent> up,
                           std::vector<std::string>& notes) {
  if (!az1_deg) az1_deg = stated_azimuth(h1, "the first horizontal");
  StationRecord station{std::move(h1.motion), az1_deg, std::nullopt, az2_deg, std::nullopt};
  if (h2) {
    if (!station.az2_deg) station.az2_deg = stated_azimuth(*h2, "the second horizontal");
    station.h2 = std::move(h2->motion);
  }
  if (up) {
    if (!up->component.empty() && azimuth_of_component(up->component))
      throw UserError(up->label + ": its header names a horizontal component ('" + up->component +
                                  "'), given as the vertical");
    if (is_downward_component(up->component)) {
      notes.push_back("vertical component '" + up->component + "' (" + up->label +
                      ") is positive down: negated to positive up");
      station.up = up->motion.scaled(-1.0);
    } else {
      station.up = std::move(up->motion);
    }
  }
  for (auto& note : station.align()) notes.push_back(std::move(note));
  return station;
}

GroundMotion in_plane_motion(const StationRecord& record, std::optional<double> incidence_deg) {
  if (!incidence_deg) return record.h1;
  if (!record.h2 || !record.az1_deg || !record.az2_deg)
    throw UserError("an incidence needs both horizontal components and their azimuths ('" + record.h1.name() +
                                "' " + (record.h2 ? "has no azimuth" : "has no second component") + ")");
  if (record.h2->size() != record.h1.size())
    throw UserError("the components of '" + record.h1.name() + "' are not aligned");
  return project(HorizontalPair{record.h1, *record.az1_deg, *record.h2, *record.az2_deg}, *incidence_deg);
}

ScaledExcitation frame_excitation(const StationRecord& record, std::optional<double> incidence_deg, double factor) {
  const GroundMotion horizontal = in_plane_motion(record, incidence_deg);
  if (!record.up) return ScaledExcitation(Excitation(horizontal), factor);
  if (record.up->size() != horizontal.size())
    throw UserError("the vertical component '" + record.up->name() + "' is not aligned with '" + record.h1.name() + "'");
  return ScaledExcitation(Excitation(horizontal, &*record.up), factor);
}

double station_intensity(const StationRecord& record, std::optional<double> incidence_deg, const IntensitySpec& spec) {
  const int percentile = rotd_percentile(spec.measure);
  if (percentile == 0) return intensity_of(in_plane_motion(record, incidence_deg), spec);
  if (!record.h2 || !record.az1_deg || !record.az2_deg)
    throw UserError(to_string(spec.measure) + " needs both horizontal components and their azimuths ('" +
                                record.h1.name() + "' " + (record.h2 ? "has no azimuth" : "has no second component") + ")");
  const RotD both = rotd(HorizontalPair{record.h1, *record.az1_deg, *record.h2, *record.az2_deg}, spec);
  return percentile == 50 ? both.rotd50 : both.rotd100;
}

}  // namespace pcrf
