/// \file hazard_file.hpp
/// \brief A site's hazard curve read from CSV: intensity against mean annual rate of
/// exceedance [1/yr]. The file is untrusted: every refusal names the file, the line and the
/// problem (a UserError at the file and line), and nothing is allocated by a size the file gives.
///
/// Layout (docs/risk.md):
///     # any comment; blank lines are skipped
///     # period_s = 1.0            (required before the header when the measure is sa_g)
///     sa_g,annual_rate_per_yr      (the measure as a study spells it, then annual_rate_per_yr)
///     0.1,2.1e-2
///     0.5,2.1e-3
/// Intensities increase, rates are positive and decrease.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "pcrf/analysis/risk.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf::hazard {

struct HazardFile {
  std::filesystem::path file;
  std::string measure;               ///< "pga_g", "sa_g", … as the header names it
  std::optional<double> period_s;    ///< from `# period_s = …`
  std::size_t header_line = 0;       ///< where the measure is named (1-based)
  risk::HazardCurve curve;
  /// What the curve's numbers suggest is wrong with it (hazard_warnings): each a UserError at
  /// the file and line, not thrown; a front end prints it as a warning (or, with warnings as
  /// errors, throws it).
  std::vector<UserError> warnings;
};

/// Reads and checks the file. \throws UserError at the file and line.
HazardFile read_hazard_file(const std::filesystem::path& file, risk::Tail tail);

/// The largest file read (bytes) and the most points taken: a hazard curve has tens (USGS
/// and OpenQuake give 20 to 50), and λ_c's cost grows with them (risk.hpp: linear per
/// fragility, but a risk report integrates each frame's ~1000 bootstrap refits).
inline constexpr std::uintmax_t kMaxHazardFileBytes = 16u << 20;
inline constexpr std::size_t kMaxHazardPoints = 10000;

/// The largest intensity a hazard curve can plausibly reach: no ground motion has been
/// recorded above about 4.4 g of PGA (2008 Iwate–Miyagi) or 4 m/s of PGV, and a spectral
/// acceleration about 2.5 times the PGA; beyond these bounds a curve's intensities are taken
/// to be in other units than its header says (cm/s² or % g under pga_g: the curve reads 490 g).
inline constexpr double kMaxHazardAcceleration_g = 10.0;
inline constexpr double kMaxHazardVelocity_m_s = 10.0;
/// The least a curve's largest intensity can be under a guessed unit: a hazard curve runs up
/// to damaging shaking.
inline constexpr double kLeastHazardEnd_g = 0.1;
inline constexpr double kLeastHazardEnd_m_s = 0.1;
/// Rates whose first is at least this [1/yr] and none above 1 look like probabilities of
/// exceedance over a period (they saturate below 1), not annual rates.
inline constexpr double kProbabilityLikeRate_per_yr = 0.5;
/// The largest scale factor that hazard-consistent stripes may ask of a record before the
/// study warns that the curve's units or the records are not what they seem (a curve in
/// cm/s² under pga_g asks factors of 660–1991 of the far-field set).
inline constexpr double kMaxHazardScaleFactor = 100.0;

/// The curve's implausibilities, each naming the file, the line (`first_row`, `last_row`:
/// the lines of its first and last points) and the likely cause: a largest intensity beyond
/// kMaxHazardAcceleration_g (kMaxHazardVelocity_m_s), with the units that would make it
/// plausible; a first rate of at least kProbabilityLikeRate_per_yr with none above 1
/// (probabilities over a period in the rate column).
std::vector<UserError> hazard_warnings(const HazardFile& hazard, std::size_t first_row, std::size_t last_row);

}  // namespace pcrf::hazard
