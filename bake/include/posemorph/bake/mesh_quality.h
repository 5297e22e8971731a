// SPDX-License-Identifier: MIT
// Where a baked mesh keeps too small an angle, and why: the bake refines
// further when the smallest angle over all poses stays below its quality
// floor (bake.h); when that does not lift it, DescribeSmallestAngle says
// where the worst triangle is, in the drawing's pixels, and how much one
// pose squeezes it against another. A drawing that squeezes its outline
// (an arm lying against the body in one pose and raised in another) leaves
// no mesh of one layer that keeps its triangles' shape in both.
#pragma once
#include <cstdint>
#include <string>

#include "posemorph/rig.h"

namespace posemorph::bake {

struct SmallestAngle {
  double degrees = 180;        // the smallest angle of any triangle in any pose
  std::uint32_t triangle = 0;  // the triangle that has it
  std::uint32_t pose = 0;      // the pose it has it in
  // The triangle's shortest edge in that pose, and the same edge where it is
  // longest (in pose `long_pose`), in rig units: their ratio is the squeeze.
  double short_edge = 0, long_edge = 0;
  std::uint32_t long_pose = 0;
};

// Over every triangle and pose of `rig` (its pose positions).
SmallestAngle FindSmallestAngle(const Rig& rig);

// The smallest angle comes from a squeeze: another pose has the triangle's
// shortest edge at least twice as long. Then the outlines' correspondence
// is what to change (the bake's smoothed correspondence, bake.h; the
// advice DescribeSmallestAngle gives), not the refinement.
bool Squeezed(const SmallestAngle& s);

// One line: the angle, the triangle, its centre in the pose's drawing
// pixels (y down, as landmarks are given), the part on a layered rig, the
// squeeze against the other pose and what an animator can do about it.
// `floor` (degrees) is the bound it is below.
std::string DescribeSmallestAngle(const Rig& rig, const SmallestAngle& s, double floor);

}  // namespace posemorph::bake
