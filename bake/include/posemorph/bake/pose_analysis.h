// SPDX-License-Identifier: MIT
// Step 5 of the bake: every triangle's rotation angle and stretch in every
// pose, relative to pose 0 (DESIGN.md section 3; paper section 3.1: the
// polar split A = R(alpha) S of each triangle's affine map), with the angles
// unwrapped over the triangle adjacency so that interpolating them takes the
// short way round and does not depend on the order of the triangles.
#pragma once
#include <vector>

#include "posemorph/bake/pose_meshes.h"

namespace posemorph::bake {

struct PoseAnalysis {
  std::vector<double> angles;     // T x N, triangle-major: alpha of triangle t in pose i at t * N + i
  std::vector<double> stretches;  // T x N x 3: S00, S01, S11 of the symmetric stretch S
};

// Needs validated meshes (validate_rig.h): every triangle of positive area in
// every pose, so each split exists.
PoseAnalysis AnalysePoses(const PoseMeshes& meshes);

}  // namespace posemorph::bake
