/// \file pulse_identification.hpp
/// \brief Whether a recorded ground motion carries a strong velocity pulse, and its period T_p.
///
/// Baker, J. W. (2007), "Quantitative classification of near-fault ground motions using
/// wavelet analysis", Bull. Seismol. Soc. Am. 97(5), 1486–1501; and Shahi, S. K. & Baker,
/// J. W. (2014), "An efficient algorithm to identify strong-velocity pulses in multicomponent
/// ground motions", Bull. Seismol. Soc. Am. 104(5), 2456–2466.
///
/// The velocity v (cm/s, trapezoidal integral of the record from rest) is analysed with the
/// continuous wavelet transform on Daubechies' wavelet of order 4 (db4, support [0, 7]):
///
///     C(a, b) = a^{-1/2} Σ_m v_m ψ((m − b)/a + 7/2),   a the scale and b the centre, in samples.
///
/// The scales are Shahi & Baker's: 51 scales evenly spaced (whole samples) from the one whose
/// pseudo-period a·dt/F_c is 0.25 s to past 15 s (F_c = 5/7 Hz, db4's centre frequency as
/// MATLAB's centfrq gives it, which both papers' T_p use).
/// The largest |C| marks the pulse; its scale is refined to the whole sample between the
/// neighbouring scales (at the same centre), and ten wavelets of that scale are taken from
/// the record one after the other (matching pursuit: each from the residual left by the
/// previous ones, centred within 0.4 a of the first). Their sum is the pulse, v minus it the
/// residual, and T_p = a·dt/F_c the pseudo-period of the pulse's scale.
///
/// One component (Baker 2007): pulse-like when the pulse indicator
///     PI = 10 / (1 + exp(−23.3 + 14.6 PGV_ratio + 20.5 energy_ratio)) > 0.85
/// (PGV_ratio = PGV of the residual / PGV, energy_ratio = Σ residual² / Σ v²), the pulse
/// arrives early (its cumulative squared velocity reaches 10 % before the record's reaches
/// 20 %) and PGV ≥ 30 cm/s.
///
/// Two horizontals (Shahi & Baker 2014): the transform of the velocity along azimuth φ is
/// sin φ C_E + cos φ C_N (the transform is linear), so the largest coefficient over all
/// orientations is max √(C_E² + C_N²), at φ = atan2(C_E, C_N). Up to five candidate pulses
/// are taken at the five largest, each time blocking ±0.4 a samples around the one taken; each
/// is extracted as above from the velocity along its own φ and classified with
///     PC = 0.63 PGV_ratio + 0.777 energy_ratio,  P = (PC − 1.208421)/0.2462717,
///     V = (PGV[cm/s] − 11.58861)/18.88015,
///     I = −7.817 − 0.5679 P² − 0.1516 V² − 3.0253 P − 1.7396 V − 2.7156 P V  > 0,
/// and not late: the record has reached less than 17 % of its cumulative squared velocity
/// when the pulse reaches 5 % of its own. The record is pulse-like when a candidate is; T_p
/// is the first such candidate's.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "pcrf/record/ground_motion.hpp"
#include "pcrf/record/horizontal_pair.hpp"

namespace pcrf {

/// Daubechies' orthonormal wavelet with four vanishing moments (db4), tabulated.
class Db4Wavelet {
 public:
  /// The eight low-pass filter coefficients h_k (Σ h_k = √2, Σ h_k² = 1; Daubechies 1992,
  /// Ten Lectures on Wavelets, Table 6.1, N = 4).
  static const std::vector<double>& lowpass();
  /// ψ(x) on [0, 7] (0 outside), linear between the points of the dyadic table (2⁻¹⁰ apart)
  /// built by the cascade (two-scale) relation from φ at the integers.
  static double psi(double x);
  /// The frequency [Hz per unit of x] where |Fourier transform of ψ| peaks among the
  /// frequencies k/7 of its Fourier series on [0, 7], as MATLAB's centfrq: 5/7.
  static double centre_frequency();
};

/// Which classification a result follows.
enum class PulseMethod { kBaker2007, kShahiBaker2014 };
std::string to_string(PulseMethod method);  ///< "baker-2007", "shahi-baker-2014"

/// One extracted pulse and its classification.
struct PulseCandidate {
  double azimuth_deg = 0.0;      ///< orientation analysed (pairs; for one component its own azimuth or 0)
  double period_s = 0.0;         ///< T_p, the pseudo-period of the pulse's wavelets [s]
  double scale_samples = 0.0;    ///< the wavelets' scale a [samples]
  double centre_s = 0.0;         ///< where the largest wavelet is centred [s]
  double pgv_cm_s = 0.0;         ///< PGV of the velocity in this orientation [cm/s]
  double pgv_ratio = 0.0;        ///< PGV of the residual / PGV [-]
  double energy_ratio = 0.0;     ///< Σ residual² / Σ v² [-]
  double pulse_indicator = 0.0;  ///< PI (Baker 2007, pulse above 0.85) or I (Shahi & Baker, pulse above 0)
  bool late = false;             ///< the pulse arrives late (the method's criterion)
  bool pulse_like = false;
  std::vector<double> velocity_cm_s;  ///< v in this orientation, one value per sample
  std::vector<double> pulse_cm_s;     ///< the extracted pulse
  std::vector<double> residual_cm_s;  ///< v minus the pulse
};

struct PulseClassification {
  PulseMethod method = PulseMethod::kBaker2007;
  double dt_s = 0.0;
  bool pulse_like = false;
  double period_s = 0.0;      ///< T_p of the deciding candidate [s]; 0 when not pulse-like
  std::size_t decided_by = 0; ///< the candidate that decided (the first pulse-like one, else 0)
  std::vector<PulseCandidate> candidates;
};

/// Baker (2007) on one component.
/// \throws UserError when the record is too short for the shortest scale.
PulseClassification classify_pulse(const GroundMotion& record);
/// Shahi & Baker (2014) on a station's two horizontals (any azimuths that span the plane).
/// \throws UserError as project(), or when the record is too short.
PulseClassification classify_pulse(const HorizontalPair& pair);

/// The trapezoidal velocity of a record from rest [cm/s].
std::vector<double> velocity_cm_s(const GroundMotion& record);

}  // namespace pcrf
