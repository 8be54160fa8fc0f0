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

std::string and_list(const std::vector<std::string>& items) {
  std::string text;
  for (std::size_t i = 0; i < items.size(); ++i)
    text += (i == 0 ? "" : i + 1 == items.size() ? " and " : ", ") + items[i];
  return text;
}

std::vector<std::string> StationRecord::align() {
  std::vector<GroundMotion*> parts{&h1};
  for (const auto member : component_members<StationRecord>())
    if (this->*member) parts.push_back(&*(this->*member));
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

/// The motion of `part`, given as `info`'s component, checked by its header as `info.enters`
/// asks; the in-plane component's azimuth from its header into `station` unless given.
GroundMotion checked_component(const ComponentInfo& info, StationComponent&& part, StationRecord& station,
                               std::vector<std::string>& notes) {
  const std::string role(info.role);
  if (info.enters == Enters::kInPlane && !station.az2_deg) station.az2_deg = stated_azimuth(part, role.c_str());
  if (info.enters != Enters::kVertical) return std::move(part.motion);
  if (!part.component.empty() && azimuth_of_component(part.component))
    throw UserError(part.label + ": its header names a horizontal component ('" + part.component + "'), given as " + role);
  if (!is_downward_component(part.component)) return std::move(part.motion);
  notes.push_back("vertical component '" + part.component + "' (" + part.label + ") is positive down: negated to positive up");
  return part.motion.scaled(-1.0);
}

}  // namespace

StationRecord make_station(StationParts parts, std::vector<std::string>& notes) {
  if (!parts.az1_deg) parts.az1_deg = stated_azimuth(parts.h1, "the first horizontal");
  StationRecord station{std::move(parts.h1.motion), parts.az1_deg, std::nullopt, parts.az2_deg, std::nullopt};
  const auto given = component_members<StationParts>();
  const auto kept = component_members<StationRecord>();
  for (std::size_t i = 0; i < kComponentCount; ++i)
    if (auto& part = parts.*given[i]) station.*kept[i] = checked_component(kStationComponents[i], std::move(*part), station, notes);
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
