// SPDX-License-Identifier: MIT
// Sampling a stored pose-space animation path.
#pragma once
#include "posemorph/export.h"
#include <cstdint>

#include "posemorph/rig.h"

namespace posemorph {

// Point on path `index` at `time` seconds. Looping paths wrap time over
// [first key, last key); others hold their end points. Non-finite time gives
// the first key. Returns false for a bad index.
PM_API bool SamplePath(const Rig& rig, std::uint32_t index, double time, double* x, double* y);
PM_API bool SamplePath(const PathView& path, double time, double* x, double* y);

}  // namespace posemorph
