// SPDX-License-Identifier: MIT
// Stage 3 of N-way mapping: fewer corresponding points, every polygon still enclosing its outline.
#pragma once
#include <vector>

#include "posemorph/bake/error.h"
#include "posemorph/bake/mapping/boundary_matching.h"
#include "posemorph/bake/mapping/polygon.h"

namespace posemorph::bake::mapping {

struct SimplifiedBoundary {
  std::vector<Polygon> polygons;       // per pose, K vertices, simple, CCW, enclosing the outline
  std::vector<std::size_t> kept;       // index among the M corresponding points of each vertex
  std::vector<std::size_t> landmarks;  // index among the K vertices of each landmark
  double max_error = 0;                // largest distance added between outline and polygon
};
// Greedily removes corresponding N-tuples with the smallest error (maximum over
// poses) while it stays <= tolerance, sliding neighbours outward so every
// polygon keeps enclosing its outline and stays simple. Landmarks are kept.
// Throws poses[k].Error(...) when no enclosing polygon can be built for pose k.
SimplifiedBoundary SimplifyEnclosing(const std::vector<Polygon>& outlines, const CorrespondedBoundary& boundary,
                                     double tolerance, const std::vector<ErrorSource>& poses);

}  // namespace posemorph::bake::mapping
