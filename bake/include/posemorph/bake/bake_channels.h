// SPDX-License-Identifier: MIT
// A character with control channels (bake/RIG_DESCRIPTION.md, "channels";
// DESIGN.md section 8): the first channel's parts are baked as one rig (the
// body, glued as a layered character), each part of another channel as a rig
// of its own over its channel's poses (an attachment), and the body's file
// gets a CHAN section that holds the attachments, each pinned to the body
// triangle under its joint (runtime/FORMAT.md, format 1.7).
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "posemorph/bake/bake.h"
#include "posemorph/bake/rig_description.h"

namespace posemorph::bake {

// The first channel's parts alone, with the glue between them: a layered
// character of one channel, which BakeRig bakes as before.
RigDescription ChannelBodyDescription(const RigDescription& description);

// Part `part` (driven by a channel after the first) alone over its channel's
// poses and paths, as a rig of one part; a drawn part's joint becomes a
// feature of every pose, so that a vertex lies on it. Its file reads "FILE:
// part 'NAME'", so that every message names the part.
RigDescription AttachmentDescription(const RigDescription& description, std::size_t part);

// A part of a later channel, planned: its own description and its joint.
struct AttachmentPlan {
  std::size_t part = 0;        // its index in the description's parts
  RigDescription description;  // AttachmentDescription(description, part)
  GlueDescription glue;        // the joint that pins it to a body part
};

// What BakeCharacter bakes, decided before any of it is baked: the body and
// the attachments in part order, and the channels' names (the CHAN section's).
struct CharacterPlan {
  RigDescription body;  // ChannelBodyDescription
  std::vector<AttachmentPlan> attachments;
  std::vector<std::string> channels;
};

// Throws BakeError naming the file and the part where a drawn part's joint
// is not given in each of its channel's poses (AttachmentDescription); the
// description's reader has checked the rest of the glue.
CharacterPlan PlanCharacter(const RigDescription& description);

// Bakes the plan: the body and every attachment (BakeOne each, with their
// checks), pins each attachment to the body triangle under its joint in pose
// 0, adds them as CHAN to the body's sections and writes the file once; then
// loads it with the runtime and measures each attachment's placement
// (AttachmentReport::placed_error). Throws BakeError naming the file, the
// part and the pose: a part that cannot be baked, a joint off the part it is
// glued to (outside its triangles in pose 0), or off the attached part.
std::vector<unsigned char> BakeCharacter(const RigDescription& description, BakeReport* report);

}  // namespace posemorph::bake
