/// \file ground_acceleration.hpp
/// \brief The ground's acceleration at one instant, as the frame feels it: the vocabulary
/// shared by the excitation (which evaluates it) and the model (which takes it).
#pragma once

namespace pcrf {

/// Ground acceleration at one instant [m/s²].
///
/// `horizontal_m_s2` lies in the frame's plane: a positive value pushes the frame into
/// θ₁ < 0 (the sign convention of Eq. (31), S ü_h on the right-hand side).
/// `vertical_m_s2` is positive up: it adds to gravity, so the frame feels g + ü_v.
///
/// A single number converts to a horizontal acceleration with no vertical component, the
/// only excitation the engine knew before vertical shaking: such a value gives bit for bit
/// the results it gave then (g + 0.0 is g).
struct GroundAcceleration {
  GroundAcceleration(double horizontal = 0.0, double vertical = 0.0)  // NOLINT: implicit by design
      : horizontal_m_s2(horizontal), vertical_m_s2(vertical) {}

  double horizontal_m_s2;
  double vertical_m_s2;
};

/// The ground over one time step, linear in τ = t − t₀ [s] (the record is linear between
/// samples): ü_h(τ) = h0 + h1·τ, ü_v(τ) = v0 + v1·τ.
struct GroundLine {
  double h0_m_s2 = 0.0, h1_m_s3 = 0.0;
  double v0_m_s2 = 0.0, v1_m_s3 = 0.0;
};

}  // namespace pcrf
