// SPDX-License-Identifier: MIT
// The state machine's step (posemorph/state_machine.h).
#include "posemorph/state_machine.h"

#include <cmath>

#include "machine_colour.h"
#include "posemorph/path.h"

namespace posemorph {
namespace {

bool HasMachine(const Rig& rig) { return rig.loaded() && rig.machine_layers().size > 0; }

bool InputOf(const Rig& rig, std::uint32_t input, MachineInputType type) {
  return HasMachine(rig) && input < rig.machine_inputs().size && rig.machine_inputs()[input].type == type;
}

bool Holds(const MachineInstance& m, const MachineInputView& input, std::uint32_t i, const MachineConditionView& c) {
  const bool truth = input.type == MachineInputType::kTrigger ? m.fired[i] != 0 : m.values[2 * i] != 0;
  const double v = m.values[2 * i];
  switch (c.op) {
    case MachineOp::kIsTrue:
      return truth;
    case MachineOp::kIsFalse:
      return !truth;
    case MachineOp::kEqual:
      return v == c.value;
    case MachineOp::kNotEqual:
      return v != c.value;
    case MachineOp::kLess:
      return v < c.value;
    case MachineOp::kLessEqual:
      return v <= c.value;
    case MachineOp::kGreater:
      return v > c.value;
    case MachineOp::kGreaterEqual:
      return v >= c.value;
  }
  return false;
}

// How far the track's path has played in its cycle (1 when it ended), for
// a state that plays `path`; 0 while the track shows something else.
double Progress(const Rig& crig, const AnimatorTrack& t, std::uint32_t path) {
  const Motion& m = t.has_pending ? t.pending : t.current;
  if (m.kind != MotionKind::kPath || m.path != path || path >= crig.path_count()) return 0;
  if (m.ended) return 1;
  const PathView p = crig.path(path);
  const double length = p.end_time() - p.start_time();
  if (!(length > 0)) return 1;
  const double u = (m.time - p.start_time()) / length;
  return u >= 0 ? (u <= 1 ? u : 1) : 0;
}

bool Allowed(const Rig& rig, const MachineInstance& m, const MachineTransitionView& t, const Rig& crig,
             const AnimatorTrack& track, const MachineStateView& from) {
  for (const MachineConditionView& c : t.conditions)
    if (!Holds(m, rig.machine_inputs()[c.input], c.input, c)) return false;
  return !t.has_exit_time || Progress(crig, track, from.path) >= t.exit_time;
}

// The point a pad or blend state shows now.
void StatePoint(const Rig& crig, const MachineInstance& m, const MachineStateView& s, double* x, double* y) {
  if (s.kind == MachineStateKind::kPad) {
    *x = m.values[2 * s.input], *y = m.values[2 * s.input + 1];
    return;
  }
  const PathView p = crig.path(s.path);
  double u = m.values[2 * s.input];
  u = u >= 0 ? (u <= 1 ? u : 1) : 0;  // NaN -> 0
  SamplePath(crig, s.path, p.start_time() + u * (p.end_time() - p.start_time()), x, y);
}

// The commands that enter state `s` over `mix` seconds.
void Enter(const Rig& rig, Span<AnimatorTrack> tracks, const MachineInstance& m, const MachineStateView& s,
           double mix) {
  const std::uint32_t channel = rig.machine_layers()[s.layer].channel;
  const Rig& crig = *rig.channel_rig(channel);
  switch (s.kind) {
    case MachineStateKind::kStop:
      AnimatorStop(rig, tracks, channel, mix);
      return;
    case MachineStateKind::kPlay: {
      PlayOptions o;
      o.speed = s.speed, o.loop = s.loop, o.mix = mix, o.start = 0;
      AnimatorPlay(rig, tracks, channel, s.path, o);
      return;
    }
    case MachineStateKind::kPad:
    case MachineStateKind::kBlend: {
      // Always a hand-over (AnimatorSetPoint would move a track already on
      // a point at once): a pad after a blend mixes too.
      double x = 0, y = 0;
      StatePoint(crig, m, s, &x, &y);
      AnimatorStop(rig, tracks, channel, mix);  // clears the queue, sets the mix
      AnimatorTrack& t = tracks[channel];
      t.pending = Motion{};
      t.pending.kind = MotionKind::kPoint;
      t.pending.x = x, t.pending.y = y;
      return;
    }
  }
}

// A pad or blend state keeps following its input.
void Sustain(const Rig& rig, Span<AnimatorTrack> tracks, const MachineInstance& m, const MachineStateView& s) {
  if (s.kind != MachineStateKind::kPad && s.kind != MachineStateKind::kBlend) return;
  const std::uint32_t channel = rig.machine_layers()[s.layer].channel;
  double x = 0, y = 0;
  StatePoint(*rig.channel_rig(channel), m, s, &x, &y);
  AnimatorSetPoint(rig, tracks, channel, x, y, 0);
}

// The layer's declared behaviours, put on its channel's track.
void StartBehaviours(const Rig& rig, Span<AnimatorTrack> tracks, const MachineLayerView& layer, std::size_t character) {
  const MachineBehavioursView& v = layer.behaviours;
  if (!v.blink && !v.breath && !v.look_at && !v.spring) return;
  Behaviours b;
  b.blink.enabled = v.blink, b.blink.pose = v.blink_pose, b.blink.interval = v.blink_interval;
  b.blink.jitter = v.blink_jitter, b.blink.duration = v.blink_duration, b.blink.strength = v.blink_strength;
  b.blink.seed = v.blink_seed + character;
  b.breath.enabled = v.breath, b.breath.period = v.breath_period, b.breath.x = v.breath_x, b.breath.y = v.breath_y;
  b.look_at.enabled = v.look_at, b.look_at.smoothing = v.look_smoothing, b.look_at.strength = v.look_strength;
  b.spring.enabled = v.spring, b.spring.frequency = v.spring_frequency, b.spring.damping = v.spring_damping;
  b.spring.strength = v.spring_strength;
  const AnimatorTrack& t = tracks[layer.channel];
  b.look_at.x = t.behaviours.look_at.x, b.look_at.y = t.behaviours.look_at.y;
  AnimatorSetBehaviours(rig, tracks, layer.channel, b);
}

}  // namespace

bool MachineReset(const Rig& rig, MachineInstance* machine) {
  if (!HasMachine(rig) || !machine) return false;
  *machine = MachineInstance{};
  for (float& p : machine->part_from) p = 1;
  for (std::size_t i = 0; i < rig.machine_inputs().size; ++i) {
    machine->values[2 * i] = rig.machine_inputs()[i].default_x;
    machine->values[2 * i + 1] = rig.machine_inputs()[i].default_y;
  }
  return true;
}

bool MachineSetBool(const Rig& rig, MachineInstance* machine, std::uint32_t input, bool value) {
  if (!machine || !InputOf(rig, input, MachineInputType::kBool)) return false;
  machine->values[2 * input] = value ? 1 : 0;
  return true;
}

bool MachineSetNumber(const Rig& rig, MachineInstance* machine, std::uint32_t input, double value) {
  if (!machine || !InputOf(rig, input, MachineInputType::kNumber)) return false;
  machine->values[2 * input] = std::isfinite(value) ? value : 0;
  return true;
}

bool MachineSetPoint(const Rig& rig, MachineInstance* machine, std::uint32_t input, double x, double y) {
  if (!machine || !InputOf(rig, input, MachineInputType::kPoint)) return false;
  machine->values[2 * input] = x, machine->values[2 * input + 1] = y;
  return true;
}

bool MachineFire(const Rig& rig, MachineInstance* machine, std::uint32_t input) {
  if (!machine || !InputOf(rig, input, MachineInputType::kTrigger)) return false;
  machine->fired[input] = 1;
  return true;
}

bool MachineStepJob::Validate() const {
  if (!rig || !HasMachine(*rig) || count > kMaxAnimatorBatch) return false;
  if (!machines.data || machines.size < count) return false;
  if (!tracks.data || tracks.size < count * rig->channel_count()) return false;
  if (!changes.empty() && (!changes.data || !change_count || !changes_missed)) return false;
  return true;
}

bool MachineStepJob::Run() const {
  if (!Validate()) return false;
  const std::uint32_t C = rig->channel_count();
  const Span<const MachineLayerView> layers = rig->machine_layers();
  const Span<const MachineStateView> states = rig->machine_states();
  std::size_t written = 0;
  std::uint64_t missed = 0;
  auto report = [&](std::size_t i, std::uint32_t l, std::uint32_t from, std::uint32_t to) {
    if (changes.empty()) return;
    if (written < changes.size)
      changes[written++] = MachineChange{std::uint32_t(i), l, from, to};
    else if (missed < ~std::uint64_t(0))
      ++missed;
  };
  for (std::size_t i = 0; i < count; ++i) {
    MachineInstance& m = machines[i];
    const Span<AnimatorTrack> t{tracks.data + i * C, C};
    bool faded = false, started = false;  // a colour fade began this step; a layer entered its initial state
    for (std::uint32_t l = 0; l < layers.size; ++l) {
      const MachineLayerView& layer = layers[l];
      const std::uint32_t now = m.state[l];
      const bool inside = now >= layer.first_state && now < layer.first_state + layer.state_count;
      const bool starting = !m.started || !inside;
      if (starting) StartBehaviours(*rig, t, layer, i);
      if (layer.behaviours.look_at && layer.behaviours.look_input >= 0) {
        const std::uint32_t in = std::uint32_t(layer.behaviours.look_input);
        AnimatorLookAt(*rig, t, layer.channel, m.values[2 * in], m.values[2 * in + 1]);
      }
      if (starting) {
        m.state[l] = layer.initial;
        started = true;
        Enter(*rig, t, m, states[layer.initial], 0);
        report(i, l, layer.initial, layer.initial);
        continue;
      }
      const MachineStateView& s = states[now];
      const Rig& crig = *rig->channel_rig(layer.channel);
      const MachineTransitionView* taken = nullptr;
      // An any-state transition does not re-enter the state it leads to.
      for (const MachineTransitionView& tr : layer.any)
        if (!taken && tr.to != now && Allowed(*rig, m, tr, crig, t[layer.channel], s)) taken = &tr;
      for (const MachineTransitionView& tr : s.transitions)
        if (!taken && Allowed(*rig, m, tr, crig, t[layer.channel], s)) taken = &tr;
      if (!taken) {
        Sustain(*rig, t, m, s);
        continue;
      }
      detail::StartFade(*rig, m, taken->mix, !faded);  // from the colour shown before the change
      faded = true;
      m.state[l] = taken->to;
      Enter(*rig, t, m, states[taken->to], taken->mix);
      report(i, l, now, taken->to);
    }
    if (started && !faded) detail::SettleFade(*rig, m);  // a start shows its states' colour at once
    m.started = 1;
    for (std::uint8_t& f : m.fired) f = 0;
  }
  if (change_count) *change_count = written;
  if (changes_missed) *changes_missed = missed;
  return true;
}

}  // namespace posemorph
