// SPDX-License-Identifier: MIT
// Compatible refinement of N triangle meshes with one connectivity: midpoint
// splits (all poses at once), flips that are legal in all N meshes and raise
// the smallest angle over all of them, and angle-based smoothing (Zhou and
// Shimada 2000) of interior vertices, pose by pose, accepted only where no
// triangle inverts and the local smallest angle does not drop.
#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "geometry.h"
#include "posemorph/bake/mapping/compatible_refinement.h"

namespace posemorph::bake::mapping {
namespace {

using Tri = std::array<std::size_t, 3>;

std::uint64_t Key(std::size_t a, std::size_t b) {
  return (std::uint64_t(std::min(a, b)) << 32) | std::uint64_t(std::max(a, b));
}

struct EdgeMap {
  std::unordered_map<std::uint64_t, std::array<std::size_t, 2>> at;  // up to two triangles, npos if none
  static constexpr std::size_t kNone = ~std::size_t(0);
  explicit EdgeMap(const std::vector<Tri>& tris) {
    for (std::size_t t = 0; t < tris.size(); ++t)
      for (int e = 0; e < 3; ++e) {
        auto [it, fresh] =
            at.try_emplace(Key(tris[t][e], tris[t][(e + 1) % 3]), std::array<std::size_t, 2>{kNone, kNone});
        (void)fresh;
        it->second[it->second[0] == kNone ? 0 : 1] = t;
      }
  }
};

double MinAngleOf(const CompatibleMesh& m, const Tri& t) {
  double worst = M_PI;
  for (const Polygon& v : m.vertices) worst = std::min(worst, TriangleMinAngle(v[t[0]], v[t[1]], v[t[2]]));
  return worst;
}

bool Positive(const Polygon& v, const Tri& t) { return Cross(v[t[0]], v[t[1]], v[t[2]]) > 0; }

// Rotates t so that its first edge is {a, b} in either direction; false if t lacks it.
bool EdgeFirst(Tri& t, std::size_t a, std::size_t b) {
  for (int r = 0; r < 3; ++r) {
    if ((t[0] == a && t[1] == b) || (t[0] == b && t[1] == a)) return true;
    std::rotate(t.begin(), t.begin() + 1, t.end());
  }
  return false;
}

// A grid point near the midpoint of a boundary edge a -> b, on it or just
// outside (to its right), so the polygon still encloses what it enclosed.
Point BoundaryMidpoint(const Point& a, const Point& b) {
  const Point m = (a + b) / 2;
  Point best = Snap(m);
  double best_d = std::numeric_limits<double>::infinity();
  for (double dx : {std::floor(m.x()), std::ceil(m.x())})
    for (double dy : {std::floor(m.y()), std::ceil(m.y())}) {
      const Point q(dx, dy);
      if (Cross(a, b, q) <= 0 && (q - m).norm() < best_d) best = q, best_d = (q - m).norm();
    }
  return best;
}

class Refiner {
 public:
  Refiner(CompatibleMesh& m, std::size_t max_vertices)
      : m_(m), held_(m.vertices[0].size(), false), max_vertices_(max_vertices) {
    // Held: the boundary (vertices on edges used by one triangle) and the features.
    EdgeMap em(m.triangles);
    for (const auto& [key, ts] : em.at)
      if (ts[1] == EdgeMap::kNone) held_[key >> 32] = held_[key & 0xffffffffu] = true;
    for (std::size_t v : m.features) held_[v] = true;
  }

  bool SplitEdge(std::size_t a, std::size_t b, const EdgeMap& em) {
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

  double Length(std::size_t a, std::size_t b) const {
    double l = 0;
    for (const Polygon& v : m_.vertices) l = std::max(l, (v[a] - v[b]).norm());
    return l;
  }

  // Splits every edge longer than max_length (longest first), until none is.
  bool Full() const { return m_.vertices[0].size() >= max_vertices_; }

  // False when the vertex budget ran out first.
  bool SplitLong(double max_length) {
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

  int Flip() {
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

  void Smooth(int passes) {
    const std::size_t V = m_.vertices[0].size();
    std::vector<std::vector<std::size_t>> incident(V);
    for (std::size_t t = 0; t < m_.triangles.size(); ++t)
      for (std::size_t v : m_.triangles[t]) incident[v].push_back(t);
    for (int pass = 0; pass < passes; ++pass) {
      std::size_t moved = 0;
      for (Polygon& pos : m_.vertices)
        for (std::size_t v = 0; v < V; ++v) {
          if (held_[v] || incident[v].empty()) continue;
          // Around v: each triangle (v, a, b) counter-clockwise; neighbour a's ring
          // neighbours are the previous and next vertices around v.
          Point sum = Point::Zero();
          double local_before = 1;  // smallest angle as -cos: larger is better
          std::unordered_map<std::size_t, std::size_t> after_of, before_of;
          for (std::size_t t : incident[v]) {
            Tri tri = m_.triangles[t];
            while (tri[0] != v) std::rotate(tri.begin(), tri.begin() + 1, tri.end());
            after_of[tri[1]] = tri[2];
            before_of[tri[2]] = tri[1];
            local_before = std::min(local_before, -MinAngleCosine(pos[tri[0]], pos[tri[1]], pos[tri[2]]));
          }
          int count = 0;
          for (const auto& [nj, next] : after_of) {
            if (!before_of.count(nj)) continue;
            const std::size_t prev = before_of[nj];
            const Point& N = pos[nj];
            const Point dv = pos[v] - N;
            const double tv = std::atan2(dv.y(), dv.x());
            auto rel = [&](const Point& q) {
              double a = std::atan2((q - N).y(), (q - N).x()) - tv;
              while (a > M_PI) a -= 2 * M_PI;
              while (a < -M_PI) a += 2 * M_PI;
              return a;
            };
            const double target = tv + (rel(pos[next]) + rel(pos[prev])) / 2;
            sum += N + dv.norm() * Point(std::cos(target), std::sin(target));
            ++count;
          }
          if (count == 0) continue;
          // Try steps of 1, 1/2, 1/4 and 1/10 toward the angle-based position and
          // toward the neighbours' centroid; keep whichever raises the local
          // smallest angle most.
          Point centroid = Point::Zero();
          for (const auto& [nj, next] : after_of) {
            (void)next;
            centroid += pos[nj];
          }
          centroid /= double(after_of.size());
          const Point old = pos[v];
          const Point angle_based = sum / count;
          Point best = old;
          double best_angle = local_before;
          for (int k = 0; k < 8; ++k) {
            const double f = k % 4 == 0 ? 1.0 : k % 4 == 1 ? 0.5 : k % 4 == 2 ? 0.25 : 0.1;
            pos[v] = Snap(old + f * ((k < 4 ? angle_based : centroid) - old));
            bool ok = true;
            double local_after = 1;
            for (std::size_t tri : incident[v]) {
              const Tri& tr = m_.triangles[tri];
              ok = ok && Positive(pos, tr);
              local_after = std::min(local_after, -MinAngleCosine(pos[tr[0]], pos[tr[1]], pos[tr[2]]));
            }
            if (ok && local_after > best_angle) best = pos[v], best_angle = local_after;
          }
          moved += best != old;
          pos[v] = best;
        }
      if (moved == 0) break;
    }
  }

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
  int CollapseBoundarySlivers(double goal, double max_distance) {
    int removed = 0;
    for (int pass = 0; pass < 16; ++pass) {
      const int this_pass = CollapseOnce(goal, max_distance);
      removed += this_pass;
      if (this_pass == 0) break;
    }
    return removed;
  }

  // Splits the longest edge of each triangle whose smallest angle is below the goal.
  int SplitBad(double goal, double min_length) {
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
      if (Length(a, b) < min_length) continue;
      if (Full()) break;
      const auto& ts = em.at.at(Key(a, b));
      if ((ts[0] != EdgeMap::kNone && touched[ts[0]]) || (ts[1] != EdgeMap::kNone && touched[ts[1]])) continue;
      for (std::size_t u : ts)
        if (u != EdgeMap::kNone) touched[u] = true;
      if (SplitEdge(a, b, em)) ++splits;
    }
    return splits;
  }

 private:
  int CollapseOnce(double goal, double max_distance) {
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
  bool TryCollapse(std::size_t v, std::size_t u, std::size_t gone,
                   const std::vector<std::vector<std::size_t>>& incident, const std::vector<std::size_t>& next_of,
                   const std::vector<std::size_t>& prev_of, double max_distance) {
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

  CompatibleMesh& m_;
  std::vector<bool> held_;  // never moved: boundary vertices and features
  std::size_t max_vertices_;
};

// Rounds of splitting the longest edge of bad triangles, then flips and
// smoothing; with `collapse`, each round first removes the boundary vertices
// that make slivers (Refiner::CollapseBoundarySlivers).
void RefineRounds(Refiner& r, const CompatibleMesh& mesh, const RefinementParameters& prm, bool collapse) {
  const double goal = prm.min_angle_goal * M_PI / 180;
  const double min_length = prm.max_edge_length > 0 ? prm.max_edge_length / 4 : 0;
  for (int round = 0; round < prm.rounds; ++round) {
    if (MinAngleDegrees(mesh) >= prm.min_angle_goal) break;
    const int collapsed = collapse ? r.CollapseBoundarySlivers(goal, prm.max_collapse_distance) : 0;
    if (r.SplitBad(goal, min_length) == 0 && collapsed == 0) break;
    r.Flip();
    r.Smooth(24);
    r.Flip();
  }
}

}  // namespace

bool RefineCompatibly(CompatibleMesh& mesh, const RefinementParameters& prm) {
  Refiner r(mesh, prm.max_vertices);
  const bool within_budget = prm.max_edge_length > 0 ? r.SplitLong(prm.max_edge_length) : true;
  if (!within_budget) return false;
  r.Flip();
  r.Smooth(24);
  r.Flip();
  if (!prm.collapse_slivers) {
    RefineRounds(r, mesh, prm, false);
    return true;
  }
  // Removing vertices can also leave the boundary too coarse for the splits
  // that follow: the rounds without it are run too, and the better kept.
  CompatibleMesh plain = mesh;
  Refiner p(plain, prm.max_vertices);  // holds the same: the boundary and the features
  RefineRounds(p, plain, prm, false);
  RefineRounds(r, mesh, prm, true);
  if (MinAngleDegrees(plain) >= MinAngleDegrees(mesh)) mesh = std::move(plain);
  return true;
}

void ImproveCompatibly(CompatibleMesh& mesh) {
  Refiner r(mesh, mesh.vertices[0].size());
  r.Flip();
  r.Smooth(8);
  r.Flip();
}

double MinAngleDegrees(const CompatibleMesh& mesh) {
  double worst = M_PI;
  for (const auto& t : mesh.triangles) worst = std::min(worst, MinAngleOf(mesh, t));
  return worst * 180 / M_PI;
}

}  // namespace posemorph::bake::mapping
