// SPDX-License-Identifier: MIT
// An outline with its arc length at every vertex, walked span by span: what
// the enclosing simplification and its span splitting share
// (enclosing_simplification.cpp, span_splitting.cpp).
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include "geometry.h"
#include "posemorph/bake/mapping/boundary_matching.h"

namespace posemorph::bake::mapping {

struct OutlineArc {
  const Polygon* outline = nullptr;
  std::vector<double> cumulative;  // arc length at each outline vertex (size n + 1)
  double perimeter = 0;

  OutlineArc() = default;
  explicit OutlineArc(const Polygon& o)
      : outline(&o), cumulative(CumulativeArcLength(o)), perimeter(cumulative.back()) {}

  // Outline vertex indices strictly between arc lengths s0 < s1 (s1 may wrap past the perimeter).
  template <typename F>
  void ForSpan(double s0, double s1, F&& f) const {
    const std::size_t n = outline->size();
    double len = std::fmod(s1 - s0, perimeter);
    if (len <= 0) len += perimeter;
    s0 = std::fmod(s0, perimeter);
    if (s0 < 0) s0 += perimeter;
    const double end = s0 + len;
    std::size_t i = std::upper_bound(cumulative.begin(), cumulative.end() - 1, s0) - cumulative.begin();
    double base = 0;
    for (std::size_t steps = 0; steps < n; ++steps, ++i) {
      if (i >= n) i -= n, base += perimeter;
      if (base + cumulative[i] >= end) break;
      f(i);
    }
  }
};

// Signed distance of q outside the directed line a->b (positive: to the right, outside).
inline double Outside(const Point& a, const Point& b, const Point& q) {
  const Point d = b - a;
  const double len = d.norm();
  return len > 0 ? -(d.x() * (q - a).y() - d.y() * (q - a).x()) / len : (q - a).norm();
}

}  // namespace posemorph::bake::mapping
