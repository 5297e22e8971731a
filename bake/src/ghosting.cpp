// SPDX-License-Identifier: MIT
#include "posemorph/bake/ghosting.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "posemorph/bake/error.h"
#include "posemorph/bake/pose_space_samples.h"
#include "posemorph/jobs.h"

namespace posemorph::bake {

// Premultiplied RGBA (of 1) of a drawing at uv, bilinear, transparent
// outside it (the viewer's clamp-to-border sampler).
void SampleDrawing(const DrawingPixels& d, double u, double v, double out[4]) {
  const double x = u * d.width - 0.5, y = v * d.height - 0.5;
  out[0] = out[1] = out[2] = out[3] = 0;
  const double fx = std::floor(x), fy = std::floor(y), ax = x - fx, ay = y - fy;
  if (!(fx >= -1 && fy >= -1 && fx < double(d.width) && fy < double(d.height))) return;
  const long x0 = long(fx), y0 = long(fy);
  auto texel = [&](long tx, long ty, double w) {
    if (tx < 0 || ty < 0 || tx >= long(d.width) || ty >= long(d.height) || w == 0) return;
    const unsigned char* p = d.rgba + (std::size_t(ty) * d.width + std::size_t(tx)) * 4;
    const double a = p[3] / 255.0;
    for (int ch = 0; ch < 3; ++ch) out[ch] += w * a * p[ch] / 255.0;
    out[3] += w * a;
  };
  texel(x0, y0, (1 - ax) * (1 - ay));
  texel(x0 + 1, y0, ax * (1 - ay));
  texel(x0, y0 + 1, (1 - ax) * ay);
  texel(x0 + 1, y0 + 1, ax * ay);
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> AdjacentPoses(const Rig& rig) {
  const std::uint32_t N = rig.pose_count();
  const auto pts = rig.pose_points();
  auto p = [&](std::uint32_t i) { return Eigen::Vector2d(pts[2 * i], pts[2 * i + 1]); };
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for (std::uint32_t a = 0; a < N; ++a)
    for (std::uint32_t b = a + 1; b < N; ++b) {
      const Eigen::Vector2d c = 0.5 * (p(a) + p(b));
      const double r2 = 0.25 * (p(a) - p(b)).squaredNorm();
      bool empty = true;
      for (std::uint32_t k = 0; k < N && empty; ++k)
        if (k != a && k != b && (p(k) - c).squaredNorm() < r2 * (1 - 1e-12)) empty = false;
      if (empty) out.emplace_back(a, b);
    }
  return out;
}

namespace {

// The frame at `at` with the rig's default settings, and its texture weights.
bool FrameAndTextureWeights(const Rig& rig, const Eigen::Vector2d& at, std::vector<double>& x,
                            std::vector<double>& texture) {
  std::vector<double> limited;
  if (!EvaluateFrame(rig, at, x, limited)) return false;
  texture.assign(limited.size(), 0.0);
  TextureWeights(MakeSpan(limited), rig.default_sigma(), MakeSpan(texture));
  return true;
}

// The frame `x` rasterised at one sample per `step` rig units (coarser than
// one per rig unit only so that it takes at most `most` samples), each pixel
// drawn with every pose in `poses` at its uvs: the mean over the pixels
// where any is at least half opaque of sum_(i<j) w_i w_j |c_i - c_j| /
// sum_(i<j) w_i w_j (of 255, over RGBA): for two poses, their mean absolute
// difference whatever their weights.
double Difference(const Rig& rig, std::vector<double> x, const std::vector<std::uint32_t>& poses,
                  const std::vector<double>& weights, const std::vector<DrawingPixels>& drawings, double most,
                  std::uint64_t* pixels, const std::string& file) {
  const std::uint32_t T = rig.triangle_count(), V = rig.vertex_count();
  const std::uint32_t* tris = rig.triangles().data;
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (std::uint32_t v = 0; v < V; ++v)
    x0 = std::min(x0, x[2 * v]), x1 = std::max(x1, x[2 * v]), y0 = std::min(y0, -x[2 * v + 1]),
    y1 = std::max(y1, -x[2 * v + 1]);
  if (!(std::isfinite(x1 - x0) && std::isfinite(y1 - y0)))
    throw BakeError(file, "the rig does not evaluate to finite positions");
  const double step = std::max(1.0, std::ceil(std::sqrt((x1 - x0 + 2) * (y1 - y0 + 2) / most)));
  for (double& c : x) c /= step;
  x0 /= step, x1 /= step, y0 /= step, y1 /= step;
  const long ox = long(std::floor(x0)), oy = long(std::floor(y0));
  const long w = long(std::ceil(x1)) - ox + 1, h = long(std::ceil(y1)) - oy + 1;
  std::vector<unsigned char> covered(std::size_t(w) * std::size_t(h), 0);
  const std::size_t K = poses.size();
  double norm = 0;
  for (std::size_t i = 0; i < K; ++i)
    for (std::size_t j = i + 1; j < K; ++j) norm += weights[i] * weights[j];
  std::vector<std::array<double, 4>> colour(K);
  double sum = 0;
  *pixels = 0;
  for (std::uint32_t t = 0; t < T; ++t) {
    const std::uint32_t* tri = tris + 3 * t;
    const double px[3] = {x[2 * tri[0]] - ox, x[2 * tri[1]] - ox, x[2 * tri[2]] - ox};
    const double py[3] = {-x[2 * tri[0] + 1] - oy, -x[2 * tri[1] + 1] - oy, -x[2 * tri[2] + 1] - oy};
    const double area = (px[1] - px[0]) * (py[2] - py[0]) - (py[1] - py[0]) * (px[2] - px[0]);
    if (!(std::abs(area) > 1e-12)) continue;
    const long cx0 = std::max(0L, long(std::floor(std::min({px[0], px[1], px[2]}))));
    const long cx1 = std::min(w - 1, long(std::ceil(std::max({px[0], px[1], px[2]}))));
    const long cy0 = std::max(0L, long(std::floor(std::min({py[0], py[1], py[2]}))));
    const long cy1 = std::min(h - 1, long(std::ceil(std::max({py[0], py[1], py[2]}))));
    for (long cy = cy0; cy <= cy1; ++cy)
      for (long cx = cx0; cx <= cx1; ++cx) {
        const std::size_t at = std::size_t(cy) * std::size_t(w) + std::size_t(cx);
        if (covered[at]) continue;
        const double qx = cx + 0.5, qy = cy + 0.5;
        const double l1 = ((qx - px[0]) * (py[2] - py[0]) - (qy - py[0]) * (px[2] - px[0])) / area;
        const double l2 = ((px[1] - px[0]) * (qy - py[0]) - (py[1] - py[0]) * (qx - px[0])) / area;
        const double l0 = 1 - l1 - l2;
        if (l0 < -1e-9 || l1 < -1e-9 || l2 < -1e-9) continue;
        covered[at] = 1;
        bool opaque = false;
        for (std::size_t k = 0; k < K; ++k) {
          const auto uv = rig.uvs(poses[k]);
          SampleDrawing(drawings[poses[k]], l0 * uv[2 * tri[0]] + l1 * uv[2 * tri[1]] + l2 * uv[2 * tri[2]],
                        l0 * uv[2 * tri[0] + 1] + l1 * uv[2 * tri[1] + 1] + l2 * uv[2 * tri[2] + 1], colour[k].data());
          opaque = opaque || colour[k][3] >= 0.5;
        }
        if (!opaque) continue;
        ++*pixels;
        double d = 0;
        for (std::size_t i = 0; i < K; ++i)
          for (std::size_t j = i + 1; j < K; ++j)
            for (int ch = 0; ch < 4; ++ch)
              d += weights[i] * weights[j] * std::abs(colour[i][std::size_t(ch)] - colour[j][std::size_t(ch)]);
        sum += d / norm;
      }
  }
  return *pixels ? 255.0 * sum / (4.0 * double(*pixels)) : 0.0;
}

}  // namespace

Ghosting MeasureGhosting(const Rig& rig, const std::vector<DrawingPixels>& drawings, const std::string& file) {
  const std::uint32_t N = rig.pose_count();
  if (rig.uvs(0).size == 0 || drawings.size() != N)
    throw BakeError(file, "the ghosting measure needs a rig baked from drawings and every pose's drawing");
  Ghosting g;
  std::vector<double> x, texture;
  const auto pts = rig.pose_points();
  for (const auto& [a, b] : AdjacentPoses(rig)) {
    GhostingPair pair;
    pair.a = a, pair.b = b;
    pair.name_a = std::string(rig.pose_name(a).data, rig.pose_name(a).size);
    pair.name_b = std::string(rig.pose_name(b).data, rig.pose_name(b).size);
    pair.at = 0.5 * Eigen::Vector2d(pts[2 * a] + pts[2 * b], pts[2 * a + 1] + pts[2 * b + 1]);
    if (!EvaluateFrame(rig, pair.at, x)) throw BakeError(file, "the rig does not evaluate at an in-between");
    pair.difference = Difference(rig, x, {a, b}, {0.5, 0.5}, drawings, kGhostingMaxPixels, &pair.pixels, file);
    g.mean += pair.difference;
    g.pairs.push_back(pair);
  }
  if (!g.pairs.empty()) g.mean /= double(g.pairs.size());
  // Over the pose hull: where two drawings or more cross-fade.
  PoseSpaceSampling sampling;
  sampling.grid = kGhostingHullGrid, sampling.per_edge = kGhostingHullEdge, sampling.per_pair = 0,
  sampling.per_path = 0;
  const std::vector<PoseSpaceSample> samples = SamplePoseSpace(rig, sampling);
  // The hull's in-betweens share kGhostingMaxHullPixels samples per drawing.
  const double most = std::max(16384.0, kGhostingMaxHullPixels / double(std::max<std::size_t>(1, samples.size())));
  for (const PoseSpaceSample& s : samples) {
    if (!s.in_hull) continue;
    if (!FrameAndTextureWeights(rig, s.at, x, texture))
      throw BakeError(file, "the rig does not evaluate at an in-between");
    GhostingSample sample;
    sample.at = s.at;
    std::vector<std::uint32_t> poses;
    std::vector<double> weights;
    for (std::uint32_t i = 0; i < N; ++i)
      if (texture[i] >= kGhostingMinTextureWeight) poses.push_back(i), weights.push_back(texture[i]);
    if (poses.size() < 2) continue;
    sample.drawings = std::uint32_t(poses.size());
    sample.difference = Difference(rig, x, poses, weights, drawings, most, &sample.pixels, file);
    g.hull_mean += sample.difference;
    if (g.hull.empty() || sample.difference > g.hull[g.hull_worst].difference) g.hull_worst = g.hull.size();
    g.hull.push_back(sample);
  }
  if (!g.hull.empty()) g.hull_mean /= double(g.hull.size());
  return g;
}

std::vector<unsigned char> ReduceDrawing(std::vector<unsigned char> rgba, std::uint32_t* width, std::uint32_t* height,
                                         std::uint32_t max_side) {
  while (std::max(*width, *height) > max_side) {
    const std::uint32_t w = *width, h = *height, hw = (w + 1) / 2, hh = (h + 1) / 2;
    std::vector<unsigned char> out(std::size_t(hw) * hh * 4, 0);
    // One output row at a time, from the two input rows it covers: the sums
    // of a 4096-pixel drawing's first halving took 128 MiB as one array.
    std::vector<double> acc(std::size_t(hw) * 4);
    for (std::uint32_t oy = 0; oy < hh; ++oy) {
      std::fill(acc.begin(), acc.end(), 0.0);
      // A transparent pixel adds exactly +0 to each sum: skipped (the same
      // bits, and most of a character's page is transparent).
      for (std::uint32_t y = 2 * oy; y < std::min(h, 2 * oy + 2); ++y)
        for (std::uint32_t x = 0; x < w; ++x) {
          const unsigned char* p = &rgba[(std::size_t(y) * w + x) * 4];
          if (p[3] == 0) continue;
          double* q = &acc[std::size_t(x / 2) * 4];
          for (int ch = 0; ch < 3; ++ch) q[ch] += 0.25 * p[3] * p[ch] / 255.0;
          q[3] += 0.25 * p[3];
        }
      unsigned char* row = &out[std::size_t(oy) * hw * 4];
      for (std::size_t i = 0; i < hw; ++i) {
        const double a = acc[i * 4 + 3];
        if (a == 0) continue;  // out is zeroed: what lround(0) gives
        for (int ch = 0; ch < 3; ++ch)
          row[i * 4 + std::size_t(ch)] =
              static_cast<unsigned char>(std::lround(std::min(255.0, acc[i * 4 + std::size_t(ch)] * 255.0 / a)));
        row[i * 4 + 3] = static_cast<unsigned char>(std::lround(std::min(255.0, a)));
      }
    }
    rgba = std::move(out);
    *width = hw, *height = hh;
  }
  return rgba;
}

std::string DescribeGhosting(const Ghosting& ghosting) {
  std::ostringstream s;
  s.precision(3);
  for (std::size_t k = 0; k < ghosting.pairs.size(); ++k)
    s << (k ? ", " : "") << ghosting.pairs[k].name_a << "-" << ghosting.pairs[k].name_b << " "
      << ghosting.pairs[k].difference;
  s << "; mean " << ghosting.mean << " (of 255)";
  return s.str();
}

std::string DescribeHullGhosting(const Ghosting& ghosting) {
  std::ostringstream s;
  s.precision(3);
  if (ghosting.hull.empty()) return "no point of the pose hull cross-fades two drawings";
  const GhostingSample& w = ghosting.hull[ghosting.hull_worst];
  s << "mean " << ghosting.hull_mean << " over " << ghosting.hull.size() << " points, worst " << w.difference << " at ("
    << w.at.x() << ", " << w.at.y() << ") with " << w.drawings << " drawings (of 255)";
  return s.str();
}

}  // namespace posemorph::bake
