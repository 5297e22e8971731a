// SPDX-License-Identifier: MIT
// Splitting spans of the corresponded boundary, for the enclosing
// simplification when a span cannot be enclosed (span_splitting.h).
#include "span_splitting.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "outline_arc.h"
#include "posemorph/bake/mapping/limits.h"

namespace posemorph::bake::mapping {

// Splits the span of every edge in `edges` (indices among the M points) of
// pose i in two: a new corresponding N-tuple at the outline vertex farthest
// outside the edge in pose i, and at the same share of the span's arc length
// in every other pose (the correspondence between the two points is linear
// in arc length, so it keeps its order and every pose its own outline).
// Returns false when no span could be split.
bool SplitSpans(const std::vector<Polygon>& outlines, std::size_t i, std::vector<std::size_t> edges,
                CorrespondedBoundary& b) {
  const std::size_t N = outlines.size(), M = b.points[0].size();
  std::vector<double> perimeter(N);
  std::vector<std::vector<double>> cumulative(N);
  for (std::size_t j = 0; j < N; ++j)
    cumulative[j] = CumulativeArcLength(outlines[j]), perimeter[j] = cumulative[j].back();
  auto span_length = [&](std::size_t j, std::size_t e) {
    double len = std::fmod(b.at[j][(e + 1) % M] - b.at[j][e], perimeter[j]);
    return len <= 0 ? len + perimeter[j] : len;
  };
  std::sort(edges.begin(), edges.end(), std::greater<std::size_t>());  // insert from the back: indices stay valid
  bool split = false;
  for (std::size_t e : edges) {
    if (b.points[0].size() >= kMaxMatchedSamples) break;  // the matching's own bound on points (limits.h)
    const std::size_t f = (e + 1) % M;
    const double len = span_length(i, e);
    if (!(len > 0)) continue;
    // The share t of the span where pose i's outline lies farthest outside its chord.
    const OutlineArc probe(outlines[i]);
    double t = 0.5, worst = -std::numeric_limits<double>::infinity();
    const double s0 = b.at[i][e];
    probe.ForSpan(s0, b.at[i][f], [&](std::size_t k) {
      const double d = Outside(b.points[i][e], b.points[i][f], outlines[i][k]);
      double along = std::fmod(cumulative[i][k] - s0, perimeter[i]);
      if (along < 0) along += perimeter[i];
      if (d > worst && along > 0 && along < len) worst = d, t = along / len;
    });
    t = std::clamp(t, 0.05, 0.95);  // never onto a neighbour
    for (std::size_t j = 0; j < N; ++j) {
      const double at = b.at[j][e] + t * span_length(j, e);
      b.at[j].insert(b.at[j].begin() + std::ptrdiff_t(e + 1), at);
      b.points[j].insert(b.points[j].begin() + std::ptrdiff_t(e + 1), PointAtArcLength(outlines[j], at));
    }
    for (std::size_t& k : b.landmarks)
      if (k > e) ++k;
    split = true;
  }
  return split;
}

// Splits, in every pose, each span whose outline stands farther than
// `deviation` outside or inside its chord, until none does (or a few rounds
// went by): with every span close to its chord the outward pushes stay
// small, where a far push past one tip made the next edge cross the outline
// on the other side of a narrow gap. Returns whether anything was split.
bool SplitDeviating(const std::vector<Polygon>& outlines, double deviation, CorrespondedBoundary& b) {
  bool any = false;
  for (int pass = 0; pass < 4; ++pass) {
    bool split = false;
    for (std::size_t i = 0; i < outlines.size(); ++i) {
      const std::size_t M = b.points[0].size();
      const OutlineArc probe(outlines[i]);
      const std::vector<double>& at = b.at[i];
      std::vector<std::size_t> far;
      for (std::size_t e = 0; e < M; ++e) {
        const std::size_t f = (e + 1) % M;
        double worst = 0;
        probe.ForSpan(at[e], at[f], [&](std::size_t k) {
          worst = std::max(worst, std::abs(Outside(b.points[i][e], b.points[i][f], outlines[i][k])));
        });
        if (worst > deviation) far.push_back(e);
      }
      if (!far.empty() && SplitSpans(outlines, i, far, b)) split = true;
    }
    if (!split) break;
    any = true;
  }
  return any;
}

}  // namespace posemorph::bake::mapping
