// SPDX-License-Identifier: MIT
// Stage 6 of N-way mapping: features, corresponding points inside the shape
// (an eye's centre, a beak's tip), become shared mesh vertices at exactly
// their points in every pose, so the drawings' interiors line up there
// (issue "Interior correspondence"; the paper leaves interiors to the
// outline's correspondence).
#pragma once
#include <cstddef>
#include <vector>

#include "posemorph/bake/error.h"
#include "posemorph/bake/mapping/compatible_triangulation.h"
#include "posemorph/bake/mapping/polygon.h"

namespace posemorph::bake::mapping {

// features[k][f]: feature f of pose k on the grid, strictly inside the mesh
// of pose k, as many in every pose. Each is first inserted at the centroid of
// the pose-0 triangle that holds it (in every pose the same triangle's
// centroid, so nothing turns over), then every pose's interior vertices move
// by the harmonic interpolation (graph Laplacian) of the features'
// displacements to their points, boundary vertices held. Appends the new
// vertex ids to mesh.features, in order. Throws poses[k].Error naming the
// pose and the feature when moving the features would turn a triangle over.
// grid_scale (grid units per rig unit) only for the messages.
// Per vertex, 1 when it lies on an edge that only one triangle uses.
std::vector<char> BoundaryVertices(const CompatibleMesh& mesh);

void PlaceFeatures(CompatibleMesh& mesh, const std::vector<std::vector<Point>>& features,
                   const std::vector<ErrorSource>& poses, double grid_scale);

}  // namespace posemorph::bake::mapping
