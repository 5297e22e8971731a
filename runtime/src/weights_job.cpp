// SPDX-License-Identifier: MIT
// Pose-space weights: barycentric interpolation in the baked grid (DESIGN.md
// section 3), then weight limiting (the paper's limit on shear and scale:
// phi(w) renormalised, the limited weights) and texture sharpening.
#include <cmath>

#include "posemorph/grid_location.h"
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

double LimitWeight(double w) { return Smoothstep(0.0, 1.0, w); }

void TextureWeights(Span<const double> limited_weights, double sigma, Span<double> out) {
  const std::size_t n = limited_weights.size;
  sigma = std::isfinite(sigma) ? Clamp(sigma, 0, 1) : 0;
  double input_sum = 0;
  for (std::size_t i = 0; i < n; ++i) input_sum += limited_weights[i];
  double sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double w = limited_weights[i];
    out[i] = sigma * Smoothstep(sigma / 2, 1 - sigma / 2, w) + (1 - sigma) * w;
    sum += out[i];
  }
  if (sum > 1e-12) {
    for (std::size_t i = 0; i < n; ++i) out[i] /= sum;
  } else {
    // Only at (or within 1e-12 of) sigma = 1 with no weight above 1/2, where
    // the formula is 0/0. Its limit as sigma -> 1 is the input itself (the
    // sharpened term is 0 once sigma/2 passes every weight), so w'' stays
    // continuous in sigma. `out` may alias the input: each entry reads its own.
    for (std::size_t i = 0; i < n; ++i) out[i] = input_sum > 0 ? limited_weights[i] / input_sum : 1.0 / double(n);
  }
}

bool WeightsJob::Validate() const {
  if (!rig || !rig->loaded()) return false;
  const std::size_t n = rig->pose_count();
  return raw.data && raw.size >= n && (limited.size == 0 || (limited.data && limited.size >= n)) &&
         (texture.size == 0 || (texture.data && texture.size >= n));
}

bool WeightsJob::Run() const {
  if (!Validate()) return false;
  const std::uint32_t n = rig->pose_count();
  const PoseSpaceGrid& g = rig->grid();

  double px = std::isnan(x) ? rig->pose_points()[0] : x;
  double py = std::isnan(y) ? rig->pose_points()[1] : y;
  // The grid triangle holding the point (grid_location.h: the bake solved the
  // node weights for exactly these coordinates).
  const GridLocation at = LocateInGrid(g, g.centre_weights.size != 0, px, py);
  const std::size_t corners = g.corner_count();
  const double* w[3];
  for (int c = 0; c < 3; ++c)
    w[c] = at.node[c] < corners ? g.weights.data + std::size_t(at.node[c]) * n
                                : g.centre_weights.data + (at.node[c] - corners) * n;
  const double l0 = at.lambda[0], l1 = at.lambda[1], l2 = at.lambda[2];
  for (std::uint32_t k = 0; k < n; ++k) raw[k] = l0 * w[0][k] + l1 * w[1][k] + l2 * w[2][k];

  // phi(w) renormalised: always a convex combination. The limited output is
  // these, or the raw weights when limiting is off; the texture weights are
  // built from these either way, never from raw weights (which extrapolate
  // below 0 and above 1).
  if (limited.size || texture.size) {
    double phi[format::kMaxPoses];
    double sum = 0;
    for (std::uint32_t k = 0; k < n; ++k) sum += (phi[k] = LimitWeight(raw[k]));
    // sum(raw) = 1 puts some raw weight at >= 1/N, so sum > 0 for any baked grid.
    for (std::uint32_t k = 0; k < n; ++k) phi[k] = sum > 0 ? phi[k] / sum : 1.0 / n;
    if (limited.size)
      for (std::uint32_t k = 0; k < n; ++k) limited[k] = limit_weights ? phi[k] : raw[k];
    if (texture.size) TextureWeights(Span<const double>(phi, n), sigma, Span<double>(texture.data, n));
  }
  return true;
}

}  // namespace posemorph
