// SPDX-License-Identifier: MIT
#include "outline_picture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace posemorph::bake {
namespace {

using Vec = Eigen::Vector2d;

struct Colour {
  unsigned char r, g, b;
};
constexpr Colour kOutline{0, 190, 230}, kBoundary{220, 0, 200}, kMesh{90, 90, 90}, kLandmark{225, 30, 30},
    kStart{0, 170, 60}, kPlaced{255, 255, 255}, kInk{20, 20, 20}, kFeature{255, 190, 0};

// Digits 0-9 in a 3 x 5 grid, one row per 3 bits (most significant bit left).
constexpr std::array<std::array<unsigned char, 5>, 10> kDigits{{
    {7, 5, 5, 5, 7},
    {2, 6, 2, 2, 7},
    {7, 1, 7, 4, 7},
    {7, 1, 7, 1, 7},
    {5, 5, 7, 1, 1},
    {7, 4, 7, 1, 7},
    {7, 4, 7, 5, 7},
    {7, 1, 2, 2, 2},
    {7, 5, 7, 5, 7},
    {7, 5, 7, 1, 7},
}};

class Canvas {
 public:
  Canvas(std::uint32_t w, std::uint32_t h, Vec low, double scale) : low_(low), scale_(scale) {
    image_.width = w;
    image_.height = h;
    image_.rgba.resize(std::size_t(w) * h * 4);
    for (std::uint32_t y = 0; y < h; ++y)
      for (std::uint32_t x = 0; x < w; ++x) {
        const unsigned char v = ((x / 8 + y / 8) % 2) ? 236 : 250;  // checkerboard: the drawing's alpha shows
        unsigned char* p = Pixel(x, y);
        p[0] = p[1] = p[2] = v;
        p[3] = 255;
      }
  }
  // Drawing units -> picture pixels.
  Vec At(const Vec& d) const { return (d - low_) * scale_; }
  double scale() const { return scale_; }

  void Blend(long x, long y, Colour c, double a) {
    if (x < 0 || y < 0 || x >= long(image_.width) || y >= long(image_.height) || a <= 0) return;
    unsigned char* p = Pixel(std::uint32_t(x), std::uint32_t(y));
    a = std::min(a, 1.0);
    p[0] = static_cast<unsigned char>(std::lround(p[0] + (c.r - p[0]) * a));
    p[1] = static_cast<unsigned char>(std::lround(p[1] + (c.g - p[1]) * a));
    p[2] = static_cast<unsigned char>(std::lround(p[2] + (c.b - p[2]) * a));
  }

  // Pixel coverage of a shape given its signed distance function (negative inside), over a box.
  template <class Distance>
  void Fill(const Vec& lo, const Vec& hi, Colour c, double alpha, Distance distance) {
    const long x0 = long(std::floor(lo.x())) - 1, x1 = long(std::ceil(hi.x())) + 1;
    const long y0 = long(std::floor(lo.y())) - 1, y1 = long(std::ceil(hi.y())) + 1;
    for (long y = std::max(0L, y0); y <= std::min(long(image_.height) - 1, y1); ++y)
      for (long x = std::max(0L, x0); x <= std::min(long(image_.width) - 1, x1); ++x) {
        const double d = distance(Vec(double(x) + 0.5, double(y) + 0.5));
        Blend(x, y, c, alpha * std::clamp(0.5 - d, 0.0, 1.0));
      }
  }

  void Disc(const Vec& centre, double r, Colour c, double alpha = 1) {
    Fill(centre - Vec(r, r), centre + Vec(r, r), c, alpha, [&](const Vec& p) { return (p - centre).norm() - r; });
  }
  void Ring(const Vec& centre, double r, double width, Colour c, double alpha = 1) {
    const double o = r + width;
    Fill(centre - Vec(o, o), centre + Vec(o, o), c, alpha,
         [&](const Vec& p) { return std::abs((p - centre).norm() - r) - width / 2; });
  }
  void Line(const Vec& a, const Vec& b, double width, Colour c, double alpha = 1) {
    const Vec ab = b - a;
    const double len2 = ab.squaredNorm();
    Fill(a.cwiseMin(b) - Vec(width, width), a.cwiseMax(b) + Vec(width, width), c, alpha, [&](const Vec& p) {
      const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
      return (p - (a + t * ab)).norm() - width / 2;
    });
  }
  void Loop(const std::vector<Vec>& points, double width, Colour c) {
    for (std::size_t i = 0; i < points.size(); ++i) Line(At(points[i]), At(points[(i + 1) % points.size()]), width, c);
  }
  // A number with its top-left corner at `at`, `cell` pixels per font pixel, on a light box.
  void Number(std::size_t n, const Vec& at, int cell) {
    const std::string text = std::to_string(n);
    const double w = double(text.size()) * 4 * cell + cell, h = 7.0 * cell;
    Fill(at, at + Vec(w, h), kPlaced, 0.85, [&](const Vec& p) {
      return std::max(std::max(at.x() - p.x(), p.x() - at.x() - w), std::max(at.y() - p.y(), p.y() - at.y() - h));
    });
    for (std::size_t i = 0; i < text.size(); ++i) {
      const auto& glyph = kDigits[std::size_t(text[i] - '0')];
      for (int row = 0; row < 5; ++row)
        for (int col = 0; col < 3; ++col)
          if (glyph[std::size_t(row)] & (4 >> col))
            for (int dy = 0; dy < cell; ++dy)
              for (int dx = 0; dx < cell; ++dx)
                Blend(long(at.x()) + long(i) * 4 * cell + cell + col * cell + dx, long(at.y()) + cell + row * cell + dy,
                      kInk, 1);
    }
  }
  // The drawing, nearest filtering, alpha over the checkerboard.
  void Drawing(const RgbaImage& d) {
    for (std::uint32_t y = 0; y < image_.height; ++y)
      for (std::uint32_t x = 0; x < image_.width; ++x) {
        const Vec p = low_ + Vec(x + 0.5, y + 0.5) / scale_;
        if (p.x() < 0 || p.y() < 0 || p.x() >= d.width || p.y() >= d.height) continue;
        const unsigned char* s = &d.rgba[(std::size_t(p.y()) * d.width + std::size_t(p.x())) * 4];
        Blend(x, y, Colour{s[0], s[1], s[2]}, s[3] / 255.0);
      }
  }
  RgbaImage& image() { return image_; }

 private:
  unsigned char* Pixel(std::uint32_t x, std::uint32_t y) {
    return &image_.rgba[(std::size_t(y) * image_.width + x) * 4];
  }
  RgbaImage image_;
  Vec low_;
  double scale_;
};

// The picture's extent in drawing units.
Eigen::AlignedBox2d PictureFrame(const DrawnPoseOutline& pose, const RgbaImage& drawing) {
  Eigen::AlignedBox2d box;
  if (drawing.width > 0) return Eigen::AlignedBox2d(Vec(0, 0), Vec(drawing.width, drawing.height));
  for (const Vec& p : pose.traced) box.extend(p);
  for (const Vec& p : pose.landmarks) box.extend(p);
  for (const Vec& p : pose.features) box.extend(p);
  for (const Vec& p : pose.boundary) box.extend(p);
  const Vec grow = Vec::Constant(std::max(box.sizes().maxCoeff() / 10, 1e-9));
  return Eigen::AlignedBox2d(box.min() - grow, box.max() + grow);
}

// An arrow from the start landmark along the traced outline, in the
// landmarks' order: the direction the outline runs from landmark 0 to 1.
void StartArrow(Canvas& c, const DrawnPoseOutline& pose, const Vec& start, double length) {
  const std::vector<Vec>& t = pose.traced;
  if (t.size() < 2) return;
  std::size_t nearest = 0;
  for (std::size_t i = 1; i < t.size(); ++i)
    if ((t[i] - start).squaredNorm() < (t[nearest] - start).squaredNorm()) nearest = i;
  // Walk along the outline until `length` drawing units away.
  std::size_t i = nearest;
  for (std::size_t step = 0; step < t.size() && (t[i] - t[nearest]).norm() < length; ++step) i = (i + 1) % t.size();
  const Vec a = c.At(t[nearest]), b = c.At(t[i]);
  if ((b - a).norm() < 1) return;
  const Vec dir = (b - a).normalized(), side(-dir.y(), dir.x());
  const double head = std::min(12.0, (b - a).norm() / 2);
  c.Line(a, b, 3, kStart);
  c.Line(b, b - head * dir + head * 0.6 * side, 3, kStart);
  c.Line(b, b - head * dir - head * 0.6 * side, 3, kStart);
}

}  // namespace

RgbaImage OutlinePicture(const DrawnPoseOutline& pose, const Triangles& triangles, const RgbaImage& drawing,
                         int* scale_out) {
  const Eigen::AlignedBox2d frame = PictureFrame(pose, drawing);
  const double longer = std::max(frame.sizes().maxCoeff(), 1e-9);
  const int scale = std::clamp(int(640 / longer), 1, 16);
  if (scale_out) *scale_out = scale;
  const Vec size = (frame.sizes() * scale).array().ceil();
  Canvas c(std::uint32_t(std::clamp(size.x(), 1.0, 8192.0)), std::uint32_t(std::clamp(size.y(), 1.0, 8192.0)),
           frame.min(), scale);
  if (drawing.width > 0) c.Drawing(drawing);
  const double unit = std::clamp(scale / 4.0, 1.0, 3.0);  // line widths grow with the scale
  if (!pose.vertices.empty())
    for (const auto& t : triangles)
      for (int e = 0; e < 3; ++e)
        c.Line(c.At(pose.vertices[t[std::size_t(e)]]), c.At(pose.vertices[t[std::size_t(e + 1) % 3]]), 1, kMesh, 0.5);
  c.Loop(pose.traced, unit, kOutline);
  c.Loop(pose.boundary, unit * 1.5, kBoundary);
  for (const Vec& p : pose.boundary) c.Disc(c.At(p), unit * 1.5, kBoundary);
  const double mark = std::max(4.0, unit * 3);
  const int cell = std::clamp(int(unit * 1.5), 2, 4);
  for (std::size_t l = 0; l < pose.landmarks.size(); ++l) {
    const Vec at = c.At(pose.landmarks[l]);
    const Colour colour = l == 0 ? kStart : kLandmark;
    c.Ring(at, pose.landmark_distance * scale, unit, colour, 0.8);
    if (l < pose.placed.size()) c.Disc(c.At(pose.placed[l]), mark * 0.6, kPlaced);
    c.Disc(at, mark, colour);
    c.Number(l, at + Vec(mark + 2, mark + 2), cell);
  }
  for (std::size_t f = 0; f < pose.features.size(); ++f) {  // an amber cross, numbered
    const Vec at = c.At(pose.features[f]);
    c.Line(at - Vec(mark, mark), at + Vec(mark, mark), unit * 1.5, kFeature);
    c.Line(at - Vec(mark, -mark), at + Vec(mark, -mark), unit * 1.5, kFeature);
    c.Number(f, at + Vec(mark + 2, mark + 2), cell);
  }
  if (!pose.landmarks.empty())
    StartArrow(c, pose, pose.landmarks[0], std::max(3 * pose.landmark_distance, 24.0 / scale));
  return std::move(c.image());
}

}  // namespace posemorph::bake
