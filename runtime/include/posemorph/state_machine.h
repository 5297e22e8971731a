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
#include "posemorph/draw_list.h"
#include "posemorph/rig.h"
#include "posemorph/rig_format.h"
#include "posemorph/span.h"

namespace posemorph {

// One character's machine: its inputs and each layer's state. A plain
// value of fixed size (about 1.4 KB); any bytes in it are defined.
struct MachineInstance {
  double values[2 * format::kMaxMachineInputs] = {};   // per input: bool 0/1, number, point x and y
  std::uint8_t fired[format::kMaxMachineInputs] = {};  // triggers fired since the last step
  std::uint32_t state[format::kMaxChannels] = {};      // per layer: the state it is in (index in the machine)
  std::uint8_t started = 0;  // nonzero: the layers have entered their initial states (a byte: any value reads)
  // The colour fade (format 1.10, MachineColourJob): the colour and body
  // parts' opacities shown when the last change of state began, and how
  // far the fade to the states' own has come.
  float colour_from[4] = {1, 1, 1, 1};
  float part_from[format::kMaxParts] = {};
  double fade_elapsed = 0, fade_duration = 0;
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
// A step that changes a layer's state starts a fade of the character's
// colour (see MachineColourJob) over the transition's mix (the longest, when
// several layers change in one step) from the colour shown then.
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

// The colour the machines' states set (format 1.10: a state's "colour",
// "opacity" and "parts"): the target of a character is the product over its
// layers of each one's state colour (tint and opacity) and, per body part,
// of their part opacities (1 where a state gives none). A change of state
// fades linearly from the colour shown at that moment to the new target
// over the transition's mix; a change mid-fade starts from where the fade
// was, so the colour never jumps (a mix of 0 cuts). Run it after the step,
// with the update's dt: it advances each fade by dt and writes each
// character's colour (DrawListJob::colours) and, for a rig with parts, its
// body parts' opacities (DrawListJob::part_opacities, count x
// rig.part_count()). Multiply them with a colour of the game's own as it
// likes. Deterministic, allocation free, and defined for any bytes in a
// MachineInstance (a non-finite or out-of-range component reads as 1, a
// non-finite fade as finished). dt as AnimatorUpdateJob takes it.
//
// Validate() fails (and Run() does nothing) when: rig is null, not loaded
// or has no machine; count is above kMaxAnimatorBatch; machines holds
// fewer than count; colours is given but shorter than count;
// part_opacities is given but shorter than count x rig.part_count() or the
// rig has no parts.
struct PM_API MachineColourJob {
  const Rig* rig = nullptr;
  std::size_t count = 1;
  double dt = 0;
  Span<MachineInstance> machines;
  Span<Colour> colours;        // optional: count
  Span<float> part_opacities;  // optional: count x rig->part_count()

  bool Validate() const;
  bool Run() const;
};

}  // namespace posemorph
