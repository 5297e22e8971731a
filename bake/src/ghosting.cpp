// SPDX-License-Identifier: MIT
#include "posemorph/bake/ghosting.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "posemorph/bake/error.h"
#include "posemorph/bake/pose_space_samples.h"

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

Ghosting MeasureGhosting(const Rig& rig, const std::vector<DrawingPixels>& drawings, const std::string& file) {
  const std::uint32_t N = rig.pose_count(), T = rig.triangle_count(), V = rig.vertex_count();
  if (rig.uvs(0).size == 0 || drawings.size() != N)
    throw BakeError(file, "the ghosting measure needs a rig baked from drawings and every pose's drawing");
  const std::uint32_t* tris = rig.triangles().data;
  Ghosting g;
  std::vector<double> x;
  for (const auto& [a, b] : AdjacentPoses(rig)) {
    GhostingPair pair;
    pair.a = a, pair.b = b;
    pair.name_a = std::string(rig.pose_name(a).data, rig.pose_name(a).size);
    pair.name_b = std::string(rig.pose_name(b).data, rig.pose_name(b).size);
    const auto pts = rig.pose_points();
    pair.at = 0.5 * Eigen::Vector2d(pts[2 * a] + pts[2 * b], pts[2 * a + 1] + pts[2 * b + 1]);
    if (!EvaluateFrame(rig, pair.at, x)) throw BakeError(file, "the rig does not evaluate at an in-between");
    // Pixels of the frame: x right, y down (rig units are drawing pixels, y up).
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (std::uint32_t v = 0; v < V; ++v)
      x0 = std::min(x0, x[2 * v]), x1 = std::max(x1, x[2 * v]), y0 = std::min(y0, -x[2 * v + 1]),
      y1 = std::max(y1, -x[2 * v + 1]);
    if (!(std::isfinite(x1 - x0) && std::isfinite(y1 - y0)))
      throw BakeError(file, "the rig does not evaluate to finite positions");
    // Samples `step` rig units apart, at most kGhostingMaxPixels of them.
    const double step = std::max(1.0, std::ceil(std::sqrt((x1 - x0 + 2) * (y1 - y0 + 2) / kGhostingMaxPixels)));
    for (double& c : x) c /= step;
    x0 /= step, x1 /= step, y0 /= step, y1 /= step;
    const long ox = long(std::floor(x0)), oy = long(std::floor(y0));
    const long w = long(std::ceil(x1)) - ox + 1, h = long(std::ceil(y1)) - oy + 1;
    std::vector<unsigned char> covered(std::size_t(w) * std::size_t(h), 0);
    const auto ua = rig.uvs(a), ub = rig.uvs(b);
    double sum = 0;
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
          double ca[4], cb[4];
          SampleDrawing(drawings[a], l0 * ua[2 * tri[0]] + l1 * ua[2 * tri[1]] + l2 * ua[2 * tri[2]],
                        l0 * ua[2 * tri[0] + 1] + l1 * ua[2 * tri[1] + 1] + l2 * ua[2 * tri[2] + 1], ca);
          SampleDrawing(drawings[b], l0 * ub[2 * tri[0]] + l1 * ub[2 * tri[1]] + l2 * ub[2 * tri[2]],
                        l0 * ub[2 * tri[0] + 1] + l1 * ub[2 * tri[1] + 1] + l2 * ub[2 * tri[2] + 1], cb);
          if (!(ca[3] >= 0.5 || cb[3] >= 0.5)) continue;
          ++pair.pixels;
          for (int ch = 0; ch < 4; ++ch) sum += std::abs(ca[ch] - cb[ch]);
        }
    }
    pair.difference = pair.pixels ? 255.0 * sum / (4.0 * double(pair.pixels)) : 0.0;
    g.mean += pair.difference;
    g.pairs.push_back(pair);
  }
  if (!g.pairs.empty()) g.mean /= double(g.pairs.size());
  return g;
}

std::vector<unsigned char> ReduceDrawing(std::vector<unsigned char> rgba, std::uint32_t* width, std::uint32_t* height,
                                         std::uint32_t max_side) {
  while (std::max(*width, *height) > max_side) {
    const std::uint32_t w = *width, h = *height, hw = (w + 1) / 2, hh = (h + 1) / 2;
    std::vector<double> acc(std::size_t(hw) * hh * 4, 0.0);
    for (std::uint32_t y = 0; y < h; ++y)
      for (std::uint32_t x = 0; x < w; ++x) {
        const unsigned char* p = &rgba[(std::size_t(y) * w + x) * 4];
        double* q = &acc[(std::size_t(y / 2) * hw + x / 2) * 4];
        for (int ch = 0; ch < 3; ++ch) q[ch] += 0.25 * p[3] * p[ch] / 255.0;
        q[3] += 0.25 * p[3];
      }
    std::vector<unsigned char> out(acc.size());
    for (std::size_t i = 0; i < std::size_t(hw) * hh; ++i) {
      const double a = acc[i * 4 + 3];
      for (int ch = 0; ch < 3; ++ch)
        out[i * 4 + std::size_t(ch)] =
            a > 0 ? static_cast<unsigned char>(std::lround(std::min(255.0, acc[i * 4 + std::size_t(ch)] * 255.0 / a)))
                  : 0;
      out[i * 4 + 3] = static_cast<unsigned char>(std::lround(std::min(255.0, a)));
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

}  // namespace posemorph::bake
