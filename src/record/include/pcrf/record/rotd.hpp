/// \file rotd.hpp
/// \brief Orientation-independent intensity of a horizontal pair: RotD50 and RotD100.
///
/// Boore, D. M. (2010), "Orientation-independent, nongeometric-mean measures of seismic
/// intensity from two horizontal components of motion", Bull. Seismol. Soc. Am. 100(4),
/// 1830–1835. The pair's motion is projected on the azimuths φ = az₁ + k·1°, k = 0 … 179
/// (horizontal_pair.hpp: also for pairs that are not orthogonal); each projection's peak is
/// taken as intensity_of() takes it. RotD100 is the largest of the 180 peaks and RotD50
/// their median. Sa of a projection is the same projection of the two components'
/// oscillator responses (the oscillator is linear), so each component is integrated once.
#pragma once

#include "pcrf/record/horizontal_pair.hpp"
#include "pcrf/record/intensity.hpp"

namespace pcrf {

struct RotD {
  double rotd50;   ///< median over azimuth, in the measure's units
  double rotd100;  ///< largest over azimuth, in the measure's units
};

/// RotD50 and RotD100 of `spec`'s measure for the pair.
/// \throws UserError as project() and spectral_acceleration_g().
RotD rotd(const HorizontalPair& pair, const IntensitySpec& spec);

}  // namespace pcrf
