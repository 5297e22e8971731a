// SPDX-License-Identifier: MIT
// The state machine's records (MACH, format 1.9; colours 1.10): its
// header, inputs, layers, states, transitions, conditions, the layers'
// behaviours and the states' colours, defined once for the bake's writer
// and the loader (record_codec.h).
#pragma once
#include <cstddef>
#include <cstdint>

#include "posemorph/format/record_codec.h"

namespace posemorph::format {

// MACH (1.9): a state machine (rig_format.h, kMachine): this header, then
// the inputs', layers', states', transitions' and conditions' entries, the
// layers' behaviours, the states' colours (1.10), then the inputs' and the
// states' names. Ranges are implied: a layer's states
// follow the previous layer's; the transitions are, layer by layer, the
// layer's any-state transitions then each of its states' in order; a
// transition's conditions follow the previous transition's.
struct MachineHeader {
  static constexpr std::uint32_t kSize = 24;
  std::uint32_t input_count;
  std::uint32_t layer_count;
  std::uint32_t state_count;
  std::uint32_t transition_count;
  std::uint32_t condition_count;
  std::uint32_t colour_count;  // 1.10: MachineColourEntry records after the behaviours (before: zero)
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.input_count), f(r.layer_count), f(r.state_count), f(r.transition_count), f(r.condition_count),
        f(r.colour_count);
  }
};
struct MachineInputEntry {
  static constexpr std::uint32_t kSize = 24;
  std::uint32_t type;  // MachineInputType (rig.h)
  std::uint32_t reserved;
  double default_x;  // bool: 0 or 1; number: its value; point: x
  double default_y;  // point: y; otherwise 0
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.type), f(r.reserved), f(r.default_x), f(r.default_y);
  }
};
struct MachineLayerEntry {
  static constexpr std::uint32_t kSize = 16;
  std::uint32_t channel;
  std::uint32_t state_count;  // 1 or more
  std::uint32_t initial;      // within the layer's states
  std::uint32_t any_count;    // transitions from any state of the layer
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.channel), f(r.state_count), f(r.initial), f(r.any_count);
  }
};
struct MachineStateEntry {
  static constexpr std::uint32_t kSize = 32;
  std::uint32_t kind;   // MachineStateKind (rig.h)
  std::uint32_t path;   // play, blend: in the layer's channel; otherwise 0
  std::uint32_t input;  // pad: a point input; blend: a number input; otherwise 0
  std::uint32_t flags;  // play: bit 0 loop given, bit 1 loop
  double speed;         // play: path seconds per second; otherwise 1
  std::uint32_t transition_count;
  std::uint32_t reserved;
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.kind), f(r.path), f(r.input), f(r.flags), f(r.speed), f(r.transition_count), f(r.reserved);
  }
};
struct MachineTransitionEntry {
  static constexpr std::uint32_t kSize = 32;
  std::uint32_t to;  // a state of the same layer (its index in the machine)
  std::uint32_t condition_count;
  std::uint32_t flags;  // bit 0: exit_time holds
  std::uint32_t reserved;
  double mix;        // seconds of crossfade
  double exit_time;  // of the state's path, 0..1 (bit 0)
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.to), f(r.condition_count), f(r.flags), f(r.reserved), f(r.mix), f(r.exit_time);
  }
};
struct MachineConditionEntry {
  static constexpr std::uint32_t kSize = 16;
  std::uint32_t input;
  std::uint32_t op;  // MachineOp (rig.h)
  double value;
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.input), f(r.op), f(r.value);
  }
};

// One per layer, after the conditions: the behaviours the layer's channel
// runs from the machine's first step (animator.h, Behaviours).
struct MachineBehavioursEntry {
  static constexpr std::uint32_t kSize = 120;
  std::uint32_t enabled;  // 1 blink, 2 breath, 4 look-at, 8 spring
  std::uint32_t blink_pose;
  double blink_interval, blink_jitter, blink_duration, blink_strength;
  std::uint64_t blink_seed;  // plus the character's index in its batch
  double breath_period, breath_x, breath_y;
  std::uint32_t look_input;  // a point input the look-at target follows, or 0xFFFFFFFF
  std::uint32_t reserved;
  double look_smoothing, look_strength;
  double spring_frequency, spring_damping, spring_strength;
  template <typename Self, typename F>
  static constexpr void Fields(Self& r, F& f) {
    f(r.enabled), f(r.blink_pose), f(r.blink_interval), f(r.blink_jitter), f(r.blink_duration), f(r.blink_strength),
        f(r.blink_seed), f(r.breath_period), f(r.breath_x), f(r.breath_y), f(r.look_input), f(r.reserved),
        f(r.look_smoothing), f(r.look_strength), f(r.spring_frequency), f(r.spring_damping), f(r.spring_strength);
  }
};

// 1.10: what a state sets on the character while its layer is in it
// (state_machine.h: MachineColourJob), after the behaviours: a tint and
// opacity (part 0xFFFFFFFF) or one body part's opacity (r, g, b are 1),
// each component in [0, 1]. Sorted by state, then part; at most one per
// (state, part); a state without one leaves the character (or the part)
// as drawn.
struct MachineColourEntry {
  static constexpr std::uint32_t kSize = 40;
  static constexpr std::uint32_t kCharacter = 0xFFFFFFFFu;
  std::uint32_t state;
  std::uint32_t part;  // of the top-level rig (Rig::part), or kCharacter
  double r, g, b, a;
  template <typename Self, typename F>
  static constexpr void Fields(Self& r_, F& f) {
    f(r_.state), f(r_.part), f(r_.r), f(r_.g), f(r_.b), f(r_.a);
  }
};

PM_FORMAT_RECORD(MachineHeader);
PM_FORMAT_FIELD(MachineHeader, colour_count, 20);
PM_FORMAT_RECORD(MachineInputEntry);
PM_FORMAT_FIELD(MachineInputEntry, default_x, 8);
PM_FORMAT_RECORD(MachineLayerEntry);
PM_FORMAT_FIELD(MachineLayerEntry, any_count, 12);
PM_FORMAT_RECORD(MachineStateEntry);
PM_FORMAT_FIELD(MachineStateEntry, speed, 16);
PM_FORMAT_FIELD(MachineStateEntry, reserved, 28);
PM_FORMAT_RECORD(MachineTransitionEntry);
PM_FORMAT_FIELD(MachineTransitionEntry, mix, 16);
PM_FORMAT_FIELD(MachineTransitionEntry, exit_time, 24);
PM_FORMAT_RECORD(MachineConditionEntry);
PM_FORMAT_FIELD(MachineConditionEntry, value, 8);
PM_FORMAT_RECORD(MachineBehavioursEntry);
PM_FORMAT_FIELD(MachineBehavioursEntry, blink_seed, 40);
PM_FORMAT_FIELD(MachineBehavioursEntry, look_input, 72);
PM_FORMAT_FIELD(MachineBehavioursEntry, spring_strength, 112);
PM_FORMAT_RECORD(MachineColourEntry);
PM_FORMAT_FIELD(MachineColourEntry, r, 8);
PM_FORMAT_FIELD(MachineColourEntry, a, 32);

}  // namespace posemorph::format
