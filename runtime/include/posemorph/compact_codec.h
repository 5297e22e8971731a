// SPDX-License-Identifier: MIT
// The integer arithmetic of the compact encoding (format 1.3), shared by the
// bake's encoder and the runtime's decoder so that both predict the same
// integers: zigzag mapping of signed residuals, and the weight grid's
// predictors. runtime/FORMAT.md describes the sections that use them.
#pragma once
#include <cstdint>

namespace posemorph::format {

// Signed residual <-> unsigned code: 0, -1, 1, -2, 2, ... -> 0, 1, 2, 3, 4, ...
inline std::uint64_t ZigZag(std::int64_t r) { return r >= 0 ? std::uint64_t(r) * 2 : std::uint64_t(-(r + 1)) * 2 + 1; }
inline std::int64_t UnZigZag(std::uint64_t u) { return (u & 1) ? -std::int64_t(u >> 1) - 1 : std::int64_t(u >> 1); }

// floor(s / 4) for any sign.
inline std::int64_t FloorDiv4(std::int64_t s) { return s >= 0 ? s / 4 : -((-s + 3) / 4); }

// A grid corner's prediction from the integers before it (q row-major, `row`
// corners per row): the residual q - prediction is D_x D_y q, with D = 1 -
// (the shift to the previous corner) applied min(order, x) times along x and
// min(order, y) times along y. Order 1 is exact for bilinear fields (the
// Lorenzo predictor), order 2 for biquadratic ones.
inline std::int64_t GridCornerPrediction(const std::int64_t* q, std::uint64_t row, std::uint64_t x, std::uint64_t y,
                                         unsigned order) {
  static const std::int64_t kCoefficients[3][3] = {{1, 0, 0}, {1, -1, 0}, {1, -2, 1}};
  const std::int64_t* a = kCoefficients[x < order ? x : order];
  const std::int64_t* b = kCoefficients[y < order ? y : order];
  std::int64_t prediction = 0;
  for (std::uint64_t j = 0; j <= order && j <= y; ++j)
    for (std::uint64_t i = 0; i <= order && i <= x; ++i)
      if (i || j) prediction -= a[i] * b[j] * q[(y - j) * row + (x - i)];
  return prediction;
}

// A cell centre's prediction: the rounded mean of its four corners.
inline std::int64_t GridCentrePrediction(std::int64_t q00, std::int64_t q10, std::int64_t q01, std::int64_t q11) {
  return FloorDiv4(q00 + q10 + q01 + q11 + 2);
}

}  // namespace posemorph::format
