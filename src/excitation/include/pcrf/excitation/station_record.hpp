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

#include <optional>
#include <string>
#include <vector>

#include "pcrf/excitation/excitation.hpp"
#include "pcrf/record/ground_motion.hpp"
#include "pcrf/record/intensity.hpp"

namespace pcrf {

struct StationRecord {
  GroundMotion h1;
  std::optional<double> az1_deg;   ///< where h1 was recorded along; needed with an incidence
  std::optional<GroundMotion> h2;  ///< the other horizontal component
  std::optional<double> az2_deg;
  std::optional<GroundMotion> up;  ///< vertical, positive up

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

/// A station put together from its component files, the one way `pcrf run`, `pcrf record`
/// and studies do it: each horizontal's azimuth from its header's component name unless
/// given, a vertical channel given as a horizontal (or a horizontal as the vertical)
/// refused, a `DWN` vertical negated to positive up (with a note), the components aligned
/// (align(); its notes appended to `notes`).
/// \throws UserError naming the file and the problem.
StationRecord make_station(StationComponent h1, std::optional<double> az1_deg, std::optional<StationComponent> h2,
                           std::optional<double> az2_deg, std::optional<StationComponent> up,
                           std::vector<std::string>& notes);

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
