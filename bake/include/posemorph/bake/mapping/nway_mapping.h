// SPDX-License-Identifier: MIT
// N-way mapping (DESIGN.md section 4, paper section 3.1): N drawings of one
// character in, N compatible triangle meshes out. Stages, one header and
// one file each (bake/src/mapping/):
//   outline_image.h / outline_svg.h   drawing -> simple CCW polygon
//   boundary_matching.h               dense corresponding boundary points
//   enclosing_simplification.h        fewer points, still enclosing
//   compatible_triangulation.h        stages I-III
//   mesh_registration.h               or: pose 0's mesh deformed onto the others
//   compatible_refinement.h           splits, flips, smoothing
//   interior_features.h               points inside the shape that correspond
//   polygon.h                         polygons and exact grid geometry
//   limits.h                          bounds on work and memory
//   mapping_sizes.h                   lengths that follow the drawing's size
//   nway_mapping.h (this)             the driver: MapPolygons
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "posemorph/bake/mapping/boundary_matching.h"
#include "posemorph/bake/mapping/compatible_refinement.h"
#include "posemorph/bake/mapping/compatible_triangulation.h"
#include "posemorph/bake/mapping/enclosing_simplification.h"
#include "posemorph/bake/mapping/interior_features.h"
#include "posemorph/bake/mapping/limits.h"
#include "posemorph/bake/mapping/mapping_sizes.h"
#include "posemorph/bake/mapping/outline_image.h"
#include "posemorph/bake/mapping/outline_svg.h"
#include "posemorph/bake/mapping/polygon.h"
#include "posemorph/bake/rig_description.h"

namespace posemorph::bake::mapping {

struct MappingStages {
  double grid_scale = 1;                      // grid units per rig unit (a power of two)
  MappingSizes sizes;                         // the lengths used (automatic ones resolved)
  std::vector<Polygon> outlines;              // grid, counter-clockwise, simple
  std::vector<std::vector<Point>> landmarks;  // on the outlines, grid
  CorrespondedBoundary matched;
  SimplifiedBoundary simplified;
  CompatibleMesh mesh;                // grid
  std::vector<std::string> warnings;  // limits that changed what was asked (e.g. a coarser spacing)
  // Poses whose start landmark seems to sit on another part of the outline
  // than pose 0's (AlignStart: the outline matches best with the start more
  // than an eighth of the way round, at under 0.8 times the cost): the
  // in-betweens may spin. Warnings; the start suggested is in rig coordinates.
  struct SpinningStart {
    std::size_t pose = 0;
    double shift = 0;  // share of the perimeter, counter-clockwise as seen
    Point suggested{0, 0};
    StartAlignment alignment;
  };
  std::vector<SpinningStart> spinning;
};
// Outlines, landmarks and features (per pose; none, or as many in every pose)
// in rig coordinates (y up, any orientation); labels name each pose in
// messages. The driver behind MapDrawings, exposed so tests can check every
// stage's promise. Throws BakeError naming `file`.
MappingStages MapPolygons(const std::vector<Polygon>& outlines, const std::vector<std::vector<Point>>& landmarks,
                          const std::vector<std::vector<Point>>& features, const MappingParameters& parameters,
                          const std::vector<std::string>& labels, const std::string& file);

}  // namespace posemorph::bake::mapping
