// SPDX-License-Identifier: MIT
// The drawings as the interior alignment samples them: a pyramid of
// blurred levels with gradients, the reference's pixels inside pose 0's
// mesh, and a pose's colour difference through its mesh
// (interior_alignment.cpp's Gauss-Newton steps use them).
#pragma once
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "posemorph/bake/mapping/interior_alignment.h"

namespace posemorph::bake::mapping::alignment {

using Vec2 = Eigen::Vector2d;

// One pyramid level of a drawing, blurred, with its central-difference
// gradients: what Gauss-Newton samples.
struct Level {
  int width = 0, height = 0;
  std::vector<float> c, gx, gy;  // 4 channels each

  // Bilinear at (x, y) in this level's pixels (centres at i + 0.5), zero
  // outside the image, into out[0..3] (and the gradients when asked).
  void Sample(double x, double y, double out[4], double dx[4] = nullptr, double dy[4] = nullptr) const {
    for (int ch = 0; ch < 4; ++ch) {
      out[ch] = 0;
      if (dx) dx[ch] = dy[ch] = 0;
    }
    const double fx = x - 0.5, fy = y - 0.5;
    if (!(fx > -1 && fy > -1 && fx < width && fy < height)) return;
    const double x0 = std::floor(fx), y0 = std::floor(fy), ax = fx - x0, ay = fy - y0;
    const long ix = long(x0), iy = long(y0);
    const double w[4] = {(1 - ax) * (1 - ay), ax * (1 - ay), (1 - ax) * ay, ax * ay};
    const long px[4] = {ix, ix + 1, ix, ix + 1}, py[4] = {iy, iy, iy + 1, iy + 1};
    for (int k = 0; k < 4; ++k) {
      if (px[k] < 0 || py[k] < 0 || px[k] >= width || py[k] >= height || w[k] == 0) continue;
      const std::size_t at = (std::size_t(py[k]) * std::size_t(width) + std::size_t(px[k])) * 4;
      for (int ch = 0; ch < 4; ++ch) {
        out[ch] += w[k] * c[at + std::size_t(ch)];
        if (dx) dx[ch] += w[k] * gx[at + std::size_t(ch)], dy[ch] += w[k] * gy[at + std::size_t(ch)];
      }
    }
  }
};

// A level from straight-alpha colours (blurred when asked), its gradients computed.
Level MakeLevel(std::vector<float> c, int w, int h, bool blur);
// levels[0] full resolution ... levels[n - 1] the coarsest; blurred when asked.
std::vector<Level> Pyramid(const AlignmentImage& image, int n, bool blur);

// A pixel of the reference inside pose 0's mesh: its triangle, its
// barycentric coordinates there, and the reference colour.
struct Sample {
  std::uint32_t triangle;
  double b[3];
  double colour[4];
};

// p's barycentric coordinates in the triangle (a, b, c) of doubled signed
// area `area`: false when p lies outside it.
bool Barycentric(const Vec2& a, const Vec2& b, const Vec2& c, double area, const Vec2& p, double l[3]);
// Where in pose 0's mesh a point lies: false when in no triangle.
bool Locate(const Triangles& triangles, const Points& mesh, const Vec2& p, std::uint32_t* triangle, double b[3]);
// Every pixel centre of `level` inside a triangle of `mesh` (scaled by
// `scale` into the level's pixels), each once.
std::vector<Sample> Samples(const Level& level, const Triangles& triangles, const Points& mesh, double scale);
// Sample s's point in a pose's mesh x, in level pixels.
Vec2 Where(const Sample& s, const Triangles& triangles, const Points& x, double scale);
// The pose's drawing there less the reference colour, per channel.
void Residual(const Level& level, const Sample& s, const Triangles& triangles, const Points& x, double scale,
              double r[4]);
// Mean absolute difference over the samples and channels, pose k's drawing
// through `mesh` (level pixels = mesh * scale) against the reference.
double MeanDifference(const Level& level, const std::vector<Sample>& samples, const Triangles& triangles,
                      const Points& mesh, double scale);

}  // namespace posemorph::bake::mapping::alignment
