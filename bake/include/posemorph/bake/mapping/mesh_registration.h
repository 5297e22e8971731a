// SPDX-License-Identifier: MIT
// Stage 4, another way: mapping by deformation (registration). Instead of
// triangulating all N polygons together (compatible_triangulation.h), pose
// 0's polygon is triangulated and refined alone, and that mesh is deformed
// onto every other pose's polygon: its boundary vertices go to their
// corresponding points (the correspondence of boundary_matching.h, each
// vertex between two polygon corners at the same share of the edge), and its
// interior follows as rigidly as it can.
//
// The deformation of pose k minimises, over all vertex positions y,
//   E(y) = sum over triangles t of area_t (|J_t|^2 + |J_t^-1|^2)
//        + w sum over boundary vertices b of |y_b - target_b|^2
// where J_t maps t in pose 0 to t in y (the symmetric Dirichlet energy: 4 for
// a rotation, infinite for a triangle of no area, so no step of the descent
// can turn a triangle over: each is cut short before any would). It starts
// from the similarity that fits pose 0's boundary to the targets best and
// raises w tenfold from 1 until every boundary vertex is within 1e-4 of the
// mean edge of its target, by Newton steps on the per-triangle Hessians made
// positive semi-definite (their 4x4 eigenvalues clamped at 0) and a
// backtracking line search. Each triangle is rotated, stretched and
// squeezed as little as the outline lets it, so a wing or an arm that turns
// far keeps its triangles' shapes, where separately chosen chords would cut
// across it.
#pragma once
#include <cstddef>
#include <vector>

#include "posemorph/bake/error.h"
#include "posemorph/bake/mapping/compatible_refinement.h"
#include "posemorph/bake/mapping/compatible_triangulation.h"
#include "posemorph/bake/mapping/polygon.h"

namespace posemorph::bake::mapping {

// polygons: the N simplified polygons (K corresponding vertices each, simple,
// counter-clockwise, on the integer grid). Pose 0's polygon is triangulated
// (at most max_steiner_points) and refined alone with `parameters`; every
// interior edge that joins two boundary vertices is then split (a triangle
// whose three corners all lie on the outline could not follow it). The mesh
// returned has N poses, boundary vertices on each polygon's edges (on them or
// outside), every triangle counter-clockwise in every pose (checked
// exactly). Throws poses[k].Error(...) when pose k cannot be reached without
// a triangle turning over.
CompatibleMesh RegisterCompatibly(const std::vector<Polygon>& polygons, const RefinementParameters& parameters,
                                  const std::vector<ErrorSource>& poses, std::size_t max_steiner_points);

}  // namespace posemorph::bake::mapping
