// SPDX-License-Identifier: MIT
// Steps 1 and 2 for a layered character (bake/RIG_DESCRIPTION.md, "parts"):
// each part's drawings are mapped N-way on their own (or its meshes read),
// then the parts are joined into one mesh in which every glue joint is one
// vertex shared by the two parts. The as-rigid-as-possible solve of the
// joined mesh (arap_system.h) then holds each joint exactly, in every frame,
// with one factor: the parts turn about their joints instead of drifting
// apart as independent solves would (DESIGN.md section 8).
#pragma once
#include <cstdint>
#include <vector>

#include "posemorph/bake/map_drawings.h"
#include "posemorph/bake/pose_meshes.h"
#include "posemorph/bake/rig_description.h"

namespace posemorph::bake {

struct JoinedParts {
  PoseMeshes meshes;                  // triangles part after part; meshes.parts says which
  MappingReport report;               // the drawn parts' mappings, summed
  std::vector<std::uint32_t> joints;  // per glue entry, its vertex in the joined mesh
};

// The description of one part alone: the rig's poses (names, points), the
// part's meshes or drawings, the rig's mapping parameters; the joints that
// involve the part become features of its drawn poses. Its file reads
// "FILE: part 'NAME'", so that every message names the part.
RigDescription PartRigDescription(const RigDescription& description, std::size_t part);

// Throws BakeError naming the file, the part, the pose and the problem: a
// part that cannot be mapped or is not a valid mesh, a joint off a part
// (no vertex there, for meshes; outside the outline, for drawings), a joint
// drawn at different points on its two parts, parts of one pose on
// different canvases, some parts with uvs and others without.
JoinedParts JoinParts(const RigDescription& description);

}  // namespace posemorph::bake
