// SPDX-License-Identifier: MIT
// Exact predicates on grid coordinates (integers held in doubles, |x| < 2^26)
// and the segment and polygon tests every mapping stage shares.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "posemorph/bake/mapping/nway_mapping.h"

namespace posemorph::bake::mapping {

constexpr double kGridLimit = 67108864.0;  // 2^26: products of differences stay below 2^55

inline std::int64_t Cross(const Point& a, const Point& b, const Point& c) {
  const auto abx = std::int64_t(b.x() - a.x()), aby = std::int64_t(b.y() - a.y());
  const auto acx = std::int64_t(c.x() - a.x()), acy = std::int64_t(c.y() - a.y());
  return abx * acy - aby * acx;
}

inline Point Snap(const Point& p) { return {std::nearbyint(p.x()), std::nearbyint(p.y())}; }

// c on the closed segment ab (collinear and within its box).
inline bool OnSegment(const Point& a, const Point& b, const Point& c) {
  return Cross(a, b, c) == 0 && std::min(a.x(), b.x()) <= c.x() && c.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= c.y() && c.y() <= std::max(a.y(), b.y());
}

// Segment c-d lies wholly outside the box [lo, hi]: a quick reject before exact tests.
inline bool OutsideBox(const Point& lo, const Point& hi, const Point& c, const Point& d) {
  return std::max(c.x(), d.x()) < lo.x() || std::min(c.x(), d.x()) > hi.x() || std::max(c.y(), d.y()) < lo.y() ||
         std::min(c.y(), d.y()) > hi.y();
}

// The open segments cross at one point interior to both.
inline bool ProperlyCross(const Point& a, const Point& b, const Point& c, const Point& d) {
  const std::int64_t o1 = Cross(a, b, c), o2 = Cross(a, b, d), o3 = Cross(c, d, a), o4 = Cross(c, d, b);
  return ((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0));
}

// Any common point at all.
inline bool SegmentsMeet(const Point& a, const Point& b, const Point& c, const Point& d) {
  return ProperlyCross(a, b, c, d) || OnSegment(a, b, c) || OnSegment(a, b, d) || OnSegment(c, d, a) ||
         OnSegment(c, d, b);
}

// Is b strictly inside the interior angle at v (prev u, next w, interior on the left)?
inline bool InCone(const Point& u, const Point& v, const Point& w, const Point& b) {
  if (Cross(u, v, w) > 0) return Cross(v, w, b) > 0 && Cross(v, b, u) > 0;
  return Cross(v, w, b) > 0 || Cross(v, b, u) > 0;
}

inline double AngleAt(const Point& a, const Point& b, const Point& c) {  // at a, radians
  const Point u = b - a, v = c - a;
  return std::atan2(std::abs(u.x() * v.y() - u.y() * v.x()), u.dot(v));
}

// Cosine of the smallest angle, which lies opposite the shortest edge (law of
// cosines). Decreases as the smallest angle grows: a cheap quality to compare.
inline double MinAngleCosine(const Point& a, const Point& b, const Point& c) {
  const double ab = (b - a).squaredNorm(), bc = (c - b).squaredNorm(), ca = (a - c).squaredNorm();
  double opposite = ab, s1 = bc, s2 = ca;
  if (bc < opposite) opposite = bc, s1 = ab, s2 = ca;
  if (ca < opposite) opposite = ca, s1 = ab, s2 = bc;
  if (s1 == 0 || s2 == 0) return 1;
  return std::clamp((s1 + s2 - opposite) / (2 * std::sqrt(s1 * s2)), -1.0, 1.0);
}

inline double TriangleMinAngle(const Point& a, const Point& b, const Point& c) {
  return std::acos(MinAngleCosine(a, b, c));
}

// Maps drawing coordinates to the integer grid and back by a power of two,
// so the round trip is exact.
struct Grid {
  double scale = 1;  // grid units per drawing unit
  static Grid For(double max_abs_coordinate) {
    Grid g;
    const double target = kGridLimit / 16;  // room for outward moves and Steiner points
    g.scale = std::ldexp(1.0, int(std::floor(std::log2(target / std::max(max_abs_coordinate, 1e-300)))));
    return g;
  }
  Point ToGrid(const Point& p) const { return Snap(p * scale); }
  Point FromGrid(const Point& p) const { return p / scale; }
};

}  // namespace posemorph::bake::mapping
