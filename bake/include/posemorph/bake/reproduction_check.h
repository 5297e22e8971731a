// SPDX-License-Identifier: MIT
// Step 9 of the bake: what was written is checked with the runtime that will
// read it. The bytes load, and evaluating the rig at each pose point gives
// that pose back within a tolerance (relative to the rig's size: 1e-6 for
// the exact encoding, the error budget for the compact one).
#pragma once
#include <string>
#include <vector>

#include "posemorph/bake/pose_meshes.h"
#include "posemorph/rig.h"

namespace posemorph::bake {

struct ReproductionCheck {
  Rig rig;               // the bytes, loaded (the in-between check evaluates it next)
  double max_error = 0;  // largest vertex distance at the pose points, relative to the rig size
  double tolerance = 0;  // what it was checked within
};

// Throws BakeError(file, "internal error: ...") when the bytes do not load,
// a pose point does not evaluate, or a pose comes back further than
// `tolerance`: a bug of the bake, never of its input.
ReproductionCheck CheckReproduction(const std::vector<unsigned char>& bytes, const PoseMeshes& meshes, double tolerance,
                                    const std::string& file);

// The same measure on a rig already loaded (one pose space of a character's
// file: its body, or an attachment's rig); `what` names it in the message
// ("part 'face'"). Returns the largest distance relative to the rig size.
double MeasureReproduction(const Rig& rig, const PoseMeshes& meshes, double tolerance, const std::string& file,
                           const std::string& what);

}  // namespace posemorph::bake
