// SPDX-License-Identifier: MIT
#include "posemorph/bake/grid_resolution.h"

#include <algorithm>
#include <cmath>

#include "posemorph/bake/error.h"
#include "posemorph/bake/pose_space_samples.h"
#include "posemorph/bake/pose_space_weights.h"

namespace posemorph::bake {
namespace {

// Samples x vertices x poses beyond which the move is bounded by the
// largest reaches instead of vertex by vertex.
constexpr double kMaxVertexWork = 4e7;

// The grid's weights at (x, y), as the runtime's WeightsJob interpolates them
// (before its weight limit).
void WeightsAt(const WeightGrid& g, std::size_t N, double x, double y, double* w) {
  const GridLocation at = LocateInGrid(g, true, x, y);
  const std::size_t corners = g.corner_count();
  for (std::size_t i = 0; i < N; ++i) w[i] = 0;
  for (int k = 0; k < 3; ++k) {
    const std::size_t node = at.node[k];
    const double* nw = node < corners ? &g.weights[node * N] : &g.centre_weights[(node - corners) * N];
    for (std::size_t i = 0; i < N; ++i) w[i] += at.lambda[k] * nw[i];
  }
}

}  // namespace

int ChooseGridResolution(const std::vector<Eigen::Vector2d>& points, const std::vector<std::string>& names,
                         const BakeParameters& parameters, const std::string& file, const PoseMeshes& meshes,
                         double pixels_per_unit, bool* coarsened, double* moved) {
  if (moved) *moved = 0;
  if (coarsened) *coarsened = false;
  if (!GridResolutionIsAutomatic(parameters) || points.size() < 2 || meshes.poses.empty())
    return parameters.grid_resolution;
  const std::size_t N = points.size(), V = meshes.poses[0].vertices.size();
  // Each pose's offsets from the poses' mean (pixels), and how far they
  // reach at most.
  std::vector<double> reach(N, 0);
  std::vector<Eigen::Vector2d> offset(N * V);
  for (std::size_t v = 0; v < V; ++v) {
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const PoseMesh& p : meshes.poses) mean += p.vertices[v];
    mean /= double(N);
    for (std::size_t i = 0; i < N; ++i) {
      offset[v * N + i] = (meshes.poses[i].vertices[v] - mean) * pixels_per_unit;
      reach[i] = std::max(reach[i], offset[v * N + i].norm());
    }
  }
  // Where the rig blends its drawn poses: the pose points' convex hull (the
  // default grid's nodes and cell centres inside it, and its edges). Beyond
  // it the grids differ by more than sampling: each holds the spline only
  // within two of its own cells of the hull and levels out past them
  // (pose_space_weights.h).
  std::vector<std::string> warnings;
  const WeightGrid fine = SolvePoseSpaceWeights(points, names, parameters, file, &warnings);
  std::vector<Eigen::Vector2d> hull = ConvexHull(points), samples;
  if (hull.size() < 3) {  // collinear pose points: the segment between the two extremes
    Eigen::Index lo = 0, hi = 0;
    const Eigen::Vector2d d = hull.size() == 2 ? hull[1] - hull[0] : Eigen::Vector2d(1, 0);
    std::vector<double> along;
    for (const Eigen::Vector2d& p : points) along.push_back(p.dot(d));
    lo = std::min_element(along.begin(), along.end()) - along.begin();
    hi = std::max_element(along.begin(), along.end()) - along.begin();
    hull = {points[std::size_t(lo)], points[std::size_t(hi)]};
  }
  const std::size_t H = hull.size();
  for (std::size_t e = 0; e < (H == 2 ? 1 : H); ++e)
    for (int k = 0; k <= 256; ++k) samples.push_back(hull[e] + (hull[(e + 1) % H] - hull[e]) * (k / 256.0));
  if (H >= 3) {
    auto inside = [&](const Eigen::Vector2d& q) {
      for (std::size_t e = 0; e < H; ++e) {
        const Eigen::Vector2d u = hull[(e + 1) % H] - hull[e], v = q - hull[e];
        if (u.x() * v.y() - u.y() * v.x() < 0) return false;
      }
      return true;
    };
    for (std::uint32_t j = 0; j <= 2 * fine.cells_y; ++j)
      for (std::uint32_t i = 0; i <= 2 * fine.cells_x; ++i) {
        const Eigen::Vector2d q(fine.origin_x + fine.cell * i / 2, fine.origin_y + fine.cell * j / 2);
        if (inside(q)) samples.push_back(q);
      }
  }
  for (int cells : kCoarseGridResolutions) {
    BakeParameters coarse_parameters = parameters;
    coarse_parameters.grid_resolution = cells;
    coarse_parameters.grid_resolution_given = true;
    std::vector<std::string> coarse_warnings;
    WeightGrid coarse;
    try {
      coarse = SolvePoseSpaceWeights(points, names, coarse_parameters, file, &coarse_warnings);
    } catch (const BakeError&) {
      continue;  // two pose points in one cell
    }
    if (coarse_warnings.size() > warnings.size()) continue;  // two pose points closer than two cells
    std::vector<double> a(N), b(N);
    double worst = 0;
    // Vertex by vertex where that is cheap enough; else the bound of the
    // largest reaches (larger, never smaller).
    const bool per_vertex = double(samples.size()) * double(V) * double(N) <= kMaxVertexWork;
    auto measure = [&](const Eigen::Vector2d& at) {
      WeightsAt(fine, N, at.x(), at.y(), a.data());
      WeightsAt(coarse, N, at.x(), at.y(), b.data());
      double bound = 0;
      if (per_vertex) {
        for (std::size_t v = 0; v < V; ++v) {
          Eigen::Vector2d move = Eigen::Vector2d::Zero();
          for (std::size_t i = 0; i < N; ++i) move += (b[i] - a[i]) * offset[v * N + i];
          bound = std::max(bound, move.norm());
        }
      } else {
        for (std::size_t i = 0; i < N; ++i) bound += std::abs(b[i] - a[i]) * reach[i];
      }
      worst = std::max(worst, bound * M_PI / 2);
    };
    for (const Eigen::Vector2d& at : samples) measure(at);
    if (worst <= kGridTolerancePx) {
      if (moved) *moved = worst;
      if (coarsened) *coarsened = true;
      return cells;
    }
  }
  return parameters.grid_resolution;
}

}  // namespace posemorph::bake
