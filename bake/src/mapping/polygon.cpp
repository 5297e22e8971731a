// SPDX-License-Identifier: MIT
// Exact polygon tests on the integer grid.
#include <algorithm>

#include "geometry.h"
#include "posemorph/bake/mapping/polygon.h"

namespace posemorph::bake::mapping {

int Orient(const Point& a, const Point& b, const Point& c) {
  const std::int64_t d = Cross(a, b, c);
  return (d > 0) - (d < 0);
}

double SignedArea(const Polygon& p) {
  double twice = 0;
  for (std::size_t i = 0, n = p.size(); i < n; ++i) {
    const Point& a = p[i];
    const Point& b = p[(i + 1) % n];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return twice / 2;
}

namespace {

// The edges (index i: p[i] to p[i + 1]) that meet another edge other than
// at a shared vertex, fold back onto a neighbour, or have no length; the
// first such edge only when `first_only`.
std::vector<std::size_t> BadEdges(const Polygon& p, bool first_only) {
  const std::size_t n = p.size();
  std::vector<std::size_t> bad;
  // Sweep over x so long outlines stay fast: edges sorted by their left end.
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  auto lo = [&](std::size_t e) { return std::min(p[e].x(), p[(e + 1) % n].x()); };
  auto hi = [&](std::size_t e) { return std::max(p[e].x(), p[(e + 1) % n].x()); };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return lo(a) < lo(b); });
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t e = order[k];
    const Point &a = p[e], &b = p[(e + 1) % n];
    if (a == b) {
      bad.push_back(e);
      if (first_only) return bad;
      continue;
    }
    for (std::size_t m = k + 1; m < n && lo(order[m]) <= hi(e); ++m) {
      const std::size_t f = order[m];
      const Point &c = p[f], &d = p[(f + 1) % n];
      bool meet;
      if (f == (e + 1) % n || e == (f + 1) % n) {
        // Neighbours share one vertex; they may not fold back onto each other.
        const Point& shared = f == (e + 1) % n ? b : a;
        const Point& x = f == (e + 1) % n ? a : b;
        const Point& y = f == (e + 1) % n ? d : c;
        meet = Cross(shared, x, y) == 0 && (x - shared).dot(y - shared) > 0;
      } else {
        meet = c != d && SegmentsMeet(a, b, c, d);
      }
      if (!meet) continue;
      bad.push_back(e), bad.push_back(f);
      if (first_only) return bad;
    }
  }
  std::sort(bad.begin(), bad.end());
  bad.erase(std::unique(bad.begin(), bad.end()), bad.end());
  return bad;
}

}  // namespace

bool IsSimplePolygon(const Polygon& p) { return p.size() >= 3 && BadEdges(p, true).empty(); }

std::vector<std::size_t> SelfCrossingEdges(const Polygon& p) { return BadEdges(p, false); }

int PointInPolygon(const Polygon& p, const Point& q) {
  bool inside = false;
  for (std::size_t i = 0, n = p.size(), j = n - 1; i < n; j = i++) {
    const Point &a = p[j], &b = p[i];
    if (OnSegment(a, b, q)) return 0;
    // Crossing test with half-open rule; the side test is exact.
    if ((a.y() > q.y()) != (b.y() > q.y())) {
      const std::int64_t s = Cross(a, b, q);
      if ((b.y() > a.y()) ? s > 0 : s < 0) inside = !inside;
    }
  }
  return inside ? 1 : -1;
}

namespace {

// b is inside the interior angle at v or on one of its two rays.
bool InClosedCone(const Point& u, const Point& v, const Point& w, const Point& b) {
  if (InCone(u, v, w, b)) return true;
  return (Cross(v, w, b) == 0 && (w - v).dot(b - v) > 0) || (Cross(v, u, b) == 0 && (u - v).dot(b - v) > 0);
}

}  // namespace

bool Encloses(const Polygon& outer, const Polygon& inner) {
  std::vector<int> where(inner.size());
  for (std::size_t i = 0; i < inner.size(); ++i) {
    where[i] = PointInPolygon(outer, inner[i]);
    if (where[i] < 0) return false;
  }
  // With every vertex inside or on, an edge leaves only by crossing an edge of
  // `outer`, by passing through one of its vertices into the exterior, or by
  // running outside between two boundary points (then its midpoint is outside).
  Polygon doubled;
  for (std::size_t i = 0, n = inner.size(); i < n; ++i) {
    const Point &a = inner[i], &b = inner[(i + 1) % n];
    const Point lo = a.cwiseMin(b), hi = a.cwiseMax(b);
    for (std::size_t k = 0, m = outer.size(); k < m; ++k) {
      const Point &c = outer[k], &d = outer[(k + 1) % m];
      if (OutsideBox(lo, hi, c, d)) continue;
      if (ProperlyCross(a, b, c, d)) return false;
      if (c != a && c != b && OnSegment(a, b, c)) {
        const Point& before = outer[(k + m - 1) % m];
        if (!InClosedCone(before, c, d, a) || !InClosedCone(before, c, d, b)) return false;
      }
    }
    if (where[i] == 0 && where[(i + 1) % n] == 0) {
      if (doubled.empty())
        for (const Point& p : outer) doubled.push_back(2 * p);
      if (PointInPolygon(doubled, a + b) < 0) return false;
    }
  }
  return true;
}

}  // namespace posemorph::bake::mapping
