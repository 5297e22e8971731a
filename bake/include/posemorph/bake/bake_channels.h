// SPDX-License-Identifier: MIT
// A character with control channels (bake/RIG_DESCRIPTION.md, "channels";
// DESIGN.md section 8): the first channel's parts are baked as one rig (the
// body, glued as a layered character), each part of another channel as a rig
// of its own over its channel's poses (an attachment), and the body's file
// gets a CHAN section that holds the attachments, each pinned to the body
// triangle under its joint (runtime/FORMAT.md, format 1.7).
#pragma once
#include <cstddef>
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

// Bakes the body and every attachment (BakeRig each, with their checks),
// pins each attachment to the body triangle under its joint in pose 0, and
// writes them as one rig; then loads it with the runtime and measures each
// attachment's placement (AttachmentReport::placed_error). Throws BakeError
// naming the file, the part and the pose: a part that cannot be baked, a
// joint off the part it is glued to (outside its triangles in pose 0), or off
// the attached part.
std::vector<unsigned char> BakeChannels(const RigDescription& description, BakeReport* report);

}  // namespace posemorph::bake
