// SPDX-License-Identifier: MIT
// The biharmonic pose-space weight field of the paper's section 4.1 on a
// regular grid. Within two cells of the pose points' convex hull the grid
// holds the thin-plate spline through (p_i, e_i) (thin_plate_spline.h: the
// biharmonic interpolant of the whole plane, so mirror images and turns of a
// layout get permuted weights and uneven layouts are not distorted by the
// grid's edge). Beyond, it minimises the paper's discrete energy
// sum over edge-adjacent grid triangles ||grad W_j - grad W_k||^2
// + eps' sum_j area_j ||grad W_j||^2 with those values held, so the field
// continues the spline smoothly and levels out (docs/DESIGN.md).
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

// Poses on a horizontal or vertical line (a walk's three frames from left
// to right, init's three poses from top to bottom) are driven along it:
// the pad range reaches one cell across (Rig::pad_range), and the weights
// vary along the line. With BakeParameters::narrow_line_layout the grid
// is this many cells across the line, centred on it, rather than the
// domain's full width: the spline's band (two cells each side) and two
// more cells to level out, where a 64-cell grid spent 43 columns (a 32 x 32
// sprite's three frames: 3,673 of its 5,894 bytes were weights). A point
// beyond the grid takes the weights at its edge, as everywhere.
constexpr std::uint32_t kLineLayoutCells = 8;

// Throws BakeError (with `file`) if two points share a grid cell. Appends to
// *warnings ("FILE: ...") each pair of points closer than two cells, between
// which the grid's linear interpolation is coarse.
WeightGrid SolvePoseSpaceWeights(const std::vector<Eigen::Vector2d>& points, const std::vector<std::string>& names,
                                 const BakeParameters& parameters, const std::string& file,
                                 std::vector<std::string>* warnings = nullptr);

}  // namespace posemorph::bake
