// SPDX-License-Identifier: MIT
// A rig's state machine (format 1.9; Rig::machine_inputs, machine_layers,
// machine_states; RIG_DESCRIPTION.md "state_machine"), run per character on
// top of the Animator: the game sets inputs (bools, numbers, triggers,
// points); a step evaluates each layer's transitions (its any-state ones
// first, then its state's, in order; the first whose conditions all hold
// and whose exit time has come is taken, at most one per layer per step;
// an any-state transition never re-enters the state it leads to),
// issues the Animator commands that enter the new state (play a path, stop,
// follow a point input, blend along a path by a number input), keeps pads
// and blends following their inputs, points each layer's look-at at its
// point input, and clears the triggers. A layer's declared behaviours
// (MachineBehavioursView) are put on its channel at the first step, the
// blink seeded with its seed plus the character's index. Then an
// AnimatorUpdateJob advances the tracks. docs/animation.md is the guide.
//
// Deterministic (comparisons and the Animator's commands only), allocation
// free, and defined for any bytes in a MachineInstance: a layer whose state
// lies outside it enters its initial state.
#pragma once
#include "posemorph/export.h"
#include <cstddef>
#include <cstdint>

#include "posemorph/animator.h"
#include "posemorph/rig.h"
#include "posemorph/rig_format.h"
#include "posemorph/span.h"

namespace posemorph {

// One character's machine: its inputs and each layer's state. A plain
// value of fixed size (about 1.1 KB); any bytes in it are defined.
struct MachineInstance {
  double values[2 * format::kMaxMachineInputs] = {};   // per input: bool 0/1, number, point x and y
  std::uint8_t fired[format::kMaxMachineInputs] = {};  // triggers fired since the last step
  std::uint32_t state[format::kMaxChannels] = {};      // per layer: the state it is in (index in the machine)
  std::uint8_t started = 0;  // nonzero: the layers have entered their initial states (a byte: any value reads)
};

// Inputs at their defaults, no trigger fired, not started (the next step
// enters the initial states, cutting). False when the rig has no machine.
PM_API bool MachineReset(const Rig& rig, MachineInstance* machine);
// Set an input by its index (Rig::FindMachineInput); false, changing
// nothing, for an index out of range or an input of another type. A
// non-finite number is taken as 0; a point is kept as given (WeightsJob
// takes any point).
PM_API bool MachineSetBool(const Rig& rig, MachineInstance* machine, std::uint32_t input, bool value);
PM_API bool MachineSetNumber(const Rig& rig, MachineInstance* machine, std::uint32_t input, double value);
PM_API bool MachineSetPoint(const Rig& rig, MachineInstance* machine, std::uint32_t input, double x, double y);
PM_API bool MachineFire(const Rig& rig, MachineInstance* machine, std::uint32_t input);

// A layer's change of state in a step.
struct MachineChange {
  std::uint32_t character = 0;
  std::uint32_t layer = 0;
  std::uint32_t from = 0, to = 0;  // state indices (equal when a layer starts)
};

// Steps `count` characters' machines and issues their commands to their
// tracks (count x rig.channel_count(), as AnimatorUpdateJob reads them).
// Validate() fails (and Run() does nothing) when: rig is null, not loaded or
// has no machine; count is above kMaxAnimatorBatch; machines holds fewer
// than count or tracks fewer than count x C; change_count or
// changes_missed is null while `changes` is given.
struct PM_API MachineStepJob {
  const Rig* rig = nullptr;
  std::size_t count = 1;
  Span<MachineInstance> machines;
  Span<AnimatorTrack> tracks;
  Span<MachineChange> changes;              // optional
  std::size_t* change_count = nullptr;      // written: changes written
  std::uint64_t* changes_missed = nullptr;  // written: changes that did not fit

  bool Validate() const;
  bool Run() const;
};

}  // namespace posemorph
