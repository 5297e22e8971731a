// SPDX-License-Identifier: MIT
// Stage 5 of N-way mapping: splits, flips and smoothing that raise the smallest angle in every pose.
#pragma once
#include <cstddef>

#include "posemorph/bake/mapping/compatible_triangulation.h"

namespace posemorph::bake::mapping {

// The bound that keeps a mesh in proportion to the sprite: at most this
// many vertices per point of a traced outline (the splits for the angle
// goal stop there: nway_mapping.cpp; the bake's variants keep to it too:
// map_again.cpp).
constexpr double kVerticesPerOutlinePoint = 2;

struct RefinementParameters {
  double max_edge_length = 0;  // 0: no splitting for length
  double min_angle_goal = 20;  // degrees; triangles below it get their longest edge split (bounded)
  int rounds = 4;
  std::size_t max_vertices = 20000;  // no split beyond this many vertices
  // The splits for the angle goal stop at this many vertices too (0: no
  // such bound), or at the count the splits for length left, if more: the
  // mesh stays in proportion to the sprite (nway_mapping.cpp: 2 per point
  // of the first pose's outline).
  std::size_t max_angle_vertices = 0;
  // Each round first removes boundary vertices that make slivers: where a
  // triangle's smallest angle is below the goal opposite a boundary edge,
  // one end of that edge is collapsed into the other, only where the
  // removed vertex is reflex or straight in every pose (so the mesh only
  // grows and still encloses the outline), no triangle turns over in any
  // pose, and the smallest angle around it rises, and it lies within
  // max_collapse_distance of the edge that replaces it in every pose. The
  // rounds without it are run too, and the mesh with the larger smallest
  // angle kept.
  bool collapse_slivers = false;
  double max_collapse_distance = 0;
  // The refinement's independent runs (with and without removing slivers;
  // the graded runs) share out this many threads at most, this one counted;
  // 0: one per core. The mesh is the same bits whatever the number.
  unsigned threads = 0;
};
// Edge splits, flips legal in all N meshes that raise the smallest angle over
// all poses, and angle-based smoothing of interior vertices that never
// inverts a triangle or lowers the local smallest angle. Boundary vertices
// and features (mesh.features) stay where they are (only new points on
// boundary edges are added).
// Stops splitting at parameters.max_vertices; returns false when splitting
// for max_edge_length stopped there (the edges are then longer than asked).
bool RefineCompatibly(CompatibleMesh& mesh, const RefinementParameters& parameters);

// Flips and smoothing only, no new vertices: the quality pass after the
// interior moved (interior_features.h). Boundary vertices and features held.
void ImproveCompatibly(CompatibleMesh& mesh);

double MinAngleDegrees(const CompatibleMesh& mesh);  // over all triangles and poses

}  // namespace posemorph::bake::mapping
