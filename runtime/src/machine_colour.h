// SPDX-License-Identifier: MIT
// The state machine's colour fade (state_machine.h, MachineColourJob),
// shared by the step (which starts a fade) and the colour job (which
// advances it and writes the colours).
#pragma once
#include "posemorph/state_machine.h"

namespace posemorph::detail {

// The colour and body parts' opacities (rig.part_count() of them when the
// rig has parts, else none written) that the machine shows now: its states'
// target reached as far as its fade has come.
void ShownColour(const Rig& rig, const MachineInstance& m, float colour[4], float* parts);
// Starts a fade over `mix` seconds from what is shown now (the first
// change of a step), or lengthens the one this step began to `mix`.
void StartFade(const Rig& rig, MachineInstance& m, double mix, bool first_change_of_step);
// At the machine's start: its states' colour shown at once.
void SettleFade(const Rig& rig, MachineInstance& m);

}  // namespace posemorph::detail
