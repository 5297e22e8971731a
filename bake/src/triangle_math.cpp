// SPDX-License-Identifier: MIT
#include "posemorph/bake/triangle_math.h"

#include <cmath>
#include <deque>
#include <map>
#include <utility>

namespace posemorph::bake {

Eigen::Matrix2d EdgeMatrix(const Points& p, const std::array<std::uint32_t, 3>& t) {
  Eigen::Matrix2d E;
  E.col(0) = p[t[0]] - p[t[2]];
  E.col(1) = p[t[1]] - p[t[2]];
  return E;
}

double SignedArea(const Points& p, const std::array<std::uint32_t, 3>& t) {
  return 0.5 * EdgeMatrix(p, t).determinant();
}

PolarSplit PolarDecompose(const Eigen::Matrix2d& A) {
  PolarSplit out;
  out.alpha = std::atan2(A(1, 0) - A(0, 1), A(0, 0) + A(1, 1));
  const double c = std::cos(out.alpha), s = std::sin(out.alpha);
  Eigen::Matrix2d Rt;
  Rt << c, s, -s, c;
  const Eigen::Matrix2d S = Rt * A;
  // R^T A is symmetric in exact arithmetic for this alpha; symmetrise the roundoff.
  out.S = 0.5 * (S + S.transpose());
  return out;
}

std::vector<std::vector<std::uint32_t>> EdgeNeighbours(const Triangles& triangles) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::uint32_t>> edges;
  for (std::uint32_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      std::uint32_t a = triangles[t][k], b = triangles[t][(k + 1) % 3];
      if (a > b) std::swap(a, b);
      edges[{a, b}].push_back(t);
    }
  std::vector<std::vector<std::uint32_t>> out(triangles.size());
  for (const auto& [edge, tris] : edges)
    for (std::uint32_t t : tris)
      for (std::uint32_t u : tris)
        if (t != u) out[t].push_back(u);
  return out;
}

void UnwrapAngles(const std::vector<std::vector<std::uint32_t>>& neighbours, const std::vector<double>& areas,
                  std::vector<double>& angles) {
  const double two_pi = 2 * M_PI;
  std::vector<char> visited(angles.size(), 0);
  std::vector<std::uint32_t> part;
  std::deque<std::uint32_t> queue;
  for (std::uint32_t seed = 0; seed < angles.size(); ++seed) {
    if (visited[seed]) continue;
    // Relative unwrapping over one edge-connected part: any walk gives the
    // same angles up to one 2 pi k for the part (neighbours differ by less
    // than pi in any pose without a fold).
    visited[seed] = 1;
    queue.push_back(seed);
    part.clear();
    while (!queue.empty()) {
      const std::uint32_t t = queue.front();
      queue.pop_front();
      part.push_back(t);
      for (std::uint32_t u : neighbours[t]) {
        if (visited[u]) continue;
        visited[u] = 1;
        angles[u] += two_pi * std::round((angles[t] - angles[u]) / two_pi);
        queue.push_back(u);
      }
    }
    // The part's 2 pi k: its area-weighted mean angle lands in (-pi, pi].
    // Nothing here depends on which triangle the walk started from, so the
    // in-betweens do not change when the triangle list is reordered.
    double area = 0, sum = 0;
    for (std::uint32_t t : part) area += areas[t], sum += areas[t] * angles[t];
    const double mean = sum / area;
    const double shift = -two_pi * std::ceil((mean - M_PI) / two_pi);
    for (std::uint32_t t : part) angles[t] += shift;
  }
}

}  // namespace posemorph::bake
