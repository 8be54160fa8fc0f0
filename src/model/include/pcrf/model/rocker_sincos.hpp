/// \file rocker_sincos.hpp
/// \brief sin x and cos x of the rigid rockers, written once over a number type: `double` for
/// the one-case solver, a SIMD pack of cases for the batch kernels (src/solver/lanes/), with
/// the same operations in the same order, so that both give the same bits (compiled with
/// -ffp-contract=off: no fused multiply-add that the other does not have).
///
/// Method (Cody & Waite's reduction, Moshier's Cephes polynomials): q = x·2/π rounded to the
/// nearest integer by adding and subtracting 1.5·2⁵², r = x − q·π/2 with π/2 split in three
/// parts (the first two with trailing zeros, so q·C1 and q·C2 are exact for |q| < 2²⁶), then
/// on |r| ≤ π/4
///
///     sin r = r + r·z·P(z),  cos r = (1 − z/2) + z²·Q(z),  z = r²,
///
/// Cephes' sin.c coefficients, P and Q by Estrin's scheme, and the quadrant q mod 4 picks
/// ±sin r or ±cos r by selects. Within 2 ulp of the true values for |x| ≤ 10⁵
/// (tests/model/rocker_sincos_test.cpp), NaN for an infinite or NaN x. No table, no call:
/// about 50 operations, inlined. On one double the reduction is skipped for q = 0 (it would
/// give x itself): a predicted branch instead of a chain of dependent operations.
#pragma once

#include <type_traits>

#include "pcrf/host_device.hpp"

namespace pcrf {
namespace detail {

/// x − q·π/2, π/2 in three parts (Cody & Waite).
template <class T>
PCRF_HD inline T reduce_quadrant(const T& x_rad, const T& q) {
  return ((x_rad - q * T(1.57079625129699707031)) - q * T(7.54978941586159635335e-8)) - q * T(5.39030285815811905290e-15);
}

}  // namespace detail

/// sin and cos of x [rad]. `Ops` gives select(mask, a, b) for T (comparisons of T give the mask).
template <class Ops, class T>
PCRF_HD inline void rocker_sincos(const T& x_rad, T& sin_x, T& cos_x) {
  const T round(6755399441055744.0);  // 1.5·2⁵²: v + round − round is v rounded to an integer
  const T q = (x_rad * T(0.63661977236758134308) + round) - round;  // 2/π
  T r = x_rad;  // x − q·π/2: x itself for q = 0 (every term 0), a rocker's usual quadrant
  if constexpr (std::is_floating_point_v<T>) {
    if (q != 0.0) r = detail::reduce_quadrant(x_rad, q);  // a branch the CPU predicts, not a wait for q
  } else {
    r = detail::reduce_quadrant(x_rad, q);
  }
  // The polynomials by Estrin's scheme (short dependency chains; the right-hand side sits on
  // the integrator's critical path).
  const T z = r * r, z2 = z * z, z4 = z2 * z2;
  const T p = (T(-1.66666666666666307295e-1) + T(8.33333333332211858878e-3) * z) +
              z2 * (T(-1.98412698295895385996e-4) + T(2.75573136213857245213e-6) * z) +
              z4 * (T(-2.50507477628578072866e-8) + T(1.58962301576546568060e-10) * z);
  const T k = (T(4.16666666666665929218e-2) + T(-1.38888888888730564116e-3) * z) +
              z2 * (T(2.48015872888517045348e-5) + T(-2.75573141792967388112e-7) * z) +
              z4 * (T(2.08757008419747316778e-9) + T(-1.13585365213876817300e-11) * z);
  const T sin_r = r + (r * z) * p;
  const T cos_r = (T(1.0) - T(0.5) * z) + z2 * k;
  // The quadrant: n = q − 4·round(q/4) in {−2, −1, 0, 1, 2} (−2 ≡ 2, −1 ≡ 3 mod 4).
  const T n = q - T(4.0) * ((q * T(0.25) + round) - round);
  // Three declarations: for a double, `two` is an int (bool | bool), the others bools.
  const auto one = n == T(1.0);
  const auto two = (n == T(2.0)) | (n == T(-2.0));
  const auto three = n == T(-1.0);
  const T s = Ops::select(one | three, cos_r, sin_r);  // odd quadrants swap sin and cos
  const T c = Ops::select(one | three, sin_r, cos_r);
  sin_x = Ops::select(two | three, -s, s);
  cos_x = Ops::select(one | two, -c, c);
}

}  // namespace pcrf
