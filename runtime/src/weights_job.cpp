// SPDX-License-Identifier: MIT
// Pose-space weights: barycentric interpolation in the baked grid (DESIGN.md
// section 3), then the paper's shear limiting and texture sharpening.
#include <cmath>

#include "posemorph/jobs.h"
#include "posemorph/rig_format.h"

namespace posemorph {
namespace {

double Smoothstep(double a, double b, double t) {
  if (!(b > a)) return t < a ? 0.0 : 1.0;  // sigma = 1: a step at 1/2
  const double s = (t - a) / (b - a);
  if (s <= 0) return 0;
  if (s >= 1) return 1;
  return s * s * (3 - 2 * s);
}

double Clamp(double v, double lo, double hi) { return v < lo ? lo : (v > hi ? hi : v); }

}  // namespace

double ShearLimit(double w) { return Smoothstep(0.0, 1.0, w); }

void TextureWeights(Span<const double> shear, double sigma, Span<double> out) {
  const std::size_t n = shear.size;
  sigma = std::isfinite(sigma) ? Clamp(sigma, 0, 1) : 0;
  double input_sum = 0;
  for (std::size_t i = 0; i < n; ++i) input_sum += shear[i];
  double sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double w = shear[i];
    out[i] = sigma * Smoothstep(sigma / 2, 1 - sigma / 2, w) + (1 - sigma) * w;
    sum += out[i];
  }
  if (sum > 1e-12) {
    for (std::size_t i = 0; i < n; ++i) out[i] /= sum;
  } else {
    // Only at (or within 1e-12 of) sigma = 1 with no weight above 1/2, where
    // the formula is 0/0. Its limit as sigma -> 1 is the input itself (the
    // sharpened term is 0 once sigma/2 passes every weight), so w'' stays
    // continuous in sigma. `out` may alias `shear`: each entry reads its own.
    for (std::size_t i = 0; i < n; ++i) out[i] = input_sum > 0 ? shear[i] / input_sum : 1.0 / double(n);
  }
}

bool WeightsJob::Validate() const {
  if (!rig || !rig->loaded()) return false;
  const std::size_t n = rig->pose_count();
  return raw.data && raw.size >= n && (shear.size == 0 || (shear.data && shear.size >= n)) &&
         (texture.size == 0 || (texture.data && texture.size >= n));
}

bool WeightsJob::Run() const {
  if (!Validate()) return false;
  const std::uint32_t n = rig->pose_count();
  const PoseSpaceGrid& g = rig->grid();

  double px = std::isnan(x) ? rig->pose_points()[0] : x;
  double py = std::isnan(y) ? rig->pose_points()[1] : y;
  const double u = Clamp((px - g.origin_x) / g.cell, 0, double(g.cells_x));
  const double v = Clamp((py - g.origin_y) / g.cell, 0, double(g.cells_y));
  const std::uint32_t i = u >= g.cells_x ? g.cells_x - 1 : std::uint32_t(u);
  const std::uint32_t j = v >= g.cells_y ? g.cells_y - 1 : std::uint32_t(v);
  const double fx = Clamp(u - i, 0, 1), fy = Clamp(v - j, 0, 1);

  const std::size_t row = std::size_t(g.cells_x) + 1;
  const double* w00 = g.weights.data + (std::size_t(j) * row + i) * n;
  const double* w10 = w00 + n;
  const double* w01 = w00 + row * n;
  const double* w11 = w01 + n;
  if (g.centre_weights.size != 0) {
    // Format 1.2: the cell is four triangles meeting at its centre c; the
    // diagonals fx = fy and fx + fy = 1 say which one holds the point.
    const double* wc = g.centre_weights.data + (std::size_t(j) * g.cells_x + i) * n;
    const double d1 = fx - fy, d2 = fx + fy - 1;
    if (d1 >= 0 && d2 <= 0) {  // bottom: (0,0) (1,0) c
      for (std::uint32_t k = 0; k < n; ++k) raw[k] = -d2 * w00[k] + d1 * w10[k] + 2 * fy * wc[k];
    } else if (d1 >= 0) {  // right: (1,0) (1,1) c
      for (std::uint32_t k = 0; k < n; ++k) raw[k] = d1 * w10[k] + d2 * w11[k] + 2 * (1 - fx) * wc[k];
    } else if (d2 >= 0) {  // top: (1,1) (0,1) c
      for (std::uint32_t k = 0; k < n; ++k) raw[k] = d2 * w11[k] - d1 * w01[k] + 2 * (1 - fy) * wc[k];
    } else {  // left: (0,1) (0,0) c
      for (std::uint32_t k = 0; k < n; ++k) raw[k] = -d1 * w01[k] - d2 * w00[k] + 2 * fx * wc[k];
    }
  } else if (fx >= fy) {  // before 1.2: each cell split on its (0,0)-(1,1) diagonal
    for (std::uint32_t k = 0; k < n; ++k) raw[k] = (1 - fx) * w00[k] + (fx - fy) * w10[k] + fy * w11[k];
  } else {
    for (std::uint32_t k = 0; k < n; ++k) raw[k] = (1 - fy) * w00[k] + (fy - fx) * w01[k] + fx * w11[k];
  }

  // phi(w) renormalised: always a convex combination. The shear output is
  // these, or the raw weights when limiting is off; the texture weights are
  // built from these either way, never from raw weights (which extrapolate
  // below 0 and above 1).
  if (shear.size || texture.size) {
    double limited[format::kMaxPoses];
    double sum = 0;
    for (std::uint32_t k = 0; k < n; ++k) sum += (limited[k] = ShearLimit(raw[k]));
    // sum(raw) = 1 puts some raw weight at >= 1/N, so sum > 0 for any baked grid.
    for (std::uint32_t k = 0; k < n; ++k) limited[k] = sum > 0 ? limited[k] / sum : 1.0 / n;
    if (shear.size)
      for (std::uint32_t k = 0; k < n; ++k) shear[k] = shear_limit ? limited[k] : raw[k];
    if (texture.size) TextureWeights(Span<const double>(limited, n), sigma, Span<double>(texture.data, n));
  }
  return true;
}

}  // namespace posemorph
