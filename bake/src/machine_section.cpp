// SPDX-License-Identifier: MIT
#include "posemorph/bake/machine_section.h"

#include <array>

#include "posemorph/rig_format.h"
#include "rig_writer.h"

namespace posemorph::bake {

namespace fmt = format;

std::vector<unsigned char> MachineSection(const StateMachineDescription& m) {
  std::vector<unsigned char> out;
  if (m.layers.empty()) return out;
  fmt::MachineHeader header{};
  header.input_count = std::uint32_t(m.inputs.size());
  header.layer_count = std::uint32_t(m.layers.size());
  for (const MachineLayerDescription& layer : m.layers) {
    header.state_count += std::uint32_t(layer.states.size());
    header.transition_count += std::uint32_t(layer.transitions.size());
    for (const MachineTransitionDescription& t : layer.transitions)
      header.condition_count += std::uint32_t(t.when.size());
  }
  for (const MachineLayerDescription& layer : m.layers)
    for (const MachineStateDescription& s : layer.states)
      header.colour_count += std::uint32_t(s.part_opacities.size()) + (s.colour != std::array<double, 4>{1, 1, 1, 1});
  AppendRecord(out, header);
  for (const MachineInputDescription& in : m.inputs) {
    fmt::MachineInputEntry e{};
    e.type = std::uint32_t(in.type);
    e.default_x = in.default_x, e.default_y = in.default_y;
    AppendRecord(out, e);
  }
  // A layer's transitions in the file: its any-state ones, then each
  // state's, each group in the description's order.
  auto from = [](const MachineLayerDescription& layer, bool any, std::uint32_t state) {
    std::vector<const MachineTransitionDescription*> picked;
    for (const MachineTransitionDescription& t : layer.transitions)
      if (t.any == any && (any || t.from == state)) picked.push_back(&t);
    return picked;
  };
  for (const MachineLayerDescription& layer : m.layers) {
    fmt::MachineLayerEntry e{};
    e.channel = layer.channel;
    e.state_count = std::uint32_t(layer.states.size());
    e.initial = layer.initial;
    e.any_count = std::uint32_t(from(layer, true, 0).size());
    AppendRecord(out, e);
  }
  std::uint32_t first_state = 0;
  std::vector<const MachineTransitionDescription*> order;
  std::vector<std::uint32_t> order_first;  // the first state of each transition's layer
  for (const MachineLayerDescription& layer : m.layers) {
    for (const MachineTransitionDescription* t : from(layer, true, 0))
      order.push_back(t), order_first.push_back(first_state);
    for (std::uint32_t i = 0; i < layer.states.size(); ++i) {
      const MachineStateDescription& s = layer.states[i];
      const auto own = from(layer, false, i);
      fmt::MachineStateEntry e{};
      e.kind = std::uint32_t(s.kind);
      e.path = s.kind == MachineStateKind::kPlay || s.kind == MachineStateKind::kBlend ? s.path : 0;
      e.input = s.kind == MachineStateKind::kPad || s.kind == MachineStateKind::kBlend ? s.input : 0;
      e.flags = s.kind == MachineStateKind::kPlay && s.loop >= 0
                    ? fmt::kMachineStateLoopGiven | (s.loop ? fmt::kMachineStateLoop : 0u)
                    : 0u;
      e.speed = s.kind == MachineStateKind::kPlay ? s.speed : 1.0;
      e.transition_count = std::uint32_t(own.size());
      AppendRecord(out, e);
      for (const MachineTransitionDescription* t : own) order.push_back(t), order_first.push_back(first_state);
    }
    first_state += std::uint32_t(layer.states.size());
  }
  for (std::size_t k = 0; k < order.size(); ++k) {
    const MachineTransitionDescription& t = *order[k];
    fmt::MachineTransitionEntry e{};
    e.to = order_first[k] + t.to;
    e.condition_count = std::uint32_t(t.when.size());
    e.flags = t.has_exit_time ? fmt::kMachineTransitionExitTime : 0u;
    e.mix = t.mix;
    e.exit_time = t.has_exit_time ? t.exit_time : 0.0;
    AppendRecord(out, e);
  }
  for (const MachineTransitionDescription* t : order)
    for (const MachineConditionDescription& c : t->when) {
      fmt::MachineConditionEntry e{};
      e.input = c.input;
      e.op = std::uint32_t(c.op);
      e.value = c.op == MachineOp::kIsTrue || c.op == MachineOp::kIsFalse ? 0.0 : c.value;
      AppendRecord(out, e);
    }
  for (const MachineLayerDescription& layer : m.layers) {
    const MachineBehavioursView& b = layer.behaviours;
    fmt::MachineBehavioursEntry e{};
    e.enabled = (b.blink ? 1u : 0u) | (b.breath ? 2u : 0u) | (b.look_at ? 4u : 0u) | (b.spring ? 8u : 0u);
    e.blink_pose = b.blink_pose;
    e.blink_interval = b.blink_interval, e.blink_jitter = b.blink_jitter, e.blink_duration = b.blink_duration;
    e.blink_strength = b.blink_strength, e.blink_seed = b.blink_seed;
    e.breath_period = b.breath_period, e.breath_x = b.breath_x, e.breath_y = b.breath_y;
    e.look_input = b.look_input < 0 ? 0xFFFFFFFFu : std::uint32_t(b.look_input);
    e.look_smoothing = b.look_smoothing, e.look_strength = b.look_strength;
    e.spring_frequency = b.spring_frequency, e.spring_damping = b.spring_damping;
    e.spring_strength = b.spring_strength;
    AppendRecord(out, e);
  }
  // The states' colours (1.10), by state, then part (the character's last).
  std::uint32_t state = 0;
  for (const MachineLayerDescription& layer : m.layers)
    for (const MachineStateDescription& s : layer.states) {
      for (const auto& [part, opacity] : s.part_opacities) {
        fmt::MachineColourEntry e{};
        e.state = state, e.part = part, e.r = e.g = e.b = 1, e.a = opacity;
        AppendRecord(out, e);
      }
      if (s.colour != std::array<double, 4>{1, 1, 1, 1}) {
        fmt::MachineColourEntry e{};
        e.state = state, e.part = fmt::MachineColourEntry::kCharacter;
        e.r = s.colour[0], e.g = s.colour[1], e.b = s.colour[2], e.a = s.colour[3];
        AppendRecord(out, e);
      }
      ++state;
    }
  for (const MachineInputDescription& in : m.inputs) AppendString(out, in.name);
  for (const MachineLayerDescription& layer : m.layers)
    for (const MachineStateDescription& s : layer.states) AppendString(out, s.name);
  return out;
}

}  // namespace posemorph::bake
