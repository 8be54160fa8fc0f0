/// \file synthetic.hpp
/// \brief Ground motions the engine makes itself, so that the demo and tests need no file.
///
/// Both generators are deterministic: the same arguments give the same samples on every
/// machine (the stochastic record uses std::mt19937_64 and its own normal transform, not
/// std::normal_distribution, whose output is implementation-defined).
#pragma once

#include <cstdint>
#include <string>

#include "pcrf/record/ground_motion.hpp"

namespace pcrf {

/// A train of full sine cycles a(t) = A sin(2π t / T_p) for 0 ≤ t < n·T_p, then zero
/// until duration_s.
struct SinePulseSpec {
  double amplitude_g = 0.5;   ///< peak acceleration A [g]
  double period_s = 0.5;      ///< T_p [s]
  int cycles = 2;             ///< n ≥ 1
  double duration_s = 5.0;    ///< total length [s] ≥ n·T_p
  double dt_s = 0.005;        ///< sample interval [s]
};
/// Samples at t = i·dt for i = 0 … duration/dt (a duration within 1e-9 relative of a whole
/// number of steps ends on a sample). The record's name is the spec in make_synthetic's
/// text form.
/// \throws UserError naming the field ("SinePulseSpec.period_s ...") when
/// amplitude_g, period_s or dt_s is not positive and finite, cycles < 1,
/// period_s < 4·dt_s, duration_s < cycles·period_s, or the record would exceed 1e8 samples.
GroundMotion make_sine_pulse_train(const SinePulseSpec& spec);

/// Filtered white noise (Kanai–Tajimi filter, ground frequency f_g, damping ζ_g) under a
/// Jennings-type envelope (quadratic rise to t_rise, plateau to t_rise + t_strong, then
/// exponential decay), scaled so that the peak |a| equals pga_g.
struct StochasticSpec {
  std::uint64_t seed = 1;
  double pga_g = 0.5;          ///< peak ground acceleration after scaling [g]
  double duration_s = 20.0;    ///< [s]
  double dt_s = 0.01;          ///< [s]
  double ground_freq_hz = 2.5; ///< Kanai–Tajimi f_g [Hz]
  double ground_damping = 0.6; ///< Kanai–Tajimi ζ_g [-]
  double rise_s = 2.0;         ///< envelope rise time [s]
  double strong_s = 6.0;       ///< envelope plateau length [s]
  double decay_per_s = 0.35;   ///< envelope decay rate after the plateau [1/s]
};
/// The filter x'' + 2ζω x' + ω² x = −w(t) starts at rest and is advanced by its exact
/// transition over dt for unit-variance noise held constant over each step; the record is
/// envelope(t) · (−2ζω x' − ω² x), so its first sample is 0. After scaling the peak |a| is
/// pga_g · kGravity_m_s2 bit for bit. Samples and name as for make_sine_pulse_train.
/// \throws UserError naming the field when pga_g, duration_s, dt_s,
/// ground_freq_hz or ground_damping is not positive and finite, rise_s, strong_s or
/// decay_per_s is negative or not finite, duration_s < dt_s, ground_freq_hz ≥ 0.5/dt_s
/// (Nyquist), or the record would exceed 1e8 samples.
GroundMotion make_stochastic(const StochasticSpec& spec);

/// A record named in text form, as the CLI and study files accept it:
/// "sine:amplitude_g=0.5,period_s=0.5,cycles=2,duration_s=5,dt_s=0.005" or
/// "stochastic:seed=3,pga_g=0.4,duration_s=20,dt_s=0.01", or a pulse of pulses.hpp by its kind:
/// "pulse-sine:period_s=0.5,amplitude_g=0.3", "pulse-cosine:…", "pulse-cycles:…,cycles=2",
/// "ricker:…", "ricker-antisymmetric:…", "mavroeidis:…,gamma=2,nu_deg=90" (any subset of the fields above,
/// the rest take their defaults; "sine" alone is all defaults). Blanks around keys and values
/// are ignored; a key given twice, an empty item or a value that is not a whole number
/// (cycles, seed) or a finite number (the rest) is an error. The record's name is the text
/// itself.
/// \throws UserError naming the unknown kind, key or bad value.
GroundMotion make_synthetic(const std::string& text);

}  // namespace pcrf
