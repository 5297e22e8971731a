// SPDX-License-Identifier: MIT
// Pose-space animation paths: piecewise linear, or cubic Hermite with
// Catmull-Rom tangents scaled for uneven key spacing in time.
#include <cmath>

#include "posemorph/path.h"

namespace posemorph {
namespace {

struct Key {
  double t, x, y;
};

Key KeyAt(const PathView& p, std::size_t k) { return {p.keys[3 * k], p.keys[3 * k + 1], p.keys[3 * k + 2]}; }

// A looping path whose last key repeats its first is closed: its tangents wrap.
bool Closed(const PathView& p) {
  const std::size_t n = p.key_count();
  return p.loop && n >= 3 && KeyAt(p, 0).x == KeyAt(p, n - 1).x && KeyAt(p, 0).y == KeyAt(p, n - 1).y;
}

void Tangent(const PathView& p, std::size_t k, double* mx, double* my) {
  const std::size_t n = p.key_count();
  Key prev, next;
  const double duration = KeyAt(p, n - 1).t - KeyAt(p, 0).t;
  if (k > 0 && k + 1 < n) {
    prev = KeyAt(p, k - 1);
    next = KeyAt(p, k + 1);
  } else if (Closed(p)) {
    prev = KeyAt(p, n - 2);
    prev.t -= duration;
    next = KeyAt(p, 1);
    if (k == n - 1) {
      prev.t += duration;
      next.t += duration;
    }
  } else {
    prev = KeyAt(p, k == 0 ? 0 : k - 1);
    next = KeyAt(p, k == 0 ? 1 : k);
  }
  const double dt = next.t - prev.t;
  *mx = (next.x - prev.x) / dt;
  *my = (next.y - prev.y) / dt;
}

}  // namespace

bool SamplePath(const PathView& p, double time, double* x, double* y) {
  const std::size_t n = p.key_count();
  if (n == 0 || !x || !y) return false;
  const Key first = KeyAt(p, 0), last = KeyAt(p, n - 1);
  if (n == 1) {
    *x = first.x;
    *y = first.y;
    return true;
  }
  double t = std::isfinite(time) ? time : first.t;
  if (p.loop) {
    const double duration = last.t - first.t;
    t = std::fmod(t - first.t, duration);
    if (t < 0) t += duration;
    t += first.t;
    if (t >= last.t) t = first.t;  // fmod rounding can land exactly on the end
  }
  if (t <= first.t) {
    *x = first.x;
    *y = first.y;
    return true;
  }
  if (t >= last.t) {
    *x = last.x;
    *y = last.y;
    return true;
  }
  // Last key with time <= t.
  std::size_t lo = 0, hi = n - 1;
  while (hi - lo > 1) {
    const std::size_t mid = (lo + hi) / 2;
    (KeyAt(p, mid).t <= t ? lo : hi) = mid;
  }
  const Key a = KeyAt(p, lo), b = KeyAt(p, lo + 1);
  const double h = b.t - a.t, s = (t - a.t) / h;
  if (p.interpolation == PathInterpolation::kLinear) {
    *x = a.x + s * (b.x - a.x);
    *y = a.y + s * (b.y - a.y);
    return true;
  }
  double max, may, mbx, mby;
  Tangent(p, lo, &max, &may);
  Tangent(p, lo + 1, &mbx, &mby);
  const double s2 = s * s, s3 = s2 * s;
  const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
  *x = h00 * a.x + h10 * h * max + h01 * b.x + h11 * h * mbx;
  *y = h00 * a.y + h10 * h * may + h01 * b.y + h11 * h * mby;
  return true;
}

bool SamplePath(const Rig& rig, std::uint32_t index, double time, double* x, double* y) {
  if (index >= rig.path_count()) return false;
  return SamplePath(rig.path(index), time, x, y);
}

}  // namespace posemorph
