// SPDX-License-Identifier: MIT
// The compact encoding's writer (compact_encoder.cpp): an exact rig's
// sections re-encoded at a position step and a weight step. CompactRig
// (compact_rig.cpp) searches the steps, measuring each trial with the
// runtime.
#pragma once
#include <cstdint>
#include <vector>

#include "posemorph/bake/compact_rig.h"
#include "posemorph/bake/rig_sections.h"
#include "posemorph/format/records.h"
#include "posemorph/rig.h"

namespace posemorph::bake::compact {

// What the encoder works from: the exact rig (loaded, and its sections, each
// tag once as SerialiseRig writes them), the uvs' tolerance, and the whole
// turns learnt from a first trial.
struct Encoder {
  const Rig& exact;
  double uv_tolerance_px;
  double pixels_per_unit;
  const RigSections& raw;
  std::vector<std::int32_t> turns;  // T x N, filled after a first load
  bool derive_last_pose = false;

  // The compact rig's sections at these steps (none when a position does
  // not fit the code's range); each noted in `report` when given, and QINF
  // written when `info` is.
  RigSections Encode(double position_step, double weight_step, CompactReport* report,
                     const format::CompactInfo* info = nullptr) const;
};

}  // namespace posemorph::bake::compact
