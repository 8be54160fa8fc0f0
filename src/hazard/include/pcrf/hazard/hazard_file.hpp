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

#include "pcrf/analysis/risk.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf::hazard {

struct HazardFile {
  std::filesystem::path file;
  std::string measure;               ///< "pga_g", "sa_g", … as the header names it
  std::optional<double> period_s;    ///< from `# period_s = …`
  std::size_t header_line = 0;       ///< where the measure is named (1-based)
  risk::HazardCurve curve;
};

/// Reads and checks the file. \throws UserError at the file and line.
HazardFile read_hazard_file(const std::filesystem::path& file, risk::Tail tail);

/// The largest file read (bytes) and the most points taken: a hazard curve has tens.
inline constexpr std::uintmax_t kMaxHazardFileBytes = 16u << 20;
inline constexpr std::size_t kMaxHazardPoints = 100000;

}  // namespace pcrf::hazard
