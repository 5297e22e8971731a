// SPDX-License-Identifier: MIT
// A description's state machine as the rig's MACH section (format 1.9,
// runtime/FORMAT.md; records in posemorph/format/records.h).
#pragma once
#include <vector>

#include "posemorph/bake/rig_description.h"

namespace posemorph::bake {

// The section's bytes; empty when the description has no state machine.
std::vector<unsigned char> MachineSection(const StateMachineDescription& machine);

}  // namespace posemorph::bake
