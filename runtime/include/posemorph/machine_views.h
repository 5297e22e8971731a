// SPDX-License-Identifier: MIT
// What a rig's state machine holds, as Rig::machine_inputs, machine_layers
// and machine_states give it (format 1.9, colours 1.10): views into the
// rig's arena, valid while the rig is.
#pragma once
#include <cstddef>
#include <cstdint>

#include "posemorph/span.h"

namespace posemorph {

// A state machine (format 1.9; RIG_DESCRIPTION.md, "state_machine";
// posemorph/state_machine.h runs it): named inputs; per channel a layer of
// states, each playing a path, following a point input (a pad), blending
// along a path by a number input, or stopped; transitions between a
// layer's states on conditions, with a crossfade and an optional exit time.
enum class MachineInputType : std::uint32_t { kBool = 0, kNumber = 1, kTrigger = 2, kPoint = 3 };
struct MachineInputView {
  StringView name;
  MachineInputType type = MachineInputType::kBool;
  double default_x = 0, default_y = 0;  // bool 0/1, number, point x and y
};
// kIsTrue / kIsFalse: a bool's value, or whether a trigger fired since the
// last step; the comparisons: a number's value against `value`.
enum class MachineOp : std::uint32_t {
  kIsTrue = 0,
  kIsFalse = 1,
  kEqual = 2,
  kNotEqual = 3,
  kLess = 4,
  kLessEqual = 5,
  kGreater = 6,
  kGreaterEqual = 7,
};
struct MachineConditionView {
  std::uint32_t input = 0;
  MachineOp op = MachineOp::kIsTrue;
  double value = 0;
};
struct MachineTransitionView {
  std::uint32_t to = 0;                         // a state of the same layer
  Span<const MachineConditionView> conditions;  // all hold
  double mix = 0;                               // seconds of crossfade
  bool has_exit_time = false;
  double exit_time = 0;  // the state's path has played this share of its cycle (or ended)
};
enum class MachineStateKind : std::uint32_t { kStop = 0, kPlay = 1, kPad = 2, kBlend = 3 };
// A body part's opacity while a state holds (format 1.10).
struct MachinePartOpacityView {
  std::uint32_t part = 0;  // Rig::part
  float opacity = 1;       // [0, 1]
};
struct MachineStateView {
  StringView name;
  std::uint32_t layer = 0;
  MachineStateKind kind = MachineStateKind::kStop;
  std::uint32_t path = 0;                         // play, blend: in the layer's channel's rig
  std::uint32_t input = 0;                        // pad: a point input; blend: a number input (0..1 along the path)
  int loop = -1;                                  // play: -1 as the path says, 0 once, 1 looped
  double speed = 1;                               // play
  Span<const MachineTransitionView> transitions;  // in priority order
  // Format 1.10: what the state sets while its layer is in it (each
  // layer's multiply; MachineColourJob fades between them): the
  // character's tint and opacity (r, g, b, a; all 1: as drawn) and body
  // parts' opacities (by part, ascending; a part not listed: 1).
  float colour[4] = {1, 1, 1, 1};
  Span<const MachinePartOpacityView> part_opacities;
};
// The behaviours a layer's channel runs from the machine's first step
// (animator.h: BlinkBehaviour ... SpringBehaviour; state_machine.h applies
// them, the blink seeded with `blink_seed` plus the character's index).
struct MachineBehavioursView {
  bool blink = false, breath = false, look_at = false, spring = false;
  std::uint32_t blink_pose = 0;
  double blink_interval = 4, blink_jitter = 0.5, blink_duration = 0.15, blink_strength = 1;
  std::uint64_t blink_seed = 1;
  double breath_period = 3.5, breath_x = 0, breath_y = 0;
  int look_input = -1;  // the point input the look-at target follows each step; -1: code sets it
  double look_smoothing = 0.1, look_strength = 1;
  double spring_frequency = 2.5, spring_damping = 0.3, spring_strength = 1;
};
struct MachineLayerView {
  MachineBehavioursView behaviours;
  std::uint32_t channel = 0;
  std::uint32_t first_state = 0, state_count = 0;
  std::uint32_t initial = 0;              // a state index in the machine
  Span<const MachineTransitionView> any;  // from any of its states, tried first
};

}  // namespace posemorph
