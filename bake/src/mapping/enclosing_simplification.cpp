// SPDX-License-Identifier: MIT
// Compatible enclosing simplification (paper section 3.1; Baxter et al.
// 2009). Starts from the M corresponding points, pushed just outward so each
// polygon encloses its outline, then removes the N-tuple whose removal costs
// least (maximum over poses) until that cost exceeds the tolerance. Removing
// vertex j joins its neighbours a and b; where the outline between them bulges
// past the chord, a and b slide outward along their other edges until the
// chord clears it, so those edges keep their lines and the outline stays
// inside. Every step is checked exactly on the integer grid: the new edges
// keep the outline on their inner side, cross neither the outline nor the
// rest of the polygon.
#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include "geometry.h"
#include "outline_arc.h"
#include "span_splitting.h"
#include "posemorph/bake/mapping/enclosing_simplification.h"
#include "posemorph/bake/error.h"
#include "posemorph/bake/mapping/limits.h"

namespace posemorph::bake::mapping {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

class OutlineEdges;
struct PoseState : OutlineArc {
  const OutlineEdges* edges = nullptr;
  std::vector<double> at;  // per corresponding point, unwrapped arc length
  Polygon pos;             // current vertex positions (grid)
};

struct Linked {
  std::vector<std::size_t> prev, next;
  std::vector<bool> alive;
};

// Does the segment (p, q) meet any alive polygon edge other than those at
// its own vertices u, v (indices), or fold back onto its neighbours?
bool HitsPolygon(const PoseState& st, const Linked& L, std::size_t u, std::size_t v, const Point& p, const Point& q,
                 std::size_t start) {
  const Point lo = p.cwiseMin(q), hi = p.cwiseMax(q);
  std::size_t e = start;
  do {
    const std::size_t f = L.next[e];
    const Point &c = st.pos[e], &d = st.pos[f];
    if (!OutsideBox(lo, hi, c, d)) {
      const bool shares_u = e == u || f == u, shares_v = e == v || f == v;
      if (shares_u && shares_v) {
        // the same edge (or the reverse of a 2-gon): skip
      } else if (shares_u || shares_v) {
        const Point& shared = shares_u ? p : q;
        const Point& mine = shares_u ? q : p;
        const Point& theirs = (e == u || e == v) ? d : c;
        if (Cross(shared, mine, theirs) == 0 && (mine - shared).dot(theirs - shared) > 0) return true;
      } else if (SegmentsMeet(p, q, c, d)) {
        return true;
      }
    }
    e = f;
  } while (e != start);
  return false;
}

// The outline's edges in a hierarchy of consecutive runs, each with its
// bounding box (runs of 16 edges, runs of 16 runs, ...): a segment is tested
// exactly only against the edges of runs whose boxes it meets, so long
// outlines cost about log(n) boxes and a few edges per test instead of n.
class OutlineEdges {
 public:
  explicit OutlineEdges(const Polygon& outline) : o_(&outline) {
    const std::size_t n = outline.size();
    std::vector<Box> level((n + kFan - 1) / kFan);
    for (std::size_t i = 0; i < n; ++i) {
      Box& b = level[i / kFan];
      const Point &c = outline[i], &d = outline[(i + 1) % n];
      b.lo = b.lo.cwiseMin(c.cwiseMin(d)), b.hi = b.hi.cwiseMax(c.cwiseMax(d));
    }
    levels_.push_back(std::move(level));
    while (levels_.back().size() > 1) {
      const std::vector<Box>& below = levels_.back();
      std::vector<Box> up((below.size() + kFan - 1) / kFan);
      for (std::size_t k = 0; k < below.size(); ++k) {
        Box& b = up[k / kFan];
        b.lo = b.lo.cwiseMin(below[k].lo), b.hi = b.hi.cwiseMax(below[k].hi);
      }
      levels_.push_back(std::move(up));
    }
  }

  // The open segment p-q properly crosses an outline edge.
  bool Crosses(const Point& p, const Point& q) const {
    if (o_->empty()) return false;
    return Visit(levels_.size() - 1, 0, p, q, p.cwiseMin(q), p.cwiseMax(q));
  }

 private:
  static constexpr std::size_t kFan = 16;
  struct Box {
    Point lo{kInf, kInf}, hi{-kInf, -kInf};
  };

  bool Visit(std::size_t level, std::size_t k, const Point& p, const Point& q, const Point& lo, const Point& hi) const {
    const Box& b = levels_[level][k];
    if (b.hi.x() < lo.x() || b.lo.x() > hi.x() || b.hi.y() < lo.y() || b.lo.y() > hi.y()) return false;
    if (level == 0) {
      const std::size_t n = o_->size();
      for (std::size_t i = k * kFan; i < std::min(n, (k + 1) * kFan); ++i) {
        const Point &c = (*o_)[i], &d = (*o_)[(i + 1) % n];
        if (!OutsideBox(lo, hi, c, d) && ProperlyCross(p, q, c, d)) return true;
      }
      return false;
    }
    const std::size_t below = levels_[level - 1].size();
    for (std::size_t c = k * kFan; c < std::min(below, (k + 1) * kFan); ++c)
      if (Visit(level - 1, c, p, q, lo, hi)) return true;
    return false;
  }

  const Polygon* o_;
  std::vector<std::vector<Box>> levels_;
};

// Every outline vertex between the edge's ends is on its inner side (or on it).
bool SpanInside(const PoseState& st, std::size_t a, std::size_t b, const Point& pa, const Point& pb) {
  bool ok = true;
  st.ForSpan(st.at[a], st.at[b], [&](std::size_t k) {
    if (ok && Cross(pa, pb, (*st.outline)[k]) < 0) ok = false;
  });
  return ok;
}

double SpanOutside(const PoseState& st, std::size_t a, std::size_t b, const Point& pa, const Point& pb) {
  double worst = -kInf;
  st.ForSpan(st.at[a], st.at[b], [&](std::size_t k) { worst = std::max(worst, Outside(pa, pb, (*st.outline)[k])); });
  return worst;
}

double SpanDistance(const PoseState& st, std::size_t a, std::size_t b, const Point& pa, const Point& pb) {
  double worst = 0;
  st.ForSpan(st.at[a], st.at[b], [&](std::size_t k) { worst = std::max(worst, -Outside(pa, pb, (*st.outline)[k])); });
  return worst;
}

// How far a polygon vertex stands from the outline near it: the outline
// vertices of its two edges' spans and its own matched point.
double VertexDistance(const PoseState& st, std::size_t prev, std::size_t next, const Point& at_k, const Point& p) {
  double best = (p - at_k).norm();
  st.ForSpan(st.at[prev], st.at[next], [&](std::size_t v) { best = std::min(best, (p - (*st.outline)[v]).norm()); });
  return best;
}

struct Candidate {
  double error = kInf;
  std::vector<Point> a, b;  // per pose, new positions of the two neighbours
};

// Line p0->p1 extended past p1 meets line q0->q1 extended past q1, at x.
bool MeetBeyond(const Point& p0, const Point& p1, const Point& q0, const Point& q1, Point& x) {
  const Point d = p1 - p0, e = q1 - q0;
  const double den = d.x() * e.y() - d.y() * e.x();
  if (std::abs(den) < 1e-9 * d.norm() * e.norm()) return false;
  const Point w = q0 - p0;
  const double s = (w.x() * e.y() - w.y() * e.x()) / den, u = (w.x() * d.y() - w.y() * d.x()) / den;
  if (!(s >= 1) || !(u >= 1)) return false;
  x = Snap(p0 + s * d);
  return std::abs(x.x()) < kGridLimit / 2 && std::abs(x.y()) < kGridLimit / 2;
}

// The simplification's state: per pose the outline and current polygon, the
// polygon's links, which corresponding points are landmarks.
class Simplifier {
 public:
  Simplifier(const std::vector<Polygon>& outlines, const CorrespondedBoundary& boundary, double tolerance)
      : outlines_(outlines),
        boundary_(boundary),
        tolerance_(tolerance),
        N(outlines.size()),
        M(boundary.points[0].size()),
        st(N),
        landmark(M, false) {
    edges.reserve(N);  // so the pointers to them stay valid
    for (std::size_t k : boundary.landmarks) landmark[k] = true;
  }

  // 1. The corresponding points of pose i, each edge pushed out just past
  // its span. Returns the edges no push could make enclose their span (an
  // outline tip between two points whose normals point past it, as a
  // pixel-art hand one pixel wide makes), or when every edge encloses its
  // span, those that cross each other: empty when the polygon is simple.
  // Careful (after a first failure): an edge that encloses its span but
  // crosses the outline elsewhere is not pushed farther (that only made it
  // cross more, across a narrow gap); its ends move back to their share of
  // the push instead.
  std::vector<std::size_t> EncloseOutline(std::size_t i, bool careful = false) {
    const std::vector<Polygon>& outlines = outlines_;
    const CorrespondedBoundary& boundary = boundary_;
    PoseState& s = st[i];
    s.outline = &outlines[i];
    edges.emplace_back(outlines[i]);
    s.edges = &edges.back();
    s.cumulative = CumulativeArcLength(outlines[i]);
    s.perimeter = s.cumulative.back();
    s.at = boundary.at[i];
    const Polygon& q = boundary.points[i];
    std::vector<double> offset(M, 0);
    for (std::size_t e = 0; e < M; ++e) {
      const std::size_t f = (e + 1) % M;
      offset[e] = std::max(0.0, SpanOutside(s, e, f, q[e], q[f])) + 2.0;
    }
    for (int attempt = 0;; ++attempt) {
      s.pos.assign(M, Point::Zero());
      for (std::size_t k = 0; k < M; ++k) {
        const std::size_t e0 = (k + M - 1) % M, e1 = k;
        // Along the vertex's bisecting normal, far enough for both edges
        // (a capped miter: sharp turns move at most ~3x the offset, never flip an edge).
        const Point d0 = (q[k] - q[e0]).normalized(), d1 = (q[(k + 1) % M] - q[k]).normalized();
        const Point n0(d0.y(), -d0.x()), n1(d1.y(), -d1.x());  // outward normals
        Point nb = n0 + n1;
        nb = nb.norm() > 1e-6 ? Point(nb.normalized()) : n1;
        const double need = std::max(offset[e0] / std::max(0.3, nb.dot(n0)), offset[e1] / std::max(0.3, nb.dot(n1)));
        const Point x = need * nb;
        s.pos[k] = Snap(q[k] + x);
      }
      std::vector<std::size_t> failing;
      for (std::size_t e = 0; e < M; ++e) {
        const std::size_t f = (e + 1) % M;
        const bool inside = SpanInside(s, e, f, s.pos[e], s.pos[f]);
        if (!inside || s.edges->Crosses(s.pos[e], s.pos[f])) {
          if (careful && inside)
            offset[e] = std::max(2.0, offset[e] * 0.5);
          else
            offset[e] = offset[e] * 1.5 + 2.0;
          failing.push_back(e);
        }
      }
      // Every edge encloses its span, but pushed out far enough they may
      // cross each other (two sides of a narrow gap, or a sharp turn's
      // miter): pushing more cannot help, so those edges' spans are split
      // (nearer their outline, they need shorter pushes).
      if (failing.empty()) return SelfCrossingEdges(s.pos);
      if (attempt == 30) return failing;
    }
  }

  // 2. Greedy removal.
  void RemoveGreedily() {
    L.prev.resize(M), L.next.resize(M), L.alive.assign(M, true);
    for (std::size_t k = 0; k < M; ++k) L.prev[k] = (k + M - 1) % M, L.next[k] = (k + 1) % M;
    alive = M;
    std::vector<std::uint32_t> version(M, 0);
    const double tolerance = tolerance_;
    using Entry = std::tuple<double, std::size_t, std::uint32_t>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
    for (std::size_t j = 0; j < M; ++j) {
      const double e = Evaluate(j).error;
      if (e <= tolerance) queue.emplace(Priority(j, e), j, version[j]);
    }
    while (!queue.empty()) {
      const auto [key, j, v] = queue.top();
      queue.pop();
      if (!L.alive[j] || v != version[j]) continue;
      const Candidate c = Evaluate(j);
      if (c.error > tolerance) continue;
      const double now = Priority(j, c.error);
      if (now > key) {  // neighbourhood changed since it was queued
        queue.emplace(now, j, version[j]);
        continue;
      }
      if (!Valid(j, c)) continue;  // until a neighbour changes
      const std::size_t a = L.prev[j], b = L.next[j];
      for (std::size_t i = 0; i < N; ++i) st[i].pos[a] = c.a[i], st[i].pos[b] = c.b[i];
      L.next[a] = b, L.prev[b] = a, L.alive[j] = false;
      --alive;
      max_error_ = std::max(max_error_, c.error);
      // Candidates within two links of a or b depend on what moved.
      std::size_t around[6] = {L.prev[L.prev[a]], L.prev[a], a, b, L.next[b], L.next[L.next[b]]};
      for (std::size_t k : around) {
        ++version[k];
        const double ek = Evaluate(k).error;
        if (ek <= tolerance) queue.emplace(Priority(k, ek), k, version[k]);
      }
    }
  }

  SimplifiedBoundary Result() const {
    const CorrespondedBoundary& boundary = boundary_;
    SimplifiedBoundary out;
    out.polygons.resize(N);
    out.max_error = max_error_;
    std::size_t first = boundary.landmarks.empty() ? 0 : boundary.landmarks[0];
    std::size_t k = first;
    do {
      if (landmark[k]) out.landmarks.push_back(out.kept.size());
      out.kept.push_back(k);
      for (std::size_t i = 0; i < N; ++i) out.polygons[i].push_back(st[i].pos[k]);
      k = L.next[k];
    } while (k != first);
    return out;
  }

 private:
  // Three ways to remove vertex j between a and b, the cheapest taken:
  //   chord   join a and b; where the outline bulges past the chord, move
  //           both out along its normal (their other edges turn outward
  //           about their far ends and still clear their spans);
  //   corner  fold the edge a-j (or j-b) into one vertex where the lines of
  //           its two neighbouring edges meet: those edges keep their lines,
  //           the polygon only grows by the triangle a, corner, j.
  // Landmarks are never removed; like any vertex they may move outward within
  // the tolerance. `valid` checks the result exactly.
  Candidate Evaluate(std::size_t j) const {
    const CorrespondedBoundary& boundary = boundary_;
    Candidate best;
    if (landmark[j] || alive <= std::max<std::size_t>(4, boundary.landmarks.size() + 2)) return best;
    const std::size_t a = L.prev[j], b = L.next[j], pa = L.prev[a], nb = L.next[b];
    for (int option = 0; option < 3; ++option) {
      Candidate c;
      c.a.resize(N), c.b.resize(N);
      double error = 0;
      bool possible = true;
      for (std::size_t i = 0; i < N && possible; ++i) {
        const PoseState& s = st[i];
        Point A = s.pos[a], B = s.pos[b];
        if (option == 0) {
          const double out = SpanOutside(s, a, b, A, B);
          if (out > -0.5) {
            const Point d = (B - A).normalized();
            const Point n(d.y(), -d.x());
            A = Snap(A + (std::max(out, 0.0) + 2.0) * n);
            B = Snap(B + (std::max(out, 0.0) + 2.0) * n);
            if (std::abs(A.x()) > kGridLimit / 2 || std::abs(A.y()) > kGridLimit / 2 ||
                std::abs(B.x()) > kGridLimit / 2 || std::abs(B.y()) > kGridLimit / 2)
              possible = false;
          }
        } else if (option == 1) {
          possible = MeetBeyond(s.pos[pa], s.pos[a], s.pos[b], s.pos[j], A);
          if (possible) error = std::max({error, (A - s.pos[a]).norm(), (A - s.pos[j]).norm()});
        } else {
          possible = MeetBeyond(s.pos[nb], s.pos[b], s.pos[a], s.pos[j], B);
          if (possible) error = std::max({error, (B - s.pos[b]).norm(), (B - s.pos[j]).norm()});
        }
        if (!possible) break;
        // Distance between outline and polygon where it changes: outline to
        // the new edges, and the moved vertices to the outline.
        error = std::max({error, SpanDistance(s, a, b, A, B), SpanDistance(s, pa, a, s.pos[pa], A),
                          SpanDistance(s, b, nb, B, s.pos[nb])});
        if (A != s.pos[a]) error = std::max(error, VertexDistance(s, pa, b, boundary.points[i][a], A));
        if (B != s.pos[b]) error = std::max(error, VertexDistance(s, a, nb, boundary.points[i][b], B));
        c.a[i] = A, c.b[i] = B;
      }
      if (!possible) continue;
      c.error = error;
      if (c.error < best.error) best = std::move(c);
    }
    return best;
  }

  // Whether the candidate's new edges keep every outline inside and cross
  // nothing, checked exactly.
  bool Valid(std::size_t j, const Candidate& c) {
    const std::size_t a = L.prev[j], b = L.next[j], pa = L.prev[a], nb = L.next[b];
    for (std::size_t i = 0; i < N; ++i) {
      PoseState& s = st[i];
      const Point A = c.a[i], B = c.b[i];
      if (!SpanInside(s, a, b, A, B)) return false;
      const bool moved_a = A != s.pos[a], moved_b = B != s.pos[b];
      if (moved_a && !SpanInside(s, pa, a, s.pos[pa], A)) return false;
      if (moved_b && !SpanInside(s, b, nb, B, s.pos[nb])) return false;
      if (s.edges->Crosses(A, B) || (moved_a && s.edges->Crosses(s.pos[pa], A)) ||
          (moved_b && s.edges->Crosses(B, s.pos[nb])))
        return false;
      // Test the new edges against the polygon as it would be.
      const Point old_a = s.pos[a], old_b = s.pos[b];
      s.pos[a] = A, s.pos[b] = B;
      L.next[a] = b, L.prev[b] = a;
      const bool hit = HitsPolygon(s, L, a, b, A, B, a) || (moved_a && HitsPolygon(s, L, pa, a, s.pos[pa], A, a)) ||
                       (moved_b && HitsPolygon(s, L, b, nb, B, s.pos[nb], a));
      L.next[a] = j, L.prev[b] = j;
      s.pos[a] = old_a, s.pos[b] = old_b;
      if (hit) return false;
    }
    return true;
  }

  // Order: error, scaled down for a vertex with a short edge in some pose, so
  // such vertices go first; short edges next to long ones make thin triangles
  // later. Only the error itself decides whether a removal is allowed.
  double Priority(std::size_t j, double error) const {
    const double short_edge = 4 * tolerance_;
    double shortest = kInf;
    for (std::size_t i = 0; i < N; ++i)
      shortest = std::min(
          {shortest, (st[i].pos[j] - st[i].pos[L.prev[j]]).norm(), (st[i].pos[j] - st[i].pos[L.next[j]]).norm()});
    return error * std::clamp(shortest / short_edge, 0.05, 1.0);
  }

  const std::vector<Polygon>& outlines_;
  const CorrespondedBoundary& boundary_;
  const double tolerance_;
  const std::size_t N, M;
  std::vector<PoseState> st;
  std::vector<OutlineEdges> edges;  // per pose
  std::vector<bool> landmark;
  Linked L;
  std::size_t alive = 0;
  double max_error_ = 0;  // the largest error of a removal made
};

}  // namespace

SimplifiedBoundary SimplifyEnclosing(const std::vector<Polygon>& outlines, const CorrespondedBoundary& boundary,
                                     double tolerance, const std::vector<ErrorSource>& poses) {
  // A span that no outward push encloses is split where its outline sticks
  // out, in every pose, and the enclosing starts again (a few rounds: each
  // split halves the spans that failed).
  constexpr int kSplitRounds = 6;
  CorrespondedBoundary refined = boundary;
  for (int round = 0;; ++round) {
    Simplifier simplifier(outlines, refined, tolerance);
    bool enclosed = true;
    for (std::size_t i = 0; i < outlines.size() && enclosed; ++i) {
      const std::vector<std::size_t> failing = simplifier.EncloseOutline(i, round > 0);
      if (failing.empty()) continue;
      // The first failure also splits every span far from its chord, in
      // every pose (a bake that encloses at once keeps its points).
      const bool deviating = round == 0 && SplitDeviating(outlines, tolerance / 4, refined);
      if (round == kSplitRounds || !(SplitSpans(outlines, i, failing, refined) || deviating))
        throw poses[i].Error("cannot build a polygon enclosing the outline");
      enclosed = false;
    }
    if (!enclosed) continue;
    simplifier.RemoveGreedily();
    return simplifier.Result();
  }
}

}  // namespace posemorph::bake::mapping
