/// \file horizontal_pair.hpp
/// \brief The ground's horizontal acceleration along any azimuth, from the two horizontal
/// components a station recorded.
///
/// A component recorded along azimuth az (degrees clockwise from north) is the projection
/// of the horizontal acceleration vector a on that direction: a_az = a · (sin az, cos az) in
/// (east, north). Two components along az₁ ≠ az₂ (± 180°) give the vector back, and with it
/// the projection on any azimuth φ:
///
///     a_φ = w₁ a₁ + w₂ a₂,   w₁ = sin(az₂ − φ) / sin(az₂ − az₁),   w₂ = sin(φ − az₁) / sin(az₂ − az₁).
///
/// For an orthogonal pair (az₂ = az₁ + 90°) this is a₁ cos(φ − az₁) + a₂ sin(φ − az₁); it
/// holds as well for pairs that are not orthogonal (Lucerne's LCN260 and LCN345 are 85°
/// apart). At φ = az₁ the weights are exactly 1 and 0, and φ + 180° gives exactly the
/// negated weights, so the projection is then −a_φ bit for bit.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "pcrf/record/ground_motion.hpp"

namespace pcrf {

/// The weights of the two components in the projection on azimuth `phi_deg`.
struct ProjectionWeights {
  double w1;
  double w2;
};
/// \throws UserError when the two azimuths are parallel (within 1°: the pair
/// does not span the plane) or any azimuth is not finite.
ProjectionWeights projection_weights(double az1_deg, double az2_deg, double phi_deg);

/// Two horizontal components of one station and the azimuths they were recorded along.
struct HorizontalPair {
  const GroundMotion& h1;
  double az1_deg;
  const GroundMotion& h2;
  double az2_deg;
};

/// The acceleration along `phi_deg`, sample by sample; the shorter component is taken as
/// zero after its end (the record is as long as the longer one). Named
/// "<h1 name>@<phi>deg".
/// \throws UserError when the components' dt differ (naming both), or as
/// projection_weights().
GroundMotion project(const HorizontalPair& pair, double phi_deg);

/// `record` with zeros appended up to `samples` samples (unchanged when it has as many).
GroundMotion padded(const GroundMotion& record, std::size_t samples);

/// The azimuth a component name states: a number of degrees ("230", "H-E07140", "LCN345",
/// "MUL009"), or a compass letter after a dash ("CHY101-N" 0°, "-E" 90°, "-S" 180°, "-W"
/// 270°). Empty for vertical components (is_vertical_component) and for names that state
/// no azimuth ("CLW-LN", "ABBAR--T").
std::optional<double> azimuth_of_component(const std::string& component);

/// The problem when angles given in degrees all look like radians: every value within ±2π
/// and not all whole degrees (3.7, meant as 212°, would run at 3.7°). It shows the first
/// such value in degrees and names the key as "{}", for the front end to spell
/// (pcrf/user_error.hpp: a warning is a UserError(key, problem, {key}) not thrown); ""
/// otherwise (0, 90, 12.5 and 370 do not warn: 12.5 is above 2π, 0 and 90 are whole degrees).
std::string radians_problem(const std::vector<double>& values_deg);

/// True for the vertical channels of PEER records: "UP", "-UP", "-V", "DWN", "VER".
bool is_vertical_component(const std::string& component);

}  // namespace pcrf
