// SPDX-License-Identifier: MIT
// Image references come from rig files (Rig::pose_image), and a rig file is
// hostile input: a renderer checks a reference before opening what it names.
#pragma once
#include "posemorph/export.h"
#include "posemorph/rig.h"

namespace posemorph {

// True when `reference` names a file inside the folder of drawings: not
// empty, relative (no leading '/'), no '..' component, no backslash, no ':'
// (a drive letter or a URL scheme), no control character.
PM_API bool ImageReferenceStaysInside(StringView reference);

}  // namespace posemorph
