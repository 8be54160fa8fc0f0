// RotD50 and RotD100 of a horizontal pair (see rotd.hpp).
#include "pcrf/record/rotd.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace pcrf {

RotD rotd(const HorizontalPair& pair, const IntensitySpec& spec) {
  // Both components on one time axis, as long as the longer one (project() checks dt and
  // the azimuths).
  const std::size_t n = project(pair, pair.az1_deg).size();
  const std::vector<double> s1 = intensity_series(padded(pair.h1, n), spec);
  const std::vector<double> s2 = intensity_series(padded(pair.h2, n), spec);
  constexpr int kAngles = 180;
  std::array<double, kAngles> peaks{};
  for (int k = 0; k < kAngles; ++k) {
    const ProjectionWeights w = projection_weights(pair.az1_deg, pair.az2_deg, pair.az1_deg + k);
    double peak = 0.0;
    for (std::size_t i = 0; i < s1.size(); ++i) peak = std::max(peak, std::fabs(w.w1 * s1[i] + w.w2 * s2[i]));
    peaks[static_cast<std::size_t>(k)] = peak;
  }
  std::sort(peaks.begin(), peaks.end());
  return {0.5 * (peaks[kAngles / 2 - 1] + peaks[kAngles / 2]), peaks.back()};
}

}  // namespace pcrf
