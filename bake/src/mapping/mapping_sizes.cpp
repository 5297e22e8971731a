// SPDX-License-Identifier: MIT
#include "posemorph/bake/mapping/mapping_sizes.h"

#include <algorithm>

namespace posemorph::bake::mapping {

MappingSizes ResolveMappingSizes(const MappingParameters& parameters, double outline_size) {
  MappingSizes sizes;
  sizes.simplify_tolerance =
      parameters.simplify_tolerance > 0 ? parameters.simplify_tolerance : std::clamp(outline_size / 50, 0.75, 2.0);
  sizes.spacing = parameters.spacing > 0 ? parameters.spacing : std::max(1.0, outline_size / 1024);
  sizes.max_edge_length =
      parameters.max_edge_length > 0 ? parameters.max_edge_length : std::max(8.0, outline_size / 10);
  sizes.spacing *= parameters.spacing_scale;
  sizes.max_edge_length *= parameters.edge_scale;
  sizes.working_scale = parameters.working_scale;
  return sizes;
}

double LandmarkTolerance(const MappingParameters& parameters, double outline_size) {
  return std::max(parameters.landmark_distance * outline_size, kLandmarkToleranceFloor);
}

}  // namespace posemorph::bake::mapping
