// SPDX-License-Identifier: MIT
// The Refiner's removal of boundary slivers (refiner.h,
// Refiner::CollapseBoundarySlivers): boundary vertices collapsed into a
// neighbour where that raises the smallest angle and keeps the mesh
// enclosing the outline.
#include <algorithm>
#include <cmath>

#include "refiner.h"

namespace posemorph::bake::mapping::refine {

// Removes boundary vertices that make slivers: where a triangle's smallest
// angle (over all poses) is below the goal and lies opposite a boundary
// edge that is the triangle's shortest in its worst pose, one end of that
// edge is collapsed into the other, so the boundary goes straight from the
// removed vertex's neighbour to its other neighbour. Accepted only where
// every changed triangle stays positive in every pose, the smallest angle
// around the removed vertex rises, no edge is duplicated (the link
// condition), and the removed vertex is a reflex or straight corner in
// every pose (removing it only grows the mesh, so the mesh still encloses
// the outline) within max_distance of the new edge (the mesh grows by no
// more). Features are never removed. Returns the number removed.
int Refiner::CollapseBoundarySlivers(double goal, double max_distance) {
  int removed = 0;
  for (int pass = 0; pass < 16; ++pass) {
    const int this_pass = CollapseOnce(goal, max_distance);
    removed += this_pass;
    if (this_pass == 0) break;
  }
  return removed;
}

int Refiner::CollapseOnce(double goal, double max_distance) {
  const std::size_t V = m_.vertices[0].size(), T = m_.triangles.size();
  std::vector<std::vector<std::size_t>> incident(V);
  for (std::size_t t = 0; t < T; ++t)
    for (std::size_t v : m_.triangles[t]) incident[v].push_back(t);
  EdgeMap em(m_.triangles);
  // next_of[v]: the boundary vertex after v (the boundary edge v -> next
  // appears in that direction in its triangle, the interior on its left).
  constexpr std::size_t kNone = EdgeMap::kNone;
  std::vector<std::size_t> next_of(V, kNone), prev_of(V, kNone);
  for (const Tri& t : m_.triangles)
    for (int e = 0; e < 3; ++e) {
      const std::size_t a = t[e], b = t[(e + 1) % 3];
      if (em.at.at(Key(a, b))[1] == kNone) next_of[a] = b, prev_of[b] = a;
    }
  std::vector<bool> is_feature(V, false);
  for (std::size_t f : m_.features) is_feature[f] = true;
  std::vector<bool> touched(V, false), dead(T, false);
  int collapsed = 0;
  for (std::size_t t = 0; t < T; ++t) {
    const Tri tri = m_.triangles[t];
    if (dead[t] || touched[tri[0]] || touched[tri[1]] || touched[tri[2]]) continue;
    if (MinAngleOf(m_, tri) >= goal) continue;
    // The worst pose and its shortest edge.
    std::size_t worst_pose = 0;
    double worst = M_PI;
    for (std::size_t k = 0; k < m_.vertices.size(); ++k) {
      const Polygon& p = m_.vertices[k];
      const double a = TriangleMinAngle(p[tri[0]], p[tri[1]], p[tri[2]]);
      if (a < worst) worst = a, worst_pose = k;
    }
    const Polygon& wp = m_.vertices[worst_pose];
    int shortest = 0;
    for (int e = 1; e < 3; ++e)
      if ((wp[tri[e]] - wp[tri[(e + 1) % 3]]).norm() < (wp[tri[shortest]] - wp[tri[(shortest + 1) % 3]]).norm())
        shortest = e;
    const std::size_t a = tri[shortest], b = tri[(shortest + 1) % 3];
    if (em.at.at(Key(a, b))[1] != kNone) continue;  // not a boundary edge
    for (const auto& [v, u] : {std::pair{a, b}, std::pair{b, a}}) {
      if (is_feature[v] || !TryCollapse(v, u, t, incident, next_of, prev_of, max_distance)) continue;
      for (std::size_t s : incident[v])
        for (std::size_t x : m_.triangles[s]) touched[x] = true;
      for (std::size_t s : incident[u])
        for (std::size_t x : m_.triangles[s]) touched[x] = true;
      dead[t] = true;
      ++collapsed;
      break;
    }
  }
  if (collapsed == 0) return 0;
  // Drop the removed triangles and the vertices no triangle uses any more.
  std::vector<Tri> kept;
  for (std::size_t t = 0; t < T; ++t)
    if (!dead[t]) kept.push_back(m_.triangles[t]);
  m_.triangles = std::move(kept);
  std::vector<bool> used(V, false);
  for (const Tri& t : m_.triangles)
    for (std::size_t v : t) used[v] = true;
  std::vector<std::size_t> index(V, kNone);
  std::size_t n = 0, boundary = 0;
  for (std::size_t v = 0; v < V; ++v)
    if (used[v]) {
      index[v] = n++;
      boundary += v < m_.boundary_vertices;
    }
  for (Polygon& p : m_.vertices) {
    Polygon q;
    q.reserve(n);
    for (std::size_t v = 0; v < V; ++v)
      if (used[v]) q.push_back(p[v]);
    p = std::move(q);
  }
  std::vector<bool> held(n);
  for (std::size_t v = 0; v < V; ++v)
    if (used[v]) held[index[v]] = held_[v];
  held_ = std::move(held);
  for (Tri& t : m_.triangles)
    for (std::size_t& v : t) v = index[v];
  for (std::size_t& f : m_.features) f = index[f];
  m_.boundary_vertices = boundary;
  return collapsed;
}

// Collapses boundary vertex v into its boundary neighbour u (the edge u-v
// is in triangle `gone`, which disappears), if that is acceptable.
bool Refiner::TryCollapse(std::size_t v, std::size_t u, std::size_t gone,
                          const std::vector<std::vector<std::size_t>>& incident,
                          const std::vector<std::size_t>& next_of, const std::vector<std::size_t>& prev_of,
                          double max_distance) {
  const std::size_t prev = prev_of[v], next = next_of[v];
  if (prev == EdgeMap::kNone || next == EdgeMap::kNone || (u != prev && u != next)) return false;
  // Link condition: u and v share exactly one neighbour, the third vertex of `gone`.
  std::size_t third = EdgeMap::kNone;
  for (std::size_t x : m_.triangles[gone])
    if (x != u && x != v) third = x;
  std::vector<std::size_t> around_u, around_v;
  for (std::size_t s : incident[u])
    for (std::size_t x : m_.triangles[s])
      if (x != u) around_u.push_back(x);
  for (std::size_t s : incident[v])
    for (std::size_t x : m_.triangles[s])
      if (x != v) around_v.push_back(x);
  for (std::size_t x : around_v)
    if (x != u && x != third && std::find(around_u.begin(), around_u.end(), x) != around_u.end()) return false;
  // In every pose the removed corner is reflex or straight (the mesh only
  // grows) and within max_distance of the edge that replaces it.
  for (const Polygon& p : m_.vertices) {
    if (Cross(p[prev], p[v], p[next]) > 0) return false;
    const Point d = p[next] - p[prev];
    const double length2 = d.squaredNorm();
    if (!(length2 > 0)) return false;
    const double t = std::clamp((p[v] - p[prev]).dot(d) / length2, 0.0, 1.0);
    if ((p[v] - (p[prev] + t * d)).norm() > max_distance) return false;
  }
  double before = M_PI, after = M_PI;
  for (std::size_t s : incident[v]) {
    before = std::min(before, MinAngleOf(m_, m_.triangles[s]));
    if (s == gone) continue;
    Tri moved = m_.triangles[s];
    for (std::size_t& x : moved)
      if (x == v) x = u;
    for (const Polygon& p : m_.vertices)
      if (!Positive(p, moved)) return false;
    after = std::min(after, MinAngleOf(m_, moved));
  }
  if (!(after > before + 1e-9)) return false;
  for (std::size_t s : incident[v])
    if (s != gone)
      for (std::size_t& x : m_.triangles[s])
        if (x == v) x = u;
  return true;
}

}  // namespace posemorph::bake::mapping::refine
