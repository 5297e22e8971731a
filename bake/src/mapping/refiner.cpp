// SPDX-License-Identifier: MIT
// The Refiner's splits, flips and smoothing (refiner.h): midpoint splits
// (all poses at once), flips that are legal in all N meshes and raise the
// smallest angle over all of them, and angle-based smoothing (Zhou and
// Shimada 2000) of interior vertices, pose by pose, accepted only where no
// triangle inverts and the local smallest angle does not drop.
#include "refiner.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace posemorph::bake::mapping::refine {

double MinAngleOf(const CompatibleMesh& m, const Tri& t) {
  double worst = M_PI;
  for (const Polygon& v : m.vertices) worst = std::min(worst, TriangleMinAngle(v[t[0]], v[t[1]], v[t[2]]));
  return worst;
}

bool Positive(const Polygon& v, const Tri& t) { return Cross(v[t[0]], v[t[1]], v[t[2]]) > 0; }

bool EdgeFirst(Tri& t, std::size_t a, std::size_t b) {
  for (int r = 0; r < 3; ++r) {
    if ((t[0] == a && t[1] == b) || (t[0] == b && t[1] == a)) return true;
    std::rotate(t.begin(), t.begin() + 1, t.end());
  }
  return false;
}

Point BoundaryMidpoint(const Point& a, const Point& b) { return OnEdgeOrOutside(a, b, (a + b) / 2); }

Point OnEdgeOrOutside(const Point& a, const Point& b, const Point& m) {
  Point best = Snap(m);
  double best_d = std::numeric_limits<double>::infinity();
  for (double dx : {std::floor(m.x()), std::ceil(m.x())})
    for (double dy : {std::floor(m.y()), std::ceil(m.y())}) {
      const Point q(dx, dy);
      if (Cross(a, b, q) <= 0 && (q - m).norm() < best_d) best = q, best_d = (q - m).norm();
    }
  return best;
}

Refiner::Refiner(CompatibleMesh& m, std::size_t max_vertices)
    : m_(m), held_(m.vertices[0].size(), false), max_vertices_(max_vertices) {
  // Held: the boundary (vertices on edges used by one triangle) and the features.
  EdgeMap em(m.triangles);
  for (const auto& [key, ts] : em.at)
    if (ts[1] == EdgeMap::kNone) held_[key >> 32] = held_[key & 0xffffffffu] = true;
  for (std::size_t v : m.features) held_[v] = true;
}

bool Refiner::SplitEdge(std::size_t a, std::size_t b, const EdgeMap& em) {
  const auto& ts = em.at.at(Key(a, b));
  const bool on_boundary = ts[1] == EdgeMap::kNone;
  const std::size_t w = m_.vertices[0].size();
  std::vector<Tri> replaced;
  std::vector<std::size_t> which;
  for (std::size_t t : ts) {
    if (t == EdgeMap::kNone) continue;
    Tri tri = m_.triangles[t];
    EdgeFirst(tri, a, b);
    replaced.push_back({tri[0], w, tri[2]});
    replaced.push_back({w, tri[1], tri[2]});
    which.push_back(t);
  }
  for (Polygon& v : m_.vertices) {
    // The boundary edge is directed with the interior on its left as it appears in its triangle.
    Tri tri = m_.triangles[which[0]];
    EdgeFirst(tri, a, b);
    v.push_back(on_boundary ? BoundaryMidpoint(v[tri[0]], v[tri[1]]) : Snap((v[a] + v[b]) / 2));
  }
  bool ok = true;
  for (const Polygon& v : m_.vertices)
    for (const Tri& t : replaced) ok = ok && Positive(v, t);
  if (!ok) {
    for (Polygon& v : m_.vertices) v.pop_back();
    return false;
  }
  held_.push_back(on_boundary);
  m_.triangles[which[0]] = replaced[0];
  m_.triangles.push_back(replaced[1]);
  if (which.size() == 2) {
    m_.triangles[which[1]] = replaced[2];
    m_.triangles.push_back(replaced[3]);
  }
  return true;
}

double Refiner::Length(std::size_t a, std::size_t b) const {
  double l = 0;
  for (const Polygon& v : m_.vertices) l = std::max(l, (v[a] - v[b]).norm());
  return l;
}

// Splits every edge longer than max_length (longest first), until none is;
// false when the vertex budget ran out first.
bool Refiner::SplitLong(double max_length) {
  for (int pass = 0; pass < 64; ++pass) {
    EdgeMap em(m_.triangles);
    std::vector<std::pair<double, std::uint64_t>> longs;
    for (const auto& [key, ts] : em.at) {
      (void)ts;
      const double l = Length(key >> 32, key & 0xffffffffu);
      if (l > max_length) longs.emplace_back(-l, key);
    }
    if (longs.empty()) return true;
    std::sort(longs.begin(), longs.end());
    std::vector<bool> touched(m_.triangles.size(), false);
    for (const auto& [neg, key] : longs) {
      (void)neg;
      const auto& ts = em.at.at(key);
      if ((ts[0] != EdgeMap::kNone && touched[ts[0]]) || (ts[1] != EdgeMap::kNone && touched[ts[1]])) continue;
      for (std::size_t t : ts)
        if (t != EdgeMap::kNone) touched[t] = true;
      if (Full()) return false;
      SplitEdge(key >> 32, key & 0xffffffffu, em);
    }
  }
  return true;
}

int Refiner::Flip() {
  int flips = 0;
  for (int pass = 0; pass < 100; ++pass) {
    EdgeMap em(m_.triangles);
    int this_pass = 0;
    std::vector<bool> touched(m_.triangles.size(), false);
    for (const auto& [key, ts] : em.at) {
      if (ts[1] == EdgeMap::kNone || touched[ts[0]] || touched[ts[1]]) continue;
      const std::size_t u = key >> 32, v = key & 0xffffffffu;
      Tri t1 = m_.triangles[ts[0]], t2 = m_.triangles[ts[1]];
      EdgeFirst(t1, u, v);
      EdgeFirst(t2, u, v);
      // t1 = (p, q, c), t2 = (q, p, d): the quad p d q c, new diagonal c-d.
      const std::size_t p = t1[0], q = t1[1], c = t1[2], d = t2[2];
      if (c == d) continue;
      const Tri n1{p, d, c}, n2{d, q, c};
      bool legal = true;
      for (const Polygon& pos : m_.vertices) legal = legal && Positive(pos, n1) && Positive(pos, n2);
      if (!legal) continue;
      if (em.at.count(Key(c, d))) continue;  // would duplicate an edge
      const double before = std::min(MinAngleOf(m_, t1), MinAngleOf(m_, t2));
      const double after = std::min(MinAngleOf(m_, n1), MinAngleOf(m_, n2));
      if (after <= before + 1e-9) continue;
      m_.triangles[ts[0]] = n1, m_.triangles[ts[1]] = n2;
      touched[ts[0]] = touched[ts[1]] = true;
      ++this_pass;
    }
    flips += this_pass;
    if (this_pass == 0) break;
  }
  return flips;
}

void Refiner::Smooth(int passes) {
  const std::size_t V = m_.vertices[0].size();
  std::vector<std::vector<std::size_t>> incident(V);
  for (std::size_t t = 0; t < m_.triangles.size(); ++t)
    for (std::size_t v : m_.triangles[t]) incident[v].push_back(t);
  // Around v: each triangle (v, a, b) counter-clockwise; neighbour a's ring
  // neighbours are the previous and next vertices around v. The ring is
  // read once (the connectivity does not change here), in the order the
  // sums below have always taken (an unordered_map's, built the same way),
  // so the positions are the same to the bit.
  struct Neighbour {
    std::size_t at, next, prev;
    bool inner;  // has a previous vertex too (not at the ring's open end)
  };
  std::vector<std::vector<Neighbour>> ring(V);
  std::vector<std::vector<Tri>> turned(V);  // the incident triangles, v first
  for (std::size_t v = 0; v < V; ++v) {
    if (held_[v] || incident[v].empty()) continue;
    std::unordered_map<std::size_t, std::size_t> after_of, before_of;
    for (std::size_t t : incident[v]) {
      Tri tri = m_.triangles[t];
      while (tri[0] != v) std::rotate(tri.begin(), tri.begin() + 1, tri.end());
      after_of[tri[1]] = tri[2];
      before_of[tri[2]] = tri[1];
      turned[v].push_back(tri);
    }
    for (const auto& [nj, next] : after_of) {
      const auto b = before_of.find(nj);
      ring[v].push_back({nj, next, b == before_of.end() ? 0 : b->second, b != before_of.end()});
    }
  }
  // A vertex whose ring has not moved since it last stayed put stays put
  // again: it is not evaluated (exact, not an approximation).
  std::vector<std::uint64_t> moved_at(V), settled_at(V);
  std::uint64_t clock = 0;
  for (Polygon& pos : m_.vertices) {
    std::fill(moved_at.begin(), moved_at.end(), 1);
    std::fill(settled_at.begin(), settled_at.end(), 0);
    for (int pass = 0; pass < passes; ++pass) {
      std::size_t moved = 0;
      for (std::size_t v = 0; v < V; ++v) {
        if (held_[v] || incident[v].empty()) continue;
        std::uint64_t last = moved_at[v];
        for (const Neighbour& n : ring[v]) last = std::max({last, moved_at[n.at], moved_at[n.next]});
        if (settled_at[v] > last) continue;
        ++clock;
        double local_before = 1;  // smallest angle as -cos: larger is better
        for (const Tri& tri : turned[v])
          local_before = std::min(local_before, -MinAngleCosine(pos[tri[0]], pos[tri[1]], pos[tri[2]]));
        Point sum = Point::Zero();
        int count = 0;
        for (const Neighbour& n : ring[v]) {
          if (!n.inner) continue;
          const Point& N = pos[n.at];
          const Point dv = pos[v] - N;
          const double tv = std::atan2(dv.y(), dv.x());
          auto rel = [&](const Point& q) {
            double a = std::atan2((q - N).y(), (q - N).x()) - tv;
            while (a > M_PI) a -= 2 * M_PI;
            while (a < -M_PI) a += 2 * M_PI;
            return a;
          };
          const double target = tv + (rel(pos[n.next]) + rel(pos[n.prev])) / 2;
          sum += N + dv.norm() * Point(std::cos(target), std::sin(target));
          ++count;
        }
        if (count == 0) {
          settled_at[v] = clock;
          continue;
        }
        // Try steps of 1, 1/2, 1/4 and 1/10 toward the angle-based position and
        // toward the neighbours' centroid; keep whichever raises the local
        // smallest angle most.
        Point centroid = Point::Zero();
        for (const Neighbour& n : ring[v]) centroid += pos[n.at];
        centroid /= double(ring[v].size());
        const Point old = pos[v];
        const Point angle_based = sum / count;
        Point best = old;
        double best_angle = local_before;
        for (int k = 0; k < 8; ++k) {
          const double f = k % 4 == 0 ? 1.0 : k % 4 == 1 ? 0.5 : k % 4 == 2 ? 0.25 : 0.1;
          pos[v] = Snap(old + f * ((k < 4 ? angle_based : centroid) - old));
          if (pos[v] == old) continue;  // what stays put raises nothing
          // Stops at the first turned triangle, or once the smallest angle is
          // no better than the best: either way this step is not kept.
          bool ok = true;
          double local_after = 1;
          for (std::size_t tri : incident[v]) {
            const Tri& tr = m_.triangles[tri];
            if (!Positive(pos, tr)) {
              ok = false;
              break;
            }
            local_after = std::min(local_after, -MinAngleCosine(pos[tr[0]], pos[tr[1]], pos[tr[2]]));
            if (local_after <= best_angle) break;
          }
          if (ok && local_after > best_angle) best = pos[v], best_angle = local_after;
        }
        pos[v] = best;
        if (best != old) {
          ++moved;
          moved_at[v] = ++clock;
        } else {
          settled_at[v] = clock;
        }
      }
      if (moved == 0) break;
    }
  }
}

// The ratio of the longest to the shortest edge of t in the pose where its
// smallest angle is smallest.
double Refiner::WorstPoseEdgeRatio(const Tri& t) const {
  double worst = M_PI, ratio = 1;
  for (const Polygon& v : m_.vertices) {
    const double angle = TriangleMinAngle(v[t[0]], v[t[1]], v[t[2]]);
    if (!(angle < worst)) continue;
    worst = angle;
    double lo = HUGE_VAL, hi = 0;
    for (int e = 0; e < 3; ++e) {
      const double l = (v[t[e]] - v[t[(e + 1) % 3]]).norm();
      lo = std::min(lo, l), hi = std::max(hi, l);
    }
    ratio = lo > 0 ? hi / lo : HUGE_VAL;
  }
  return ratio;
}

int Refiner::SplitBad(double goal, double min_length, double graded_ratio) {
  EdgeMap em(m_.triangles);
  std::vector<bool> touched(m_.triangles.size(), false);
  int splits = 0;
  const std::size_t T = m_.triangles.size();
  for (std::size_t t = 0; t < T; ++t) {
    if (touched[t] || MinAngleOf(m_, m_.triangles[t]) >= goal) continue;
    const Tri tri = m_.triangles[t];
    std::size_t a = tri[0], b = tri[1];
    for (int e = 1; e < 3; ++e)
      if (Length(tri[e], tri[(e + 1) % 3]) > Length(a, b)) a = tri[e], b = tri[(e + 1) % 3];
    if (Length(a, b) < min_length && !(graded_ratio > 0 && WorstPoseEdgeRatio(tri) > graded_ratio)) continue;
    if (Full()) break;
    const auto& ts = em.at.at(Key(a, b));
    if ((ts[0] != EdgeMap::kNone && touched[ts[0]]) || (ts[1] != EdgeMap::kNone && touched[ts[1]])) continue;
    for (std::size_t u : ts)
      if (u != EdgeMap::kNone) touched[u] = true;
    if (SplitEdge(a, b, em)) ++splits;
  }
  return splits;
}

}  // namespace posemorph::bake::mapping::refine
