// SPDX-License-Identifier: MIT
// The pose-space grid's resolution when the description leaves it
// (issue 36, point 5: small rigs for small sprites). The weight grid is most
// of a small sprite's rig, and how finely it is sampled matters in
// proportion to how far the vertices travel between poses: a 70-pixel
// sprite needs far fewer cells than a 1024-pixel one for the same frames.
#pragma once
#include <string>
#include <vector>

#include <Eigen/Core>

#include "posemorph/bake/pose_meshes.h"
#include "posemorph/bake/rig_description.h"

namespace posemorph::bake {

// The coarser grids tried, coarsest first, before the default one.
constexpr int kCoarseGridResolutions[] = {8, 12, 16, 24, 32};
// How far (pixels) a coarser grid's weights may move a vertex from where the
// default grid's put it, at most, anywhere on the grid.
constexpr double kGridTolerancePx = 0.25;

// Whether the bake chooses the grid's resolution: the description leaves
// bake.grid_resolution out and no code changed it from the default.
inline bool GridResolutionIsAutomatic(const BakeParameters& parameters) {
  return !parameters.grid_resolution_given && parameters.grid_resolution == BakeParameters{}.grid_resolution;
}

// The grid resolution the bake uses. A description that gives
// bake.grid_resolution (or code that changed it) gets that. Otherwise the
// coarsest of kCoarseGridResolutions whose weights keep every vertex within
// kGridTolerancePx of where the default resolution's weights put it, at
// every node of the default grid (its corners and cell centres); else the
// default. A vertex's move is bounded by the linear blend of the pose
// positions (sum over poses of |weight change| times how far that pose's
// vertices lie from their mean at most, by pixels_per_unit) times pi/2 (a
// rotation's arc against its chord), so the bound holds for the
// as-rigid-as-possible blend too. A coarser grid that would put two pose
// points closer than two cells is not used. Sets *coarsened to whether a
// coarser grid was chosen and *moved to its estimate (0 otherwise).
int ChooseGridResolution(const std::vector<Eigen::Vector2d>& points, const std::vector<std::string>& names,
                         const BakeParameters& parameters, const std::string& file, const PoseMeshes& meshes,
                         double pixels_per_unit, bool* coarsened = nullptr, double* moved = nullptr);

}  // namespace posemorph::bake
