// SPDX-License-Identifier: MIT
// Where the tools look for a baked rig's drawings when no folder is given
// (posemorph-view and `posemorph-bake sheet --textured` without --images).
#pragma once
#include <string>

#include "posemorph/rig.h"

namespace posemorph::bake {

// The folder the bake found the drawings in (Rig::drawing_folder, format
// 1.5: relative to the rig file) when it is a relative '/'-separated path
// without control characters and is a folder now; else the rig file's own
// folder ("." when it has none).
std::string DefaultDrawingFolder(const std::string& rig_file, const Rig& rig);

}  // namespace posemorph::bake
