// SPDX-License-Identifier: MIT
// Step 2 of the bake: the rig's meshes. Poses given as vertices are taken as
// they are, drawn poses from map_drawings.h, and poses made by dragging
// handles on another pose's mesh ("deform", paper section 3.2) are computed
// with the ARAP deformer (arap_deformer.h) in dependency order; they share
// their source's triangles, drawing and uvs.
#pragma once
#include "posemorph/bake/map_drawings.h"
#include "posemorph/bake/pose_meshes.h"
#include "posemorph/bake/rig_description.h"

namespace posemorph::bake {

// Throws BakeError naming the file, the pose and the problem: every pose
// deformed, an unknown or cyclic source, fewer than 2 handles, a handle off the
// mesh, coinciding handles, a triangle the deformation flips.
PoseMeshes DeformPoses(const RigDescription& description, const MappedDrawings& drawings);

// Steps 1 and 2 together: DeformPoses(description, MapDrawings(description)).
PoseMeshes ResolvePoseMeshes(const RigDescription& description);

}  // namespace posemorph::bake
