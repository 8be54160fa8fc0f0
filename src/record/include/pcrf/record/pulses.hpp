/// \file pulses.hpp
/// \brief Closed-form acceleration pulses, the excitations of rocking spectra.
///
/// Each pulse has a period T_p and an amplitude a_p, its peak |acceleration|. Its formula,
/// with ω_p = 2π/T_p and τ = t − t₀ the time since the pulse's start (or centre):
///
///   pulse-sine    one-sine, Makris type A (Zhang & Makris 2001):
///                 a = a_p sin(ω_p τ), 0 ≤ τ ≤ T_p.                        PGV = a_p T_p / π
///   pulse-cosine  one-cosine, type B (Zhang & Makris 2001):
///                 a = a_p cos(ω_p τ), 0 ≤ τ ≤ T_p.                        PGV = a_p T_p / (2π)
///   pulse-cycles  n cycles, type Cₙ (Makris & Roussos 2000):
///                 a = a_p cos(ω_p τ + φ), 0 ≤ τ ≤ (n + ½ − φ/π) T_p, φ the root in (0, π/2)
///                 of 2 cos φ = ((2n + 1)π − 2φ) sin φ, which brings the ground back to rest
///                 where it started (φ = 0.0697π for C₁, 0.0410π for C₂).
///                                                                         PGV = a_p T_p (1 + sin φ) / (2π)
///   ricker        symmetric Ricker wavelet (the second derivative of a Gaussian; Vassiliou &
///                 Makris 2011): a = a_p (1 − s²) e^{−s²/2}, s = τ/σ, σ = T_p/(√2 π), so that
///                 its Fourier amplitude peaks at 1/T_p; |s| ≤ 6.              PGV = a_p σ e^{−1/2}
///   ricker-antisymmetric  the third derivative: a = a_p s (3 − s²) e^{−s²/2} / c, σ = √3 T_p/(2π),
///                 c = max s(3 − s²) e^{−s²/2} (at s² = 3 − √6); |s| ≤ 6.    PGV = a_p σ / c
///   mavroeidis    Mavroeidis & Papageorgiou (2003): the velocity
///                 v = (A/2) (1 + cos(ω_p τ/γ)) cos(ω_p τ + ν), |τ| ≤ γ T_p/2, γ > 1, and its
///                 derivative as the acceleration, A chosen so that max |a| = a_p. PGV = A at ν = 0.
///
/// The record's PGA is a_p exactly: the pulse's peak falls on a sample. Pulses that start
/// smoothly (pulse-sine, the wavelets, mavroeidis) start at a delay below one sample
/// interval after t = 0, chosen for that. Pulses that start with a jump in acceleration
/// (pulse-cosine, pulse-cycles) start at t = 0 on the first sample, which a record linear
/// between samples represents exactly, and pulse-cycles uses the largest sample interval
/// ≤ dt_s that puts its peak on a sample. A jump at a pulse's end (pulse-cosine,
/// pulse-cycles) is a ramp over one sample interval, an O(dt) change of the final ground
/// velocity (its peak velocity, earlier, is not affected). A pulse record lasts as long as
/// the pulse (rounded up to a sample), or `duration_s` when that is longer.
#pragma once

#include <string>
#include <vector>

#include "pcrf/record/ground_motion.hpp"

namespace pcrf {

enum class PulseShape { kSine, kCosine, kCycles, kRicker, kRickerAntisymmetric, kMavroeidis };

struct PulseSpec {
  PulseShape shape = PulseShape::kSine;
  double period_s = 0.5;     ///< T_p [s], at least 4 dt
  double amplitude_g = 0.5;  ///< a_p, the peak |acceleration| [g]
  int cycles = 1;            ///< n of pulse-cycles (≥ 1)
  double gamma = 2.0;        ///< γ > 1 of mavroeidis: the number of oscillations in the envelope
  double nu_deg = 0.0;       ///< ν of mavroeidis: the phase of the oscillation [deg]
  double duration_s = 0.0;   ///< record length [s]; 0: the pulse's own length
  double dt_s = 0.005;       ///< sample interval [s]
};

/// The pulse's kind as written in a synthetic record's text ("pulse-sine", …, "mavroeidis").
std::string pulse_kind(PulseShape shape);
/// Every shape, in the order above.
std::vector<PulseShape> pulse_shapes();

/// The record of a pulse.
/// \throws UserError naming the field (period_s ≤ 0 or below 4 dt, a non-positive
/// or non-finite amplitude or dt, cycles < 1, γ ≤ 1, a non-finite ν, more than 1e8 samples).
GroundMotion make_pulse(const PulseSpec& spec);

/// φ of the Cₙ pulse with n cycles [rad] (see above). \throws UserError for n < 1.
double cycles_pulse_phase_rad(int cycles);

/// The peak ground velocity of the continuous pulse, from its formula [m/s].
double pulse_peak_velocity_m_s(const PulseSpec& spec);

}  // namespace pcrf
