/// \file station_record.hpp
/// \brief The components a station recorded, put together for a frame: the in-plane
/// horizontal at the frame's incidence, and the vertical.
///
/// A frame stands in a vertical plane whose azimuth (degrees clockwise from north) is its
/// incidence φ. It feels the ground's horizontal acceleration projected on that plane
/// (horizontal_pair.hpp: exact also for pairs that are not orthogonal) and the vertical
/// acceleration. Without an incidence the frame lies along the first component (φ = az₁),
/// whose motion it then feels bit for bit as if the second did not exist; φ + 180° is the
/// mirrored frame.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pcrf/excitation/excitation.hpp"
#include "pcrf/record/ground_motion.hpp"
#include "pcrf/record/intensity.hpp"

namespace pcrf {

/// How a component beside the first horizontal (h1) enters what a frame feels, which also
/// decides what its file's header may say (make_station).
enum class Enters {
  kInPlane,   ///< with h1, projected on the frame's plane at its incidence (in_plane_motion) and in
              ///< RotD measures; its header states its azimuth (az2_deg) and must not name a vertical
  kVertical,  ///< as the vertical ground acceleration ü_v, positive up (Excitation); a header naming
              ///< a horizontal is refused, a `DWN` channel negated
};

/// A component a station may have beside its first horizontal, and what each front end calls
/// it: a study's `[[records]]` key, `pcrf run`'s flag (the keyword's, flag_name()), `pcrf
/// record`'s flag, Python's keywords. Each is read like the first horizontal (a file, or in
/// Python an array of accelerations in g) and aligned with it.
struct ComponentInfo {
  std::string_view key;            ///< the study's key and the station's member: "h2"
  std::string_view role;           ///< in messages: "the second horizontal"
  std::string_view doc;            ///< help text of its flags
  std::string_view keyword;        ///< Python's keyword of its file ("record_h2"); `pcrf run`'s flag is its flag_name
  std::string_view array_keyword;  ///< Python's keyword of it as an array of accelerations [g]
  std::string_view record_flag;    ///< `pcrf record`'s flag of its file
  std::string_view measures_key;   ///< its object in `pcrf record`'s JSON
  Enters enters;
};

/// Every component beside h1, in the order front ends list them. A new one is a row here, a
/// member of StationRecord, StationParts and study::RecordSource, and its name in
/// component_members().
inline constexpr std::array kStationComponents{
    ComponentInfo{"h2", "the second horizontal", "the station's other horizontal component", "record_h2",
                  "ground_accel_h2_g", "--pair", "pair", Enters::kInPlane},
    ComponentInfo{"up", "the vertical", "the station's vertical component, positive up", "record_up",
                  "ground_accel_up_g", "--up", "up", Enters::kVertical},
};
inline constexpr std::size_t kComponentCount = kStationComponents.size();

/// One value per component of kStationComponents, in its order.
template <class T>
using PerComponent = std::array<T, kComponentCount>;

/// The members of `S` (StationRecord, StationParts, study::RecordSource) that hold the components of
/// kStationComponents, in its order.
template <class S>
constexpr auto component_members() {
  return PerComponent<decltype(&S::h2)>{&S::h2, &S::up};
}

/// `items` as a sentence lists them: "a", "a and b", "a, b and c".
std::string and_list(const std::vector<std::string>& items);

/// A station's components, aligned. (The components are initialised, so that records written
/// as {h1, az1, h2, az2, up} stay complete when a component is added.)
struct StationRecord {
  GroundMotion h1;
  std::optional<double> az1_deg;                  ///< where h1 was recorded along; needed with an incidence
  std::optional<GroundMotion> h2 = std::nullopt;  ///< the other horizontal component
  std::optional<double> az2_deg;
  std::optional<GroundMotion> up = std::nullopt;  ///< vertical, positive up

  /// Brings the components to one time axis: the shorter ones are padded with zeros to the
  /// longest (a note for each, naming it and both lengths).
  /// \throws UserError naming the components when their dt differ.
  std::vector<std::string> align();
};

/// One component file as read: its motion and the component name its header states ("230",
/// "UP", "H-DLTDWN"; empty when the file states none), and what to call it in messages.
struct StationComponent {
  GroundMotion motion;
  std::string component;
  std::string label;  ///< the file, for messages
};

/// True for a vertical channel that PEER names `DWN` (e.g. "H-DLTDWN", "AREDWN"): its
/// positive direction is down, as a horizontal's name states the azimuth its positive
/// values point to (docs/vertical_excitation.md, "Records").
bool is_downward_component(const std::string& component);

/// A station's component files as read, before they are put together (make_station): the
/// members of StationRecord, initialised as there.
struct StationParts {
  StationComponent h1;
  std::optional<double> az1_deg;  ///< given; else from h1's header
  std::optional<StationComponent> h2 = std::nullopt;
  std::optional<double> az2_deg;  ///< given; else from h2's header
  std::optional<StationComponent> up = std::nullopt;
};

/// A station put together from its component files, the one way `pcrf run`, `pcrf record`
/// and studies do it: each horizontal's azimuth from its header's component name unless
/// given, a vertical channel given as a horizontal (or a horizontal as the vertical)
/// refused, a `DWN` vertical negated to positive up (with a note), the components aligned
/// (align(); its notes appended to `notes`).
/// \throws UserError naming the file and the problem.
StationRecord make_station(StationParts parts, std::vector<std::string>& notes);
/// The same, the parts one by one.
inline StationRecord make_station(StationComponent h1, std::optional<double> az1_deg, std::optional<StationComponent> h2,
                                  std::optional<double> az2_deg, std::optional<StationComponent> up,
                                  std::vector<std::string>& notes) {
  return make_station(StationParts{std::move(h1), az1_deg, std::move(h2), az2_deg, std::move(up)}, notes);
}

/// What a frame at `incidence_deg` feels from `record` scaled by `factor`: the in-plane
/// horizontal (in_plane_motion) and the vertical, each scaled.
/// \throws UserError when an incidence is given without both horizontal
/// components and their azimuths, or the components are not aligned (StationRecord::align).
ScaledExcitation frame_excitation(const StationRecord& record, std::optional<double> incidence_deg, double factor);

/// The in-plane horizontal motion of a frame at `incidence_deg` (unscaled), for intensity
/// measures of what the frame feels. \throws as frame_excitation.
GroundMotion in_plane_motion(const StationRecord& record, std::optional<double> incidence_deg);

/// The station's value of an intensity measure: for a RotD measure of its horizontal pair
/// (rotd.hpp: the frame's orientation plays no part), else of the in-plane motion at
/// `incidence_deg` (in_plane_motion). \throws UserError when a RotD measure
/// has no pair or no azimuths, or as in_plane_motion.
double station_intensity(const StationRecord& record, std::optional<double> incidence_deg, const IntensitySpec& spec);

}  // namespace pcrf
