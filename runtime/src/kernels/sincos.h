// SPDX-License-Identifier: MIT
// sin and cos of the blended rotation angles, written once for a double and
// for vector lanes (see vec.h) so that single and batched evaluation, and
// every instruction set, agree bit for bit: no libm, whose results differ
// between C libraries. Angles are reduced by pi/2 in two parts (the first with 33
// significant bits, so k * part is exact for |k| < 2^20, i.e. |x| < 1.6e6),
// then Taylor series to degree 15 (sin) and 16 (cos) on [-pi/4, pi/4]: the
// truncation error is below (pi/4)^17/17! = 4.6e-17.
// No include guard: included once per kernel translation unit, inside its
// namespace, after vec.h.

template <typename T>
POSEMORPH_KERNEL_INLINE void SinCos(T x, T* sin_out, T* cos_out) {
  const double kTwoOverPi = 0.63661977236758134308;
  const double kRound = 6755399441055744.0;               // 1.5 * 2^52: adding it rounds to an integer
  const double kHalfPiHigh = 1.57079632673412561417e+00;  // pi/2 to 33 bits
  const double kHalfPiLow = 6.07710050650619224932e-11;   // pi/2 - kHalfPiHigh
  const T k = (x * kTwoOverPi + kRound) - kRound;
  const T r = (x - k * kHalfPiHigh) - k * kHalfPiLow;
  const T z = r * r;
  // Horner in z = r^2 with the Taylor coefficients 1/n!:
  // sin r = r + r z (-1/3! + z (1/5! - z (1/7! - ...))), cos r = 1 - z/2! + z^2/4! - ...
  T p = z * (-1.0 / 1307674368000.0) + 1.0 / 6227020800.0;  // -1/15!, 1/13!
  p = p * z - 1.0 / 39916800.0;                             // 1/11!
  p = p * z + 1.0 / 362880.0;                               // 1/9!
  p = p * z - 1.0 / 5040.0;                                 // 1/7!
  p = p * z + 1.0 / 120.0;                                  // 1/5!
  p = p * z - 1.0 / 6.0;                                    // 1/3!
  const T s = r + r * z * p;
  T c = z * (1.0 / 20922789888000.0) - 1.0 / 87178291200.0;  // 1/16!, 1/14!
  c = c * z + 1.0 / 479001600.0;                             // 1/12!
  c = c * z - 1.0 / 3628800.0;                               // 1/10!
  c = c * z + 1.0 / 40320.0;                                 // 1/8!
  c = c * z - 1.0 / 720.0;                                   // 1/6!
  c = c * z + 1.0 / 24.0;                                    // 1/4!
  c = c * z - 0.5;
  c = c * z + 1.0;
  // Quadrant q = k mod 4, with floor(k/4) = round(k/4 - 3/8) (exact for
  // integers k). The quadrant is applied with small-integer arithmetic rather
  // than comparisons and selects, which cost a quarter of the batch kernel
  // where masks had to become vectors: with h = floor(q/2) and odd = q - 2h,
  //   (sin, cos) = (1 - 2h) (odd c + (1 - odd) s), (1 - 2 (odd - h)^2) (odd s + (1 - odd) c).
  // Every product there is by 0 or +-1, so the result is exact.
  const T q = k - 4.0 * (((k * 0.25 - 0.375) + kRound) - kRound);
  const T h = ((q * 0.5 - 0.25) + kRound) - kRound;
  const T odd = q - 2.0 * h;
  const T even = 1.0 - odd;
  const T flip = odd - h;
  *sin_out = (1.0 - 2.0 * h) * (odd * c + even * s);
  *cos_out = (1.0 - 2.0 * flip * flip) * (odd * s + even * c);
}
