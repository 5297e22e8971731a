// SPDX-License-Identifier: MIT
// How much of a drawing a pose's mesh covers (the mapping's tests).
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "posemorph/bake/mapping/outline_image.h"

namespace posemorph::test {

using Point = Eigen::Vector2d;

inline double Orient(const Point& a, const Point& b, const Point& c) {
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

struct DrawingCoverage {
  std::size_t opaque = 0;           // pixels of alpha >= 128
  std::size_t shape_uncovered = 0;  // pixels of alpha >= the threshold whose centre no triangle covers
  double alpha_outside_share = 0;   // of the drawing's alpha, the part on pixels no triangle covers
};

// A pose's mesh over its drawing, through its uvs: the pixel centres each
// triangle covers (uv space has y down, so triangles are clockwise there).
inline DrawingCoverage CoverageOf(const std::vector<Eigen::Vector2f>& uvs,
                                  const std::vector<std::array<std::uint32_t, 3>>& triangles, const std::string& png,
                                  double threshold) {
  int W = 0, H = 0;
  const std::vector<unsigned char> alpha = posemorph::bake::mapping::ReadPngAlpha(png, &W, &H);
  std::vector<Point> uv;
  for (const auto& t : uvs) uv.push_back(Point(t.x() * W, t.y() * H));
  std::vector<char> covered(alpha.size(), 0);
  for (const auto& t : triangles) {
    const Point lo = uv[t[0]].cwiseMin(uv[t[1]]).cwiseMin(uv[t[2]]);
    const Point hi = uv[t[0]].cwiseMax(uv[t[1]]).cwiseMax(uv[t[2]]);
    for (int y = std::max(0, int(lo.y()) - 1); y <= std::min(H - 1, int(hi.y()) + 1); ++y)
      for (int x = std::max(0, int(lo.x()) - 1); x <= std::min(W - 1, int(hi.x()) + 1); ++x) {
        const Point c(x + 0.5, y + 0.5);
        if (Orient(uv[t[0]], uv[t[1]], c) <= 0 && Orient(uv[t[1]], uv[t[2]], c) <= 0 &&
            Orient(uv[t[2]], uv[t[0]], c) <= 0)
          covered[std::size_t(y) * std::size_t(W) + std::size_t(x)] = 1;
      }
  }
  DrawingCoverage c;
  double total = 0, outside = 0;
  for (std::size_t p = 0; p < alpha.size(); ++p) {
    total += alpha[p];
    c.opaque += alpha[p] >= 128;
    if (covered[p]) continue;
    outside += alpha[p];
    c.shape_uncovered += alpha[p] >= threshold * 255;
  }
  c.alpha_outside_share = outside / total;
  return c;
}

}  // namespace posemorph::test
