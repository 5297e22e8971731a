// SPDX-License-Identifier: MIT
// The colour of each pose wherever the tools show poses apart (the contact
// sheet, the viewer's pose pad): the colour-blind-safe Okabe-Ito palette,
// repeated after eight poses.
#pragma once
#include <cstdint>

namespace posemorph::bake {

struct PoseColour {
  std::uint8_t r, g, b;
};

constexpr PoseColour kPoseColours[8] = {{0, 114, 178},  {230, 159, 0}, {0, 158, 115},  {204, 121, 167},
                                        {86, 180, 233}, {213, 94, 0},  {240, 228, 66}, {90, 90, 90}};

constexpr PoseColour PoseColourOf(std::uint32_t pose) { return kPoseColours[pose % 8]; }

}  // namespace posemorph::bake
