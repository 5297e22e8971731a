// SPDX-License-Identifier: MIT
// The biharmonic pose-space weight field of the paper's section 4.1 on a
// regular grid: minimise sum over edge-adjacent grid triangles of
// ||grad W_j - grad W_k||^2 + eps' sum_j area_j ||grad W_j||^2 with W(p_i) = e_i.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "posemorph/bake/rig_description.h"
#include "posemorph/grid_location.h"

namespace posemorph::bake {

// The runtime's PoseSpaceGrid as the bake builds it: the same geometry type
// (grid_location.h), its node weights in vectors.
struct WeightGrid : GridGeometry {
  std::vector<double> weights;  // (cells_x+1)(cells_y+1) x N, row-major in y then x
  // cells_x * cells_y x N: each cell is four triangles meeting at its centre
  // (format 1.2; the runtime's PoseSpaceGrid::centre_weights).
  std::vector<double> centre_weights;
};

// Throws BakeError (with `file`) if two points share a grid cell.
WeightGrid SolvePoseSpaceWeights(const std::vector<Eigen::Vector2d>& points, const std::vector<std::string>& names,
                                 const BakeParameters& parameters, const std::string& file);

}  // namespace posemorph::bake
