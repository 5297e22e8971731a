// SPDX-License-Identifier: MIT
// Interior regions found and matched between poses (interior_regions.h).
#include "posemorph/bake/mapping/interior_regions.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace posemorph::bake::mapping {
namespace {

using Vec2 = Eigen::Vector2d;

// At most this many candidate regions (the largest) have their holes
// filled: the work stays a small multiple of the drawing's pixels.
constexpr std::size_t kMaxCandidates = 64;

struct Candidate {
  std::vector<std::size_t> pixels;
  long x0, y0, x1, y1;  // bounding box, inclusive
  double colour[4] = {};
};

}  // namespace

double OpaqueArea(const AlignmentImage& image) {
  double area = 0;
  for (std::size_t i = 3; i < image.rgba.size(); i += 4) area += image.rgba[i] >= 0.5f ? 1 : 0;
  return area;
}

std::vector<InteriorRegion> FindInteriorRegions(const AlignmentImage& image, const RegionParameters& parameters) {
  const long W = image.width, H = image.height;
  const std::size_t n = std::size_t(W) * std::size_t(H);
  const float* c = image.rgba.data();
  const double shape = OpaqueArea(image);
  const double min_area = parameters.min_share * shape, max_area = parameters.max_share * shape;
  std::vector<InteriorRegion> out;
  if (n == 0 || shape <= 0) return out;
  auto opaque = [&](std::size_t i) { return c[i * 4 + 3] >= 0.5f; };
  // Regions grown from the first unlabelled opaque pixel in scan order.
  std::vector<char> labelled(n, 0);
  std::vector<Candidate> candidates;
  std::vector<std::size_t> stack;
  for (std::size_t seed = 0; seed < n; ++seed) {
    if (labelled[seed] || !opaque(seed)) continue;
    Candidate r;
    r.x0 = r.x1 = long(seed % std::size_t(W)), r.y0 = r.y1 = long(seed / std::size_t(W));
    const float* s = c + seed * 4;
    bool touches = false;
    std::size_t border = 0, sharp = 0;  // neighbours outside the region, and those clearly unlike it
    labelled[seed] = 1;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const std::size_t i = stack.back();
      stack.pop_back();
      r.pixels.push_back(i);
      const long x = long(i % std::size_t(W)), y = long(i / std::size_t(W));
      r.x0 = std::min(r.x0, x), r.x1 = std::max(r.x1, x), r.y0 = std::min(r.y0, y), r.y1 = std::max(r.y1, y);
      const long nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
      for (int k = 0; k < 4; ++k) {
        if (nx[k] < 0 || ny[k] < 0 || nx[k] >= W || ny[k] >= H) {
          touches = true;
          continue;
        }
        const std::size_t j = std::size_t(ny[k]) * std::size_t(W) + std::size_t(nx[k]);
        if (!opaque(j)) {
          touches = true;
          continue;
        }
        double differs = 0;
        for (int ch = 0; ch < 4; ++ch)
          differs = std::max(differs, double(std::abs(c[j * 4 + std::size_t(ch)] - s[ch])));
        if (differs > parameters.colour_tolerance) {
          // A neighbour outside: the edge is sharp when it differs clearly.
          ++border;
          sharp += differs > 2 * parameters.colour_tolerance ? 1 : 0;
          continue;
        }
        if (labelled[j]) continue;
        labelled[j] = 1;
        stack.push_back(j);
      }
    }
    const double area = double(r.pixels.size());
    // A region's own pixels are at least a quarter of what it covers with
    // its holes (a ring round an eye is thin); the box bounds the fill.
    const double box = double(r.x1 - r.x0 + 1) * double(r.y1 - r.y0 + 1);
    // A drawn patch has a sharp edge for most of its length; a band of a
    // smooth gradient does not.
    if (touches || area > max_area || 4 * area < min_area || box > 2 * max_area || 2 * sharp < border) continue;
    for (std::size_t i : r.pixels)
      for (int ch = 0; ch < 4; ++ch) r.colour[ch] += c[i * 4 + std::size_t(ch)] / area;
    candidates.push_back(std::move(r));
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.pixels.size() > b.pixels.size(); });
  if (candidates.size() > kMaxCandidates) candidates.resize(kMaxCandidates);
  // Each candidate's holes: the pixels of its box that the box's border
  // cannot reach without crossing it.
  std::vector<char> in_hole(n, 0), mine(n, 0), reached;
  std::vector<Vec2> centre(candidates.size());
  std::vector<double> filled(candidates.size(), 0.0);
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const Candidate& r = candidates[k];
    for (std::size_t i : r.pixels) mine[i] = 1;
    const long bw = r.x1 - r.x0 + 3, bh = r.y1 - r.y0 + 3;  // the box, one pixel wider each side
    reached.assign(std::size_t(bw) * std::size_t(bh), 0);
    auto inside = [&](long x, long y) {  // box coordinates -> is it a pixel of the region
      const long ix = x + r.x0 - 1, iy = y + r.y0 - 1;
      if (ix < 0 || iy < 0 || ix >= W || iy >= H) return false;
      return mine[std::size_t(iy) * std::size_t(W) + std::size_t(ix)] != 0;
    };
    std::vector<std::size_t> queue(1, 0);
    reached[0] = 1;
    while (!queue.empty()) {
      const std::size_t b = queue.back();
      queue.pop_back();
      const long x = long(b % std::size_t(bw)), y = long(b / std::size_t(bw));
      const long nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
      for (int q = 0; q < 4; ++q) {
        if (nx[q] < 0 || ny[q] < 0 || nx[q] >= bw || ny[q] >= bh) continue;
        const std::size_t j = std::size_t(ny[q]) * std::size_t(bw) + std::size_t(nx[q]);
        if (reached[j] || inside(nx[q], ny[q])) continue;
        reached[j] = 1;
        queue.push_back(j);
      }
    }
    Vec2 sum = Vec2::Zero();
    for (long y = 1; y + 1 < bh; ++y)
      for (long x = 1; x + 1 < bw; ++x) {
        const std::size_t b = std::size_t(y) * std::size_t(bw) + std::size_t(x);
        if (reached[b]) continue;  // outside the region and its holes
        const long ix = x + r.x0 - 1, iy = y + r.y0 - 1;
        const std::size_t i = std::size_t(iy) * std::size_t(W) + std::size_t(ix);
        if (!mine[i]) in_hole[i] = 1;
        filled[k] += 1;
        sum += Vec2(double(ix) + 0.5, double(iy) + 0.5);
      }
    centre[k] = sum / filled[k];
    for (std::size_t i : r.pixels) mine[i] = 0;
  }
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const Candidate& r = candidates[k];
    if (in_hole[r.pixels.front()] || filled[k] < min_area || filled[k] > max_area) continue;
    InteriorRegion region;
    region.centre = centre[k];
    region.area = filled[k];
    std::copy(r.colour, r.colour + 4, region.colour);
    out.push_back(region);
  }
  return out;
}

std::vector<RegionMatch> MatchInteriorRegions(const std::vector<InteriorRegion>& reference,
                                              const std::vector<Vec2>& predicted,
                                              const std::vector<InteriorRegion>& regions, double shape_area,
                                              const RegionParameters& parameters) {
  const std::size_t R = reference.size(), K = regions.size();
  std::vector<char> used_reference(R, 0), used_region(K, 0);
  auto compatible = [&](std::size_t i, std::size_t j) {
    if (used_reference[i] || used_region[j] || !predicted[i].allFinite()) return false;
    for (int ch = 0; ch < 4; ++ch)
      if (std::abs(reference[i].colour[ch] - regions[j].colour[ch]) > parameters.match_colour) return false;
    const double a = reference[i].area, b = regions[j].area;
    return std::max(a, b) <= parameters.area_ratio * std::min(a, b);
  };
  const double radius = parameters.match_radius_share * std::sqrt(std::max(shape_area, 0.0));
  // The pairs a shift makes: compatible ones within the radius, nearest
  // first, each region once.
  struct Pair {
    double distance;
    std::size_t i, j;
  };
  auto pairs_for = [&](const Vec2& shift) {
    std::vector<Pair> all;
    for (std::size_t i = 0; i < R; ++i)
      for (std::size_t j = 0; j < K; ++j) {
        if (!compatible(i, j)) continue;
        const double d = (regions[j].centre - predicted[i] - shift).norm();
        if (d <= radius) all.push_back({d, i, j});
      }
    std::stable_sort(all.begin(), all.end(), [](const Pair& a, const Pair& b) { return a.distance < b.distance; });
    std::vector<char> used_i(R, 0), used_j(K, 0);
    std::vector<Pair> kept;
    for (const Pair& p : all)
      if (!used_i[p.i] && !used_j[p.j]) used_i[p.i] = used_j[p.j] = 1, kept.push_back(p);
    return kept;
  };
  // Groups, one after another: each time the shift that pairs the most
  // area among the regions not yet paired (then the shortest shift).
  std::vector<Pair> all_pairs;
  for (;;) {
    std::vector<Vec2> shifts(1, Vec2::Zero());
    for (std::size_t i = 0; i < R; ++i)
      for (std::size_t j = 0; j < K; ++j)
        if (compatible(i, j)) shifts.push_back(regions[j].centre - predicted[i]);
    std::vector<Pair> best;
    double best_area = 0, best_shift = std::numeric_limits<double>::infinity();
    for (const Vec2& s : shifts) {
      std::vector<Pair> pairs = pairs_for(s);
      if (pairs.empty()) continue;
      Vec2 mean = Vec2::Zero();
      for (const Pair& p : pairs) mean += regions[p.j].centre - predicted[p.i];
      mean /= double(pairs.size());
      std::vector<Pair> refined = pairs_for(mean);
      if (refined.size() >= pairs.size()) pairs = std::move(refined);
      double area = 0;
      for (const Pair& p : pairs) area += std::min(reference[p.i].area, regions[p.j].area);
      const double length = mean.norm();
      // A lone region that moved further than the radius counts only when
      // nothing else could be it: alone, its shift proves nothing.
      if (pairs.size() == 1 && length > radius) {
        int others = 0;
        for (std::size_t j = 0; j < K; ++j) others += compatible(pairs[0].i, j) ? 1 : 0;
        for (std::size_t i = 0; i < R; ++i) others += compatible(i, pairs[0].j) ? 1 : 0;
        if (others > 2) continue;
      }
      if (area > best_area * (1 + 1e-12) || (area >= best_area * (1 - 1e-12) && length < best_shift))
        best = pairs, best_area = area, best_shift = length;
    }
    if (best.empty()) break;
    for (const Pair& p : best) used_reference[p.i] = used_region[p.j] = 1, all_pairs.push_back(p);
  }
  std::vector<Pair>& best = all_pairs;
  std::vector<RegionMatch> out;
  std::sort(best.begin(), best.end(), [](const Pair& a, const Pair& b) { return a.i < b.i; });
  for (const Pair& p : best) out.push_back({p.i, reference[p.i].centre, regions[p.j].centre, reference[p.i].area});
  return out;
}

}  // namespace posemorph::bake::mapping
