// SPDX-License-Identifier: MIT
// The drawings as the interior alignment samples them (alignment_image.h),
// and the public AlignmentImageFromRgba and AlignmentHalvings.
#include "alignment_image.h"

#include <algorithm>
#include <cmath>

namespace posemorph::bake::mapping {
namespace alignment {

namespace {

// Half the size: each pixel the mean of the 2 x 2 it covers (transparent
// beyond the edge), so a point's coordinates halve exactly.
std::vector<float> Halve(const std::vector<float>& c, int w, int h, int* hw, int* hh) {
  *hw = (w + 1) / 2, *hh = (h + 1) / 2;
  std::vector<float> out(std::size_t(*hw) * std::size_t(*hh) * 4, 0.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int ch = 0; ch < 4; ++ch)
        out[(std::size_t(y / 2) * std::size_t(*hw) + std::size_t(x / 2)) * 4 + std::size_t(ch)] +=
            0.25f * c[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 4 + std::size_t(ch)];
  return out;
}

// The binomial kernel (1 6 15 20 15 6 1) / 64, a Gaussian of about 1.2
// pixels, separable, transparent beyond the edge: exact weights, no libm,
// so every compiler bakes the same bits.
std::vector<float> Blur(const std::vector<float>& c, int w, int h) {
  constexpr int r = 3;
  constexpr float k[2 * r + 1] = {1 / 64.0f, 6 / 64.0f, 15 / 64.0f, 20 / 64.0f, 15 / 64.0f, 6 / 64.0f, 1 / 64.0f};
  std::vector<float> tmp(c.size(), 0.0f), out(c.size(), 0.0f);
  auto at = [w](int x, int y, int ch) {
    return (std::size_t(y) * std::size_t(w) + std::size_t(x)) * 4 + std::size_t(ch);
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int i = -r; i <= r; ++i) {
        if (x + i < 0 || x + i >= w) continue;
        for (int ch = 0; ch < 4; ++ch) tmp[at(x, y, ch)] += k[i + r] * c[at(x + i, y, ch)];
      }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int i = -r; i <= r; ++i) {
        if (y + i < 0 || y + i >= h) continue;
        for (int ch = 0; ch < 4; ++ch) out[at(x, y, ch)] += k[i + r] * tmp[at(x, y + i, ch)];
      }
  return out;
}

}  // namespace

Level MakeLevel(std::vector<float> c, int w, int h, bool blur) {
  Level l;
  l.width = w, l.height = h;
  l.c = blur ? Blur(c, w, h) : std::move(c);
  l.gx.assign(l.c.size(), 0.0f);
  l.gy.assign(l.c.size(), 0.0f);
  auto value = [&](int x, int y, int ch) -> float {
    if (x < 0 || y < 0 || x >= w || y >= h) return 0.0f;
    return l.c[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * 4 + std::size_t(ch)];
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int ch = 0; ch < 4; ++ch) {
        const std::size_t at = (std::size_t(y) * std::size_t(w) + std::size_t(x)) * 4 + std::size_t(ch);
        l.gx[at] = 0.5f * (value(x + 1, y, ch) - value(x - 1, y, ch));
        l.gy[at] = 0.5f * (value(x, y + 1, ch) - value(x, y - 1, ch));
      }
  return l;
}

// levels[0] full resolution ... levels[n - 1] the coarsest; blurred when asked.
std::vector<Level> Pyramid(const AlignmentImage& image, int n, bool blur) {
  std::vector<Level> out;
  std::vector<float> c = image.rgba;
  int w = image.width, h = image.height;
  for (int l = 0; l < n; ++l) {
    out.push_back(MakeLevel(c, w, h, blur));
    int hw = 0, hh = 0;
    c = Halve(c, w, h, &hw, &hh);
    w = hw, h = hh;
  }
  return out;
}

// p's barycentric coordinates in the triangle (a, b, c) of doubled signed
// area `area`: false when p lies outside it.
bool Barycentric(const Vec2& a, const Vec2& b, const Vec2& c, double area, const Vec2& p, double l[3]) {
  l[1] = ((p - a).x() * (c - a).y() - (p - a).y() * (c - a).x()) / area;
  l[2] = ((b - a).x() * (p - a).y() - (b - a).y() * (p - a).x()) / area;
  l[0] = 1 - l[1] - l[2];
  return !(l[0] < -1e-9 || l[1] < -1e-9 || l[2] < -1e-9);
}

// Where in pose 0's mesh a point lies: false when in no triangle.
bool Locate(const Triangles& triangles, const Points& mesh, const Vec2& p, std::uint32_t* triangle, double b[3]) {
  for (std::uint32_t t = 0; t < triangles.size(); ++t) {
    const Vec2 &a = mesh[triangles[t][0]], &u = mesh[triangles[t][1]], &v = mesh[triangles[t][2]];
    const double area = (u - a).x() * (v - a).y() - (u - a).y() * (v - a).x();
    if (!(std::abs(area) > 1e-12) || !Barycentric(a, u, v, area, p, b)) continue;
    *triangle = t;
    return true;
  }
  return false;
}

// Every pixel centre of `level` inside a triangle of `mesh` (scaled by
// `scale` into the level's pixels), each once.
std::vector<Sample> Samples(const Level& level, const Triangles& triangles, const Points& mesh, double scale) {
  std::vector<Sample> out;
  std::vector<unsigned char> taken(std::size_t(level.width) * std::size_t(level.height), 0);
  for (std::uint32_t t = 0; t < triangles.size(); ++t) {
    const Vec2 a = mesh[triangles[t][0]] * scale, b = mesh[triangles[t][1]] * scale, c = mesh[triangles[t][2]] * scale;
    const double area = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    if (!(std::abs(area) > 1e-12)) continue;
    const int x0 = std::max(0, int(std::floor(std::min({a.x(), b.x(), c.x()}))));
    const int x1 = std::min(level.width - 1, int(std::ceil(std::max({a.x(), b.x(), c.x()}))));
    const int y0 = std::max(0, int(std::floor(std::min({a.y(), b.y(), c.y()}))));
    const int y1 = std::min(level.height - 1, int(std::ceil(std::max({a.y(), b.y(), c.y()}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const std::size_t at = std::size_t(y) * std::size_t(level.width) + std::size_t(x);
        if (taken[at]) continue;
        Sample s{t, {}, {}};
        if (!Barycentric(a, b, c, area, Vec2(x + 0.5, y + 0.5), s.b)) continue;
        taken[at] = 1;
        for (int ch = 0; ch < 4; ++ch) s.colour[ch] = level.c[at * 4 + std::size_t(ch)];
        out.push_back(s);
      }
  }
  return out;
}

// Sample s's point in a pose's mesh x, in level pixels.
Vec2 Where(const Sample& s, const Triangles& triangles, const Points& x, double scale) {
  const auto& t = triangles[s.triangle];
  return (s.b[0] * x[t[0]] + s.b[1] * x[t[1]] + s.b[2] * x[t[2]]) * scale;
}

// The pose's drawing there less the reference colour, per channel.
void Residual(const Level& level, const Sample& s, const Triangles& triangles, const Points& x, double scale,
              double r[4]) {
  const Vec2 y = Where(s, triangles, x, scale);
  level.Sample(y.x(), y.y(), r);
  for (int ch = 0; ch < 4; ++ch) r[ch] -= s.colour[ch];
}

// Mean absolute difference over the samples and channels, pose k's drawing
// through `mesh` (level pixels = mesh * scale) against the reference.
double MeanDifference(const Level& level, const std::vector<Sample>& samples, const Triangles& triangles,
                      const Points& mesh, double scale) {
  if (samples.empty()) return 0;
  double sum = 0;
  for (const Sample& s : samples) {
    double r[4];
    Residual(level, s, triangles, mesh, scale, r);
    for (double c : r) sum += std::abs(c);
  }
  return sum / (4.0 * double(samples.size()));
}

}  // namespace alignment

AlignmentImage AlignmentImageFromRgba(const unsigned char* rgba, int width, int height, int halvings) {
  const int f = 1 << std::max(0, halvings);
  AlignmentImage image;
  image.width = (width + f - 1) / f, image.height = (height + f - 1) / f;
  image.rgba.assign(std::size_t(image.width) * std::size_t(image.height) * 4, 0.0f);
  const float share = 1.0f / float(f * f);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const unsigned char* p = rgba + (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4;
      if (p[3] == 0) continue;  // adds exactly +0: the same bits
      float* q = &image.rgba[(std::size_t(y / f) * std::size_t(image.width) + std::size_t(x / f)) * 4];
      const float a = float(p[3]) / 255.0f;
      for (int ch = 0; ch < 3; ++ch) q[ch] += share * a * float(p[ch]) / 255.0f;
      q[3] += share * a;
    }
  return image;
}

int AlignmentHalvings(int width, int height) {
  int h = 0;
  while ((std::max(width, height) >> h) > kAlignmentMaxSide) ++h;
  return h;
}

}  // namespace posemorph::bake::mapping
