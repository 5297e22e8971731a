// SPDX-License-Identifier: MIT
// A sample RigDescription as the rig-description JSON committed in assets/.
#pragma once
#include <cmath>
#include <string>

#include "posemorph/bake/rig_description.h"

namespace posemorph::samples {

// Vertices rounded to 1e-9 (readable files; the bake reads back exactly what
// the file says), then bake::RigDescriptionText.
inline std::string DescriptionJson(bake::RigDescription rig) {
  for (bake::PoseDescription& pose : rig.poses)
    for (Eigen::Vector2d& v : pose.vertices) v = {std::round(v.x() * 1e9) / 1e9, std::round(v.y() * 1e9) / 1e9};
  return bake::RigDescriptionText(rig);
}

}  // namespace posemorph::samples
