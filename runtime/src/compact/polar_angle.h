// SPDX-License-Identifier: MIT
// The polar split A = R(alpha) S of a triangle's 2x2 deformation gradient,
// computed from + - * / and sqrt only, so that a compact rig derives the same
// angles and stretches on every compiler, C library and instruction set
// (libm's atan2 differs between C libraries; the basic operations and sqrt
// are correctly rounded everywhere).
#pragma once
#include <cmath>

namespace posemorph::detail {

// atan2(y, x) in (-pi, pi]; 0 for (0, 0). Reduced to t = min/max in [0, 1],
// then by pi/4 to |u| <= tan(pi/8), halved once with
// atan u = 2 atan(u / (1 + sqrt(1 + u^2))) to |v| <= tan(pi/16) = 0.199, and
// summed as the Taylor series to v^23 (truncation below 0.199^25/25 = 1.2e-19).
inline double PortableAtan2(double y, double x) {
  const double kPi = 3.141592653589793116, kHalfPi = 1.570796326794896558, kQuarterPi = 0.7853981633974482790;
  const double ax = std::fabs(x), ay = std::fabs(y);
  if (!(ax > 0) && !(ay > 0)) return 0;
  const bool swap = ay > ax;
  const double t = swap ? ax / ay : ay / ax;
  double base = 0, u = t;
  if (t > 0.41421356237309503) {  // tan(pi/8)
    u = (t - 1) / (t + 1);
    base = kQuarterPi;
  }
  const double v = u / (1 + std::sqrt(1 + u * u));
  const double z = v * v;
  double p = -1.0 / 23;
  p = p * z + 1.0 / 21;
  p = p * z - 1.0 / 19;
  p = p * z + 1.0 / 17;
  p = p * z - 1.0 / 15;
  p = p * z + 1.0 / 13;
  p = p * z - 1.0 / 11;
  p = p * z + 1.0 / 9;
  p = p * z - 1.0 / 7;
  p = p * z + 1.0 / 5;
  p = p * z - 1.0 / 3;
  p = p * z + 1.0;
  double a = base + 2 * (v * p);
  if (swap) a = kHalfPi - a;
  if (x < 0) a = kPi - a;
  return y < 0 ? -a : a;
}

struct PolarParts {
  double alpha;          // principal rotation angle, (-pi, pi]
  double s11, s12, s22;  // the symmetric stretch S = R(alpha)^T A, symmetrised
};

// A = [[a, b], [c, d]] with det A > 0 (then a + d and c - b are not both 0).
inline PolarParts PolarSplit(double a, double b, double c, double d) {
  const double cs = a + d, sn = c - b;
  const double inv_h = 1 / std::sqrt(cs * cs + sn * sn);
  const double co = cs * inv_h, si = sn * inv_h;
  PolarParts out;
  out.alpha = PortableAtan2(sn, cs);
  out.s11 = co * a + si * c;
  out.s12 = 0.5 * ((co * b + si * d) + (co * c - si * a));
  out.s22 = co * d - si * b;
  return out;
}

}  // namespace posemorph::detail
