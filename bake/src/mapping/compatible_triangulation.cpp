// SPDX-License-Identifier: MIT
// Compatible triangulation of N polygons with corresponding vertices (paper
// section 3.1, extending Baxter et al. 2009 to N shapes). Each piece is split
// along one chord valid in every pose, found in the paper's order:
//   I   a vertex pair with line of sight inside all N polygons;
//   II  a pair joined through one Steiner point in each polygon;
//   III the pair whose shortest link path (Floyd-Warshall over a visibility
//       graph of interior candidate points, per polygon) needs the fewest
//       Steiner points over all N; shorter paths are padded by subdividing.
// Stages II and III share one computation: the Steiner count of a pair is the
// largest over poses of its link distance minus one.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>

#include "geometry.h"
#include "posemorph/bake/mapping/compatible_triangulation.h"
#include "posemorph/bake/error.h"

namespace posemorph::bake::mapping {
namespace {

using Piece = std::vector<std::size_t>;  // global vertex ids, counter-clockwise

// The triangulation's work, counted in elementary steps (a segment test, a
// relaxation) as it goes: intricate boundaries in very different poses could
// otherwise take hours (Floyd-Warshall is cubic in the candidate points).
// Past the budget the bake stops with a message instead.
struct Work {
  std::uint64_t used = 0;
  const ErrorSource* poses = nullptr;
  void Spend(std::uint64_t steps) {
    used += steps;
    if (used > kMaxTriangulationWork)
      throw poses->Error(
          "the boundaries are too intricate to triangulate compatibly within the bake's "
          "limit of " +
          std::to_string(kMaxTriangulationWork) +
          " steps; raise mapping.simplify_tolerance or add landmarks where the poses differ");
  }
};

struct View {  // one pose's positions of one piece
  Polygon p;
  std::size_t n() const { return p.size(); }
  const Point& at(std::size_t k) const { return p[k % p.size()]; }
};

bool IsDiagonal(const View& v, std::size_t a, std::size_t b) {
  const std::size_t n = v.n();
  const Point &A = v.p[a], &B = v.p[b];
  if (!InCone(v.at(a + n - 1), A, v.at(a + 1), B) || !InCone(v.at(b + n - 1), B, v.at(b + 1), A)) return false;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t l = (k + 1) % n;
    if (k == a || k == b || l == a || l == b) continue;
    if (SegmentsMeet(A, B, v.p[k], v.p[l])) return false;
  }
  // No other vertex on the chord (the split would touch itself).
  for (std::size_t k = 0; k < n; ++k)
    if (k != a && k != b && OnSegment(A, B, v.p[k])) return false;
  return true;
}

// Interior point c seen from vertex a (strictly inside the angle, touching nothing).
bool SeesPoint(const View& v, std::size_t a, const Point& c) {
  const std::size_t n = v.n();
  const Point& A = v.p[a];
  if (!InCone(v.at(a + n - 1), A, v.at(a + 1), c)) return false;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t l = (k + 1) % n;
    if (k == a || l == a) continue;
    if (SegmentsMeet(A, c, v.p[k], v.p[l])) return false;
  }
  return true;
}

bool PointsSeeEachOther(const View& v, const Point& c, const Point& d) {
  for (std::size_t k = 0; k < v.n(); ++k)
    if (SegmentsMeet(c, d, v.p[k], v.at(k + 1))) return false;
  return true;
}

// Interior candidates for Steiner points: centroids of an ear-clipping
// triangulation of this pose's piece and midpoints of its diagonals, so any
// two vertices are joined through them along the triangulation's dual tree.
std::vector<Point> Candidates(const View& v, Work& work) {
  std::vector<std::size_t> idx(v.n());
  for (std::size_t k = 0; k < v.n(); ++k) idx[k] = k;
  std::vector<Point> out;
  while (idx.size() > 3) {
    bool clipped = false;
    for (std::size_t k = 0; k < idx.size(); ++k) {
      const std::size_t m = idx.size();
      const std::size_t a = idx[(k + m - 1) % m], b = idx[k], c = idx[(k + 1) % m];
      if (Cross(v.p[a], v.p[b], v.p[c]) <= 0) continue;
      work.Spend(2 * m);
      View rest;
      for (std::size_t i : idx) rest.p.push_back(v.p[i]);
      if (!IsDiagonal(rest, (k + m - 1) % m, (k + 1) % m)) continue;
      out.push_back(Snap((v.p[a] + v.p[b] + v.p[c]) / 3));
      out.push_back(Snap((v.p[a] + v.p[c]) / 2));
      idx.erase(idx.begin() + std::ptrdiff_t(k));
      clipped = true;
      break;
    }
    if (!clipped) break;
  }
  if (idx.size() == 3) out.push_back(Snap((v.p[idx[0]] + v.p[idx[1]] + v.p[idx[2]]) / 3));
  std::vector<Point> inside;
  for (const Point& c : out)
    if (PointInPolygon(v.p, c) == 1) inside.push_back(c);
  return inside;
}

// The smallest angle a chord a-b makes with the boundary edges at its ends,
// over all poses: chords that nearly run along an edge leave slivers.
double Clearance(const std::vector<View>& views, std::size_t a, std::size_t b) {
  double worst = M_PI;
  for (const View& v : views) {
    const std::size_t n = v.n();
    worst = std::min({worst, AngleAt(v.p[a], v.p[b], v.at(a + n - 1)), AngleAt(v.p[a], v.p[b], v.at(a + 1)),
                      AngleAt(v.p[b], v.p[a], v.at(b + n - 1)), AngleAt(v.p[b], v.p[a], v.at(b + 1))});
  }
  return worst;
}
constexpr double kSliver = 4 * M_PI / 180;

constexpr int kUnreachable = std::numeric_limits<int>::max() / 4;

struct LinkPaths {  // one pose's shortest link paths between piece vertices through candidates
  std::vector<Point> cand;
  std::vector<int> steiner;      // n x n: Steiner points needed, or kUnreachable
  std::vector<int> first, last;  // n x n: candidate entered from a, candidate leaving to b
  std::vector<int> dist, next;   // c x c Floyd-Warshall over candidates
};

LinkPaths ComputeLinkPaths(const View& v, Work& work) {
  LinkPaths lp;
  const std::size_t n = v.n();
  lp.cand = Candidates(v, work);
  const std::size_t c = lp.cand.size();
  work.Spend(std::uint64_t(c) * c * (n + c) + std::uint64_t(n) * c * n);  // visibility, Floyd-Warshall, sight lines
  lp.dist.assign(c * c, kUnreachable);
  lp.next.assign(c * c, -1);
  for (std::size_t i = 0; i < c; ++i) {
    lp.dist[i * c + i] = 0, lp.next[i * c + i] = int(i);
    for (std::size_t j = i + 1; j < c; ++j)
      if (PointsSeeEachOther(v, lp.cand[i], lp.cand[j])) {
        lp.dist[i * c + j] = lp.dist[j * c + i] = 1;
        lp.next[i * c + j] = int(j), lp.next[j * c + i] = int(i);
      }
  }
  for (std::size_t k = 0; k < c; ++k)
    for (std::size_t i = 0; i < c; ++i)
      for (std::size_t j = 0; j < c; ++j)
        if (lp.dist[i * c + k] + lp.dist[k * c + j] < lp.dist[i * c + j]) {
          lp.dist[i * c + j] = lp.dist[i * c + k] + lp.dist[k * c + j];
          lp.next[i * c + j] = lp.next[i * c + k];
        }
  std::vector<char> sees(n * c);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t i = 0; i < c; ++i) sees[a * c + i] = SeesPoint(v, a, lp.cand[i]);
  lp.steiner.assign(n * n, kUnreachable);
  lp.first.assign(n * n, -1), lp.last.assign(n * n, -1);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 2; b < n; ++b) {
      if (a == 0 && b == n - 1) continue;
      if (IsDiagonal(v, a, b)) {
        lp.steiner[a * n + b] = 0;
        continue;
      }
      int best = kUnreachable;
      work.Spend(n + c);
      for (std::size_t i = 0; i < c; ++i) {
        if (!sees[a * c + i]) continue;
        work.Spend(c);
        for (std::size_t j = 0; j < c; ++j) {
          if (!sees[b * c + j] || lp.dist[i * c + j] >= best - 1) continue;
          best = lp.dist[i * c + j] + 1;
          lp.first[a * n + b] = int(i), lp.last[a * n + b] = int(j);
        }
      }
      lp.steiner[a * n + b] = best;
    }
  return lp;
}

// Stage I: a chord a-b inside the piece in every pose; balanced ones first
// (both halves at least a third), then short ones, slivers last.
bool FindCommonChord(const std::vector<View>& views, Work& work, std::size_t* A, std::size_t* B) {
  const std::size_t N = views.size(), n = views[0].p.size();
  std::vector<std::tuple<bool, int, double, std::size_t, std::size_t>> pairs;
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 2; b < n; ++b) {
      if (a == 0 && b == n - 1) continue;
      const std::size_t small = std::min(b - a, n - (b - a));
      double length = 0;
      for (std::size_t i = 0; i < N; ++i) length = std::max(length, (views[i].p[a] - views[i].p[b]).norm());
      pairs.emplace_back(Clearance(views, a, b) < kSliver, 3 * small >= n ? 0 : int(n - small), length, a, b);
    }
  std::sort(pairs.begin(), pairs.end());
  for (const auto& [sliver, bucket, length, a, b] : pairs) {
    (void)sliver, (void)bucket, (void)length;
    bool all = true;
    for (std::size_t i = 0; i < N && all; ++i) {
      work.Spend(n);
      all = IsDiagonal(views[i], a, b);
    }
    if (all) {
      *A = a, *B = b;
      return true;
    }
  }
  return false;
}

// One pose's link path from a to b with k Steiner points (a path with fewer
// is padded by subdividing its longest link), end points included, into
// *out; true if both halves it cuts the piece into are simple with area.
bool LinkPathSplits(const LinkPaths& L, const View& view, std::size_t a, std::size_t b, int k, Polygon* out) {
  const std::size_t n = view.p.size(), c = L.cand.size();
  Polygon& path = *out;
  path.push_back(view.p[a]);
  if (L.steiner[a * n + b] > 0)
    for (int s = L.first[a * n + b];; s = L.next[std::size_t(s) * c + std::size_t(L.last[a * n + b])]) {
      path.push_back(L.cand[std::size_t(s)]);
      if (s == L.last[a * n + b]) break;
    }
  path.push_back(view.p[b]);
  while (path.size() < std::size_t(k) + 2) {
    std::size_t longest = 0;
    for (std::size_t j = 0; j + 1 < path.size(); ++j)
      if ((path[j + 1] - path[j]).squaredNorm() > (path[longest + 1] - path[longest]).squaredNorm()) longest = j;
    path.insert(path.begin() + std::ptrdiff_t(longest + 1), Snap((path[longest] + path[longest + 1]) / 2));
  }
  // Both halves must be simple polygons with area in this pose.
  Polygon left(view.p.begin() + std::ptrdiff_t(a), view.p.begin() + std::ptrdiff_t(b) + 1);
  left.insert(left.end(), path.rbegin() + 1, path.rend() - 1);
  Polygon right(view.p.begin() + std::ptrdiff_t(b), view.p.end());
  right.insert(right.end(), view.p.begin(), view.p.begin() + std::ptrdiff_t(a) + 1);
  right.insert(right.end(), path.begin() + 1, path.end() - 1);
  return SignedArea(left) > 0 && SignedArea(right) > 0 && IsSimplePolygon(left) && IsSimplePolygon(right);
}

// Stages II and III: the chord a-b whose link paths need the fewest Steiner
// points in every pose, its points added to the mesh as *chain (ids from A
// to B). Throws poses.Error when none fits.
void SplitThroughSteiner(const std::vector<View>& views, Work& work, std::size_t max_steiner_points,
                         const ErrorSource& poses, CompatibleMesh& mesh, std::size_t* A, std::size_t* B,
                         std::vector<std::size_t>* chain) {
  const std::size_t N = views.size(), n = views[0].p.size();
  std::vector<LinkPaths> lp(N);
  for (std::size_t i = 0; i < N; ++i) lp[i] = ComputeLinkPaths(views[i], work);
  std::vector<std::tuple<int, bool, std::size_t, std::size_t, std::size_t>> options;  // k, sliver, -balance, a, b
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = a + 2; b < n; ++b) {
      if (a == 0 && b == n - 1) continue;
      int k = 0;
      for (std::size_t i = 0; i < N; ++i) k = std::max(k, lp[i].steiner[a * n + b]);
      if (k >= kUnreachable) continue;
      options.emplace_back(k, Clearance(views, a, b) < kSliver, n - std::min(b - a, n - (b - a)), a, b);
    }
  std::sort(options.begin(), options.end());
  for (const auto& [k, sliver, unbalance, a, b] : options) {
    (void)sliver, (void)unbalance;
    work.Spend(std::uint64_t(N) * (n + std::size_t(k)) * 8);  // paths, both halves checked simple
    if (mesh.steiner_points + std::size_t(k) > max_steiner_points) {
      throw poses.Error("the drawings cannot be triangulated compatibly with at most " +
                        std::to_string(max_steiner_points) + " Steiner points (mapping.max_steiner_points)");
    }
    std::vector<Polygon> paths(N);
    bool ok = true;
    for (std::size_t i = 0; i < N && ok; ++i) ok = LinkPathSplits(lp[i], views[i], a, b, k, &paths[i]);
    if (!ok) continue;
    *A = a, *B = b;
    chain->resize(std::size_t(k));
    for (std::size_t& id : *chain) {
      id = mesh.vertices[0].size();
      for (std::size_t i = 0; i < N; ++i) mesh.vertices[i].push_back(Point::Zero());
    }
    for (std::size_t i = 0; i < N; ++i)
      for (std::size_t j = 0; j < chain->size(); ++j) mesh.vertices[i][(*chain)[j]] = paths[i][j + 1];
    mesh.steiner_points += chain->size();
    return;
  }
  throw poses.Error(
      "the drawings cannot be triangulated compatibly (no chord joins the same two boundary points inside every pose)");
}

}  // namespace

CompatibleMesh TriangulateCompatibly(const std::vector<Polygon>& polygons, const ErrorSource& poses,
                                     std::size_t max_steiner_points) {
  const std::size_t N = polygons.size(), n0 = polygons[0].size();
  Work work;
  work.poses = &poses;
  CompatibleMesh mesh;
  mesh.vertices = polygons;
  mesh.boundary_vertices = n0;
  std::vector<Piece> stack(1);
  for (std::size_t k = 0; k < n0; ++k) stack[0].push_back(k);

  while (!stack.empty()) {
    Piece piece = std::move(stack.back());
    stack.pop_back();
    const std::size_t n = piece.size();
    std::vector<View> views(N);
    for (std::size_t i = 0; i < N; ++i)
      for (std::size_t id : piece) views[i].p.push_back(mesh.vertices[i][id]);
    if (n == 3) {
      for (std::size_t i = 0; i < N; ++i)
        if (Cross(views[i].p[0], views[i].p[1], views[i].p[2]) <= 0)
          throw poses.Error("internal: a degenerate triangle in pose " + std::to_string(i + 1) + " of these " +
                            std::to_string(N));
      mesh.triangles.push_back({piece[0], piece[1], piece[2]});
      continue;
    }

    std::size_t A = 0, B = 0;
    std::vector<std::size_t> chain;  // Steiner vertex ids from A to B
    work.Spend(std::uint64_t(n) * n * N);
    if (!FindCommonChord(views, work, &A, &B))
      SplitThroughSteiner(views, work, max_steiner_points, poses, mesh, &A, &B, &chain);
    Piece left(piece.begin() + std::ptrdiff_t(A), piece.begin() + std::ptrdiff_t(B) + 1);
    left.insert(left.end(), chain.rbegin(), chain.rend());
    Piece right(piece.begin() + std::ptrdiff_t(B), piece.end());
    right.insert(right.end(), piece.begin(), piece.begin() + std::ptrdiff_t(A) + 1);
    right.insert(right.end(), chain.begin(), chain.end());
    stack.push_back(std::move(left));
    stack.push_back(std::move(right));
  }
  return mesh;
}

}  // namespace posemorph::bake::mapping
