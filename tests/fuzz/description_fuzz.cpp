// SPDX-License-Identifier: MIT
// libFuzzer harness: the rig description parser and validation, and the
// N-way mapping of small outlines given inline. Every refusal must be a
// BakeError (the bake's one error type, which names the file); any other
// exception, a crash or a hang is a finding. Files named by the description
// resolve under a folder that does not exist, so nothing is read.
#include <cstdint>
#include <string>

#include "posemorph/bake/error.h"
#include "posemorph/bake/deform_poses.h"
#include "posemorph/bake/orient_triangles.h"
#include "posemorph/bake/rig_description.h"
#include "posemorph/bake/validate_rig.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace posemorph::bake;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    RigDescription rig = ParseRigDescription(text, "fuzz.json", "/nonexistent-posemorph-fuzz");
    // Mapping is the expensive stage; fuzz it on small shapes (what it does
    // with large ones is bounded by its limits and covered by the hostile
    // corpus replay).
    std::size_t points = 0;
    for (const PoseDescription& pose : rig.poses) points += pose.outline.size() + pose.landmarks.size();
    if (points > 256 || rig.poses.size() > 8) return 0;
    PoseMeshes meshes = ResolvePoseMeshes(rig);  // maps drawn poses first
    meshes.triangles = OrientTriangles(meshes);
    (void)ValidateRig(meshes, rig.paths);
  } catch (const BakeError&) {
  }
  return 0;
}
