// SPDX-License-Identifier: MIT
// Step 8 of the bake: everything the runtime reads, in its binary layout
// (runtime/FORMAT.md), at full precision (the exact encoding; compact_rig.h
// re-encodes it within an error budget).
#pragma once
#include <vector>

#include "posemorph/bake/arap_system.h"
#include "posemorph/bake/pose_analysis.h"
#include "posemorph/bake/pose_meshes.h"
#include "posemorph/bake/pose_space_weights.h"
#include "posemorph/bake/rig_description.h"
#include "posemorph/bake/rig_sections.h"

namespace posemorph::bake {

// The rig's bounding-box diagonal in pose 0 (the runtime's Rig::size()): the
// scale of its tolerances.
double RigBoundingBoxDiagonal(const PoseMeshes& meshes);

// True when the poses come from drawings (a canvas is known): rig units are
// then drawing pixels.
bool HasCanvases(const PoseMeshes& meshes);

// Names, paths, the texture filter hint and the default sigma come from the
// description; the rest from the steps before. Needs validated meshes.
// Returns the sections in file order (WriteRig makes the file of them).
RigSections SerialiseRig(const RigDescription& description, const PoseMeshes& meshes, const PoseAnalysis& analysis,
                         const ArapSystem& system, const WeightGrid& grid);

}  // namespace posemorph::bake
