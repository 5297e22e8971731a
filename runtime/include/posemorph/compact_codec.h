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

// QPOS's prediction field (1.13, 1.14): which predictions the codes are
// residuals of.
// The poses after the first code their residuals less pose 0's (1.13).
constexpr std::uint32_t kPositionsAgainstPose0 = 1;
// A vertex is predicted by the mean of its earlier neighbours (1.14;
// EarlierNeighbours), not by the previous vertex.
constexpr std::uint32_t kPositionsFromNeighbours = 2;

// A vertex's earlier neighbours: at most this many are kept.
constexpr std::uint32_t kMaxEarlierNeighbours = 16;

// The earlier neighbours of each vertex v: the corners u < v of the
// triangles that hold v, triangle by triangle in order and within a
// triangle in corner order (a neighbour in two triangles counts twice), the
// first kMaxEarlierNeighbours of them. Written as lists: v's are
// list[start[v]] .. list[start[v + 1] - 1]. start holds V + 1 entries, fill
// V (scratch), list at most 3T. Every index in `triangles` is below V.
inline void EarlierNeighbours(const std::uint32_t* triangles, std::uint64_t T, std::uint64_t V, std::uint32_t* start,
                              std::uint32_t* fill, std::uint32_t* list) {
  for (std::uint64_t v = 0; v < V; ++v) fill[v] = 0;
  for (int pass = 0; pass < 2; ++pass) {
    for (std::uint64_t t = 0; t < T; ++t)
      for (int c = 0; c < 3; ++c) {
        const std::uint32_t v = triangles[3 * t + std::uint64_t(c)];
        for (int d = 0; d < 3; ++d) {
          const std::uint32_t u = triangles[3 * t + std::uint64_t(d)];
          if (u >= v || fill[v] >= kMaxEarlierNeighbours) continue;
          if (pass == 1) list[start[v] + fill[v]] = u;
          ++fill[v];
        }
      }
    if (pass == 0) {
      start[0] = 0;
      for (std::uint64_t v = 0; v < V; ++v) start[v + 1] = start[v] + fill[v], fill[v] = 0;
    }
  }
}

// Vertex v's prediction in one coordinate (q: that coordinate's integers,
// `stride` apart, each in 0..2^40): the mean of its earlier neighbours'
// integers rounded down, or, with none, the previous vertex's (0 for vertex
// 0).
inline std::int64_t NeighbourPrediction(const std::int64_t* q, std::uint64_t stride, std::uint64_t v,
                                        const std::uint32_t* start, const std::uint32_t* list) {
  const std::uint32_t count = start[v + 1] - start[v];
  if (count == 0) return v > 0 ? q[(v - 1) * stride] : 0;
  std::int64_t sum = 0;
  for (std::uint32_t k = start[v]; k < start[v + 1]; ++k) sum += q[std::uint64_t(list[k]) * stride];
  return sum / std::int64_t(count);
}

}  // namespace posemorph::format
