// SPDX-License-Identifier: MIT
// Step 3 of the bake: pose 0 decides the orientation. A mesh given clockwise
// (its triangles' signed areas in pose 0 summing below 0) is turned around, so
// that every later step can take counter-clockwise triangles for granted.
#pragma once
#include "posemorph/bake/pose_meshes.h"

namespace posemorph::bake {

// The triangle list, each triangle's last two vertices swapped when the mesh
// is clockwise in pose 0; unchanged otherwise. Triangles naming a vertex pose
// 0 does not have are left out of the sum (validate_rig.h refuses them).
Triangles OrientTriangles(const PoseMeshes& meshes);

}  // namespace posemorph::bake
