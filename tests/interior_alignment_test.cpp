// SPDX-License-Identifier: MIT
// Interior alignment by the drawings (interior_alignment.h): a drawing and a
// copy whose interior pattern is warped by a known smooth map, the outline
// where it was; the alignment finds the map at the mesh's vertices, the
// colour difference drops to near nothing, and no triangle turns over or
// loses more than half of its smallest angle.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "posemorph/bake/mapping/interior_alignment.h"

namespace pm = posemorph::bake::mapping;
using Vec2 = Eigen::Vector2d;

namespace {

constexpr int kSize = 128;
constexpr double kLo = 16, kHi = 112;  // the square shape, pixels

// The known warp: zero on the square's edge, up to `amplitude` pixels inside.
Vec2 Warp(const Vec2& p, double amplitude) {
  const double s = std::sin(M_PI * (p.x() - kLo) / (kHi - kLo)) * std::sin(M_PI * (p.y() - kLo) / (kHi - kLo));
  const double t = std::sin(M_PI * (p.x() - kLo) / (kHi - kLo));
  return p + amplitude * Vec2(0.8 * s, 0.6 * s * t);
}

// The pattern inside the square: smooth colour waves in three directions.
void Pattern(const Vec2& p, float out[4]) {
  out[0] = float(0.5 + 0.4 * std::sin(p.x() / 6.0 + 0.3 * std::sin(p.y() / 9.0)));
  out[1] = float(0.5 + 0.4 * std::sin(p.y() / 7.0 + 1.0));
  out[2] = float(0.5 + 0.4 * std::sin((p.x() + p.y()) / 8.0 + 2.0));
  out[3] = 1.0f;
}

// The drawing: the pattern seen through the warp's inverse (found by fixed
// point iteration), opaque inside the square.
pm::AlignmentImage Drawing(double amplitude) {
  pm::AlignmentImage image;
  image.width = image.height = kSize;
  image.rgba.assign(std::size_t(kSize) * kSize * 4, 0.0f);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const Vec2 q(x + 0.5, y + 0.5);
      if (q.x() < kLo || q.x() > kHi || q.y() < kLo || q.y() > kHi) continue;
      Vec2 p = q;
      for (int it = 0; it < 60; ++it) p = q - (Warp(p, amplitude) - p);
      Pattern(p, &image.rgba[(std::size_t(y) * kSize + std::size_t(x)) * 4]);
    }
  return image;
}

// A grid mesh over the square, n x n cells, each cut in two.
struct GridMesh {
  posemorph::bake::Points vertices;
  posemorph::bake::Triangles triangles;
  std::vector<bool> boundary;
};
GridMesh Grid(int n) {
  GridMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      m.vertices.emplace_back(kLo + (kHi - kLo) * i / n, kLo + (kHi - kLo) * j / n);
      m.boundary.push_back(i == 0 || j == 0 || i == n || j == n);
    }
  auto id = [n](int i, int j) { return std::uint32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

double SmallestAngle(const Vec2& a, const Vec2& b, const Vec2& c) {
  auto angle = [](const Vec2& p, const Vec2& q, const Vec2& r) {
    const Vec2 u = q - p, v = r - p;
    return std::atan2(std::abs(u.x() * v.y() - u.y() * v.x()), u.dot(v));
  };
  return std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)});
}

}  // namespace

TEST_CASE("alignment recovers a known smooth warp of the interior within half a pixel") {
  const double amplitude = 5;  // pixels at the square's centre
  const std::vector<pm::AlignmentImage> images{Drawing(0), Drawing(amplitude)};
  const GridMesh grid = Grid(8);
  std::vector<posemorph::bake::Points> meshes{grid.vertices, grid.vertices};
  pm::AlignmentReport report;
  pm::AlignInteriors(images, grid.triangles, grid.boundary, meshes, {}, &report);

  double worst = 0, worst_before = 0;
  for (std::size_t v = 0; v < grid.vertices.size(); ++v) {
    const Vec2 expected = Warp(grid.vertices[v], amplitude);
    worst = std::max(worst, (meshes[1][v] - expected).norm());
    worst_before = std::max(worst_before, (grid.vertices[v] - expected).norm());
    if (grid.boundary[v]) CHECK(meshes[1][v] == grid.vertices[v]);  // held exactly
  }
  MESSAGE("vertex error " << worst << " px (before " << worst_before << "); colour difference "
                          << report.difference_before[1] << " -> " << report.difference_after[1] << "; " << report.steps
                          << " steps, " << report.seconds << " s");
  CHECK(worst_before > 4.5);
  CHECK(worst < 0.5);
  CHECK(report.difference_after[1] < 0.1 * report.difference_before[1]);
  CHECK(meshes[0] == grid.vertices);  // the reference does not move
  for (const auto& t : grid.triangles) {
    const double before = SmallestAngle(grid.vertices[t[0]], grid.vertices[t[1]], grid.vertices[t[2]]);
    const Vec2 &a = meshes[1][t[0]], &b = meshes[1][t[1]], &c = meshes[1][t[2]];
    CHECK((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x() > 0);
    CHECK(SmallestAngle(a, b, c) >= 0.5 * before - 1e-12);
  }
}

TEST_CASE("alignment leaves drawings that already agree where they are") {
  const std::vector<pm::AlignmentImage> images{Drawing(0), Drawing(0)};
  const GridMesh grid = Grid(6);
  std::vector<posemorph::bake::Points> meshes{grid.vertices, grid.vertices};
  pm::AlignmentReport report;
  pm::AlignInteriors(images, grid.triangles, grid.boundary, meshes, {}, &report);
  double worst = 0;
  for (std::size_t v = 0; v < grid.vertices.size(); ++v)
    worst = std::max(worst, (meshes[1][v] - grid.vertices[v]).norm());
  CHECK(worst < 0.01);
  CHECK(report.difference_before[1] < 1e-6);
}
