// SPDX-License-Identifier: MIT
// Step 4 of the bake: everything the math needs from the meshes, checked
// before any of it runs. Pure: it changes nothing and throws nothing.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "posemorph/bake/pose_meshes.h"
#include "posemorph/bake/rig_description.h"

namespace posemorph::bake {

// The first problem found, naming the pose and triangle, or nullopt when the
// rig is sound. Checked in this order (each check assumes the ones before
// passed): counts (at least 2 poses and 3 vertices, the same vertex and uv
// count in every pose, unique names, uvs for all or none); indices (in
// range, no repeated vertex, no repeated triangle); a manifold mesh (an edge
// borders at most two triangles); one connected mesh using every vertex;
// finite points, vertices and uvs; no degenerate or flipped triangle in any
// pose (the meshes are oriented first: orient_triangles.h); pose points
// within +-1e12, distinct and spanning at least 1e-6; and the rig format's
// limits on poses, vertices, triangles, paths, keys and string bytes.
std::optional<std::string> ValidateRig(const PoseMeshes& meshes, const std::vector<PathDescription>& paths);

// The bake's work bound, checked with the counts: its time and memory grow
// with vertices x poses (a 90,000-vertex, 3-pose mesh: about 10 s and
// 800 MB on the development machine, docs/performance.md "Bake times"), so
// a rig beyond this many vertex-poses is refused at once, not after
// minutes. The runtime's own limit for rigs from players is far below it
// (LoadLimits::Untrusted(): 20,000 vertices).
constexpr std::uint64_t kMaxBakeVertexPoses = 1000000;

}  // namespace posemorph::bake
