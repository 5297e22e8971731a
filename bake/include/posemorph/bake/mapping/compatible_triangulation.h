// SPDX-License-Identifier: MIT
// Stage 4 of N-way mapping: one triangulation valid in all N polygons (stages I-III).
#pragma once
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "posemorph/bake/error.h"
#include "posemorph/bake/mapping/polygon.h"

namespace posemorph::bake::mapping {

struct CompatibleMesh {
  std::vector<Polygon> vertices;                      // per pose, one position per vertex
  std::vector<std::array<std::size_t, 3>> triangles;  // shared, CCW in every pose
  std::size_t boundary_vertices = 0;                  // vertices 0..boundary_vertices-1 are the polygon's, in order
  std::size_t steiner_points = 0;                     // interior vertices the triangulation added
  std::vector<std::size_t> features;                  // feature vertices (interior_features.h); refinement holds them
};
// Splits all N polygons along chords valid in every pose (stage I), through
// one Steiner point per pose (II) or the fewest over shortest link paths
// (III) until every piece is a triangle. Throws poses.Error(...) (the source
// naming all the poses) when no compatible split exists or more than
// `max_steiner_points` would be needed.
CompatibleMesh TriangulateCompatibly(const std::vector<Polygon>& polygons, const ErrorSource& poses,
                                     std::size_t max_steiner_points);

}  // namespace posemorph::bake::mapping
