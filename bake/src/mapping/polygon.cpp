// Exact polygon tests on the integer grid.
#include <algorithm>

#include "geometry.h"

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

bool IsSimplePolygon(const Polygon& p) {
  const std::size_t n = p.size();
  if (n < 3) return false;
  // Sweep over x so long outlines stay fast: edges sorted by their left end.
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  auto lo = [&](std::size_t e) { return std::min(p[e].x(), p[(e + 1) % n].x()); };
  auto hi = [&](std::size_t e) { return std::max(p[e].x(), p[(e + 1) % n].x()); };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return lo(a) < lo(b); });
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t e = order[k];
    const Point &a = p[e], &b = p[(e + 1) % n];
    if (a == b) return false;
    for (std::size_t m = k + 1; m < n && lo(order[m]) <= hi(e); ++m) {
      const std::size_t f = order[m];
      const Point &c = p[f], &d = p[(f + 1) % n];
      if (f == (e + 1) % n || e == (f + 1) % n) {
        // Neighbours share one vertex; they may not fold back onto each other.
        const Point& shared = f == (e + 1) % n ? b : a;
        const Point& x = f == (e + 1) % n ? a : b;
        const Point& y = f == (e + 1) % n ? d : c;
        if (Cross(shared, x, y) == 0 && (x - shared).dot(y - shared) > 0) return false;
        if (n == 3) continue;
        continue;
      }
      if (SegmentsMeet(a, b, c, d)) return false;
    }
  }
  return true;
}

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

}  // namespace posemorph::bake::mapping
