// SPDX-License-Identifier: MIT
// The mapping's lengths that follow the drawing's size (issue: fidelity).
// A description that leaves simplify_tolerance, spacing or max_edge_length
// at 0 gets them from the size of the first drawn pose's outline (its
// bounding-box diagonal, drawing units), so a 32-pixel sprite and a
// 1024-pixel drawing both get meshes in proportion to them.
#pragma once
#include "posemorph/bake/rig_description.h"

namespace posemorph::bake::mapping {

struct MappingSizes {
  // Working units (MappingParameters): drawing units at the working level.
  double simplify_tolerance = 0;  // how far the boundary may stand off the outline
  double spacing = 0;             // between matched boundary samples
  double max_edge_length = 0;     // longest mesh edge in any pose
  double working_scale = 1;       // drawing units per working unit, for messages
};

// Automatic values (size s = the outline's bounding-box diagonal):
//   simplify_tolerance  s / 50, within [0.75, 2]   (2 from about 100 units up)
//   spacing             s / 1024, at least 1       (1 up to 1024 units)
//   max_edge_length     s / 10, at least 8         (8 below 80 units: no
//                       triangles of a pixel or two on a sprite)
// Values given (non-zero) are kept as they are. Then spacing and
// max_edge_length are multiplied by parameters.spacing_scale and edge_scale.
MappingSizes ResolveMappingSizes(const MappingParameters& parameters, double outline_size);

// How far (drawing units) a landmark may lie off its outline:
// parameters.landmark_distance times the outline's size (its bounding-box
// diagonal), but never less than kLandmarkToleranceFloor, so that a small
// part's landmarks are not held to a pixel and a half (5% of 30 pixels) when
// the traced outline itself stands up to a pixel off the drawn edge.
constexpr double kLandmarkToleranceFloor = 3;
double LandmarkTolerance(const MappingParameters& parameters, double outline_size);

}  // namespace posemorph::bake::mapping
