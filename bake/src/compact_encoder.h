// SPDX-License-Identifier: MIT
// The compact encoding's writer (compact_encoder.cpp): an exact rig's
// sections re-encoded at a position step and a weight step. CompactRig
// (compact_rig.cpp) searches the steps, measuring each trial with the
// runtime.
#pragma once
#include <cstdint>
#include <map>
#include <vector>

#include "posemorph/bake/compact_rig.h"
#include "posemorph/format/records.h"
#include "posemorph/rig.h"

namespace posemorph::bake::compact {

// The exact rig's sections by tag, as its bytes hold them.
std::map<std::uint32_t, std::vector<unsigned char>> RawSections(const std::vector<unsigned char>& bytes);

// What the encoder works from: the exact rig (loaded, and its sections), the
// uvs' tolerance, and the whole turns learnt from a first trial.
struct Encoder {
  const Rig& exact;
  double uv_tolerance_px;
  double pixels_per_unit;
  std::map<std::uint32_t, std::vector<unsigned char>> raw;
  std::vector<std::int32_t> turns;  // T x N, filled after a first load
  bool derive_last_pose = false;

  // The compact rig's bytes at these steps (empty when a position does not
  // fit the code's range); its sections noted in `report` when given, and
  // QINF written when `info` is.
  std::vector<unsigned char> Encode(double position_step, double weight_step, CompactReport* report,
                                    const format::CompactInfo* info = nullptr) const;
};

}  // namespace posemorph::bake::compact
