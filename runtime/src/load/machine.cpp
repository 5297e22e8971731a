// SPDX-License-Identifier: MIT
// MACH (format 1.9): a state machine's entries and names, checked before
// the arena is laid out (counts, ranges implied by the counts, kinds,
// input types, conditions that can be evaluated, transitions within their
// layer); their views in the arena; the paths the states name, once every
// channel's rig is loaded.
#include "loader.h"

#include <cmath>
#include <cstring>
#include <initializer_list>

namespace posemorph {

using namespace detail::load;  // NOLINT(google-build-using-namespace): the loader's own types

namespace {

constexpr double kMaxMachineValue = 1e9;

bool Finite(double v, double bound) { return std::fabs(v) <= bound; }

// One transition: its target in [first, first + count) of its layer, its
// conditions at `*condition` onward (advanced past them).
bool CheckTransition(const fmt::MachineTransitionEntry& t, std::uint32_t index, std::uint32_t first,
                     std::uint32_t count, bool from_play, const Machine& m, std::uint64_t* condition, Error* err) {
  if (t.to < first || t.to >= first + count)
    return Fail(err, ErrorCode::kBadValue, "MACH transition %u: target state %u is not in its layer (%u..%u)", index,
                t.to, first, first + count - 1);
  if ((t.flags & ~fmt::kMachineTransitionExitTime) || t.reserved)
    return Fail(err, ErrorCode::kBadLayout, "MACH transition %u: unknown flags or reserved bits", index);
  if (!(t.mix >= 0 && t.mix <= 1e6))
    return Fail(err, ErrorCode::kBadValue, "MACH transition %u: mix %g outside 0..1e6", index, t.mix);
  const bool exit = (t.flags & fmt::kMachineTransitionExitTime) != 0;
  if (exit ? !(t.exit_time >= 0 && t.exit_time <= 1) : t.exit_time != 0)
    return Fail(err, ErrorCode::kBadValue, "MACH transition %u: exit time %g outside 0..1 (or given without its flag)",
                index, t.exit_time);
  if (exit && !from_play)
    return Fail(err, ErrorCode::kBadValue, "MACH transition %u: an exit time on a state that plays no path", index);
  if (!exit && t.condition_count == 0)
    return Fail(err, ErrorCode::kBadValue, "MACH transition %u: no condition and no exit time: it always fires", index);
  if (t.condition_count > m.h.condition_count - *condition)
    return Fail(err, ErrorCode::kBadLayout, "MACH transition %u: its conditions run past the %u there are", index,
                m.h.condition_count);
  for (std::uint32_t k = 0; k < t.condition_count; ++k, ++*condition) {
    const auto c = fmt::DecodeEntry<fmt::MachineConditionEntry>(m.conditions, *condition);
    if (c.input >= m.h.input_count)
      return Fail(err, ErrorCode::kBadValue, "MACH condition %llu: input %u of %u", (unsigned long long)*condition,
                  c.input, m.h.input_count);
    const auto type = MachineInputType(fmt::DecodeEntry<fmt::MachineInputEntry>(m.inputs, c.input).type);
    const bool truth = c.op == std::uint32_t(MachineOp::kIsTrue) || c.op == std::uint32_t(MachineOp::kIsFalse);
    const bool compare = c.op >= std::uint32_t(MachineOp::kEqual) && c.op <= std::uint32_t(MachineOp::kGreaterEqual);
    const bool fits = type == MachineInputType::kNumber
                          ? compare
                          : (type == MachineInputType::kBool || type == MachineInputType::kTrigger) && truth;
    if (!fits)
      return Fail(err, ErrorCode::kBadValue, "MACH condition %llu: operator %u does not apply to input %u's type %u",
                  (unsigned long long)*condition, c.op, c.input, std::uint32_t(type));
    if (!Finite(c.value, kMaxMachineValue) || (truth && c.value != 0))
      return Fail(err, ErrorCode::kBadValue, "MACH condition %llu: value %g", (unsigned long long)*condition, c.value);
  }
  return true;
}

}  // namespace

bool RigLoader::ReadMachine(const unsigned char* bytes, const Parser& parser, bool nested, std::uint32_t channel_count,
                            Machine* m, Error* err) {
  const Section* section = parser.table.Find(fmt::kMachine);
  if (!section) return true;
  if (nested) return Fail(err, ErrorCode::kBadLayout, "an attachment's rig has a MACH section of its own");
  const unsigned char* p = bytes + section->offset;
  const std::uint64_t size = section->size;
  if (size < fmt::MachineHeader::kSize)
    return Fail(err, ErrorCode::kBadLayout, "MACH section of %llu bytes is shorter than its header",
                (unsigned long long)size);
  m->h = fmt::DecodeRecord<fmt::MachineHeader>(p);
  const fmt::MachineHeader& h = m->h;
  if (h.input_count > fmt::kMaxMachineInputs || h.layer_count < 1 || h.layer_count > channel_count ||
      h.state_count < h.layer_count || h.state_count > fmt::kMaxMachineStates ||
      h.transition_count > fmt::kMaxMachineTransitions || h.condition_count > fmt::kMaxMachineConditions)
    return Fail(
        err, ErrorCode::kBadValue,
        "MACH counts outside their limits: %u inputs (0..%u), %u layers (1..%u channels), %u states (layers..%u), "
        "%u transitions (..%u), %u conditions (..%u)",
        h.input_count, fmt::kMaxMachineInputs, h.layer_count, channel_count, h.state_count, fmt::kMaxMachineStates,
        h.transition_count, fmt::kMaxMachineTransitions, h.condition_count, fmt::kMaxMachineConditions);
  if (h.colour_count > h.state_count * (fmt::kMaxParts + 1))
    return Fail(err, ErrorCode::kBadValue, "MACH: %u colours for %u states, above one per state and part",
                h.colour_count, h.state_count);
  std::uint64_t at = fmt::MachineHeader::kSize;
  auto take = [&](std::uint64_t count, std::uint32_t entry) {
    const unsigned char* q = p + at;
    at += count * entry;
    return q;
  };
  m->inputs = take(h.input_count, fmt::MachineInputEntry::kSize);
  m->layers = take(h.layer_count, fmt::MachineLayerEntry::kSize);
  m->states = take(h.state_count, fmt::MachineStateEntry::kSize);
  m->transitions = take(h.transition_count, fmt::MachineTransitionEntry::kSize);
  m->conditions = take(h.condition_count, fmt::MachineConditionEntry::kSize);
  m->behaviours = take(h.layer_count, fmt::MachineBehavioursEntry::kSize);
  m->colours = take(h.colour_count, fmt::MachineColourEntry::kSize);
  if (at > size) return Fail(err, ErrorCode::kBadLayout, "MACH's entries run past the section");
  m->names = p + at;
  for (std::uint64_t k = 0; k < std::uint64_t(h.input_count) + h.state_count; ++k) {
    if (size - at < 4) return Fail(err, ErrorCode::kBadLayout, "MACH's names run past the section");
    std::uint32_t n = 0;
    fmt::FieldDecoder{p + at}(n);
    if (n < 1 || n > fmt::kMaxMachineName || size - at - 4 < n)
      return Fail(err, ErrorCode::kBadValue, "MACH name %llu is %u bytes, outside 1..%u or past the section",
                  (unsigned long long)k, n, fmt::kMaxMachineName);
    at += 4 + n;
    m->name_bytes += n;
  }
  if (at != size)
    return Fail(err, ErrorCode::kBadLayout, "MACH has %llu trailing bytes", (unsigned long long)(size - at));
  for (std::uint32_t i = 0; i < h.input_count; ++i) {
    const auto e = fmt::DecodeEntry<fmt::MachineInputEntry>(m->inputs, i);
    const auto type = MachineInputType(e.type);
    if (e.type > std::uint32_t(MachineInputType::kPoint) || e.reserved)
      return Fail(err, ErrorCode::kBadValue, "MACH input %u: type %u", i, e.type);
    const bool truth = type == MachineInputType::kBool || type == MachineInputType::kTrigger;
    if (!Finite(e.default_x, kMaxMachineValue) || !Finite(e.default_y, kMaxMachineValue) ||
        (type != MachineInputType::kPoint && e.default_y != 0) ||
        (truth && !(e.default_x == 0 || (type == MachineInputType::kBool && e.default_x == 1))))
      return Fail(err, ErrorCode::kBadValue, "MACH input %u: default (%g, %g) does not suit its type", i, e.default_x,
                  e.default_y);
  }
  for (std::uint32_t l = 0; l < h.layer_count; ++l) {
    const auto b = fmt::DecodeEntry<fmt::MachineBehavioursEntry>(m->behaviours, l);
    const double values[] = {b.blink_interval, b.blink_jitter,     b.blink_duration, b.blink_strength,
                             b.breath_period,  b.breath_x,         b.breath_y,       b.look_smoothing,
                             b.look_strength,  b.spring_frequency, b.spring_damping, b.spring_strength};
    for (double v : values)
      if (!Finite(v, 1e6))
        return Fail(err, ErrorCode::kBadValue, "MACH layer %u's behaviours: a parameter (%g) beyond 1e6", l, v);
    if ((b.enabled & ~15u) || b.reserved)
      return Fail(err, ErrorCode::kBadValue, "MACH layer %u's behaviours: unknown bits", l);
    if (b.look_input != 0xFFFFFFFFu &&
        (b.look_input >= h.input_count ||
         MachineInputType(fmt::DecodeEntry<fmt::MachineInputEntry>(m->inputs, b.look_input).type) !=
             MachineInputType::kPoint))
      return Fail(err, ErrorCode::kBadValue, "MACH layer %u's behaviours: look-at input %u is not a point input", l,
                  b.look_input);
  }
  for (std::uint32_t k = 0; k < h.colour_count; ++k) {
    const auto c = fmt::DecodeEntry<fmt::MachineColourEntry>(m->colours, k);
    const bool part = c.part != fmt::MachineColourEntry::kCharacter;
    if (c.state >= h.state_count || (part && c.part >= fmt::kMaxParts))
      return Fail(err, ErrorCode::kBadValue, "MACH colour %u: state %u of %u, part %u", k, c.state, h.state_count,
                  c.part);
    for (double v : {c.r, c.g, c.b, c.a})
      if (!(v >= 0 && v <= 1))
        return Fail(err, ErrorCode::kBadValue, "MACH colour %u: a component (%g) outside 0..1", k, v);
    if (part && !(c.r == 1 && c.g == 1 && c.b == 1))
      return Fail(err, ErrorCode::kBadValue, "MACH colour %u: a part's tint is not 1, 1, 1 (parts set opacity)", k);
    if (k > 0) {
      const auto before = fmt::DecodeEntry<fmt::MachineColourEntry>(m->colours, k - 1);
      if (!(before.state < c.state || (before.state == c.state && before.part < c.part)))
        return Fail(err, ErrorCode::kBadLayout, "MACH colour %u: not after colour %u (by state, then part, once each)",
                    k, k - 1);
    }
    m->part_colours += part ? 1 : 0;
  }
  bool has_layer[fmt::kMaxChannels] = {};
  std::uint64_t state = 0, transition = 0, condition = 0;
  for (std::uint32_t l = 0; l < h.layer_count; ++l) {
    const auto e = fmt::DecodeEntry<fmt::MachineLayerEntry>(m->layers, l);
    if (e.channel >= channel_count || has_layer[e.channel])
      return Fail(err, ErrorCode::kBadValue, "MACH layer %u: channel %u is not one of %u, or has a layer already", l,
                  e.channel, channel_count);
    has_layer[e.channel] = true;
    if (e.state_count < 1 || e.state_count > h.state_count - state || e.initial >= e.state_count)
      return Fail(err, ErrorCode::kBadLayout, "MACH layer %u: %u states (initial %u) do not fit the %u there are", l,
                  e.state_count, e.initial, h.state_count);
    const std::uint32_t first = std::uint32_t(state);
    if (e.any_count > h.transition_count - transition)
      return Fail(err, ErrorCode::kBadLayout, "MACH layer %u: its transitions run past the %u there are", l,
                  h.transition_count);
    for (std::uint32_t k = 0; k < e.any_count; ++k, ++transition)
      if (!CheckTransition(fmt::DecodeEntry<fmt::MachineTransitionEntry>(m->transitions, transition),
                           std::uint32_t(transition), first, e.state_count, false, *m, &condition, err))
        return false;
    for (std::uint32_t k = 0; k < e.state_count; ++k, ++state) {
      const auto s = fmt::DecodeEntry<fmt::MachineStateEntry>(m->states, state);
      const auto kind = MachineStateKind(s.kind);
      const std::uint32_t i = std::uint32_t(state);
      if (s.kind > std::uint32_t(MachineStateKind::kBlend) || s.reserved ||
          (kind == MachineStateKind::kPlay ? (s.flags & ~3u) != 0 : s.flags != 0))
        return Fail(err, ErrorCode::kBadValue, "MACH state %u: kind %u, flags 0x%x", i, s.kind, s.flags);
      const bool uses_path = kind == MachineStateKind::kPlay || kind == MachineStateKind::kBlend;
      const bool uses_input = kind == MachineStateKind::kPad || kind == MachineStateKind::kBlend;
      if ((!uses_path && s.path) || (!uses_input && s.input))
        return Fail(err, ErrorCode::kBadValue, "MACH state %u: a path or input its kind does not use", i);
      if (uses_input) {
        const MachineInputType want =
            kind == MachineStateKind::kPad ? MachineInputType::kPoint : MachineInputType::kNumber;
        if (s.input >= h.input_count ||
            MachineInputType(fmt::DecodeEntry<fmt::MachineInputEntry>(m->inputs, s.input).type) != want)
          return Fail(err, ErrorCode::kBadValue, "MACH state %u: input %u is not a %s input", i, s.input,
                      want == MachineInputType::kPoint ? "point" : "number");
      }
      if (kind == MachineStateKind::kPlay ? !(s.speed >= 0 && s.speed <= 1e6) : s.speed != 1)
        return Fail(err, ErrorCode::kBadValue, "MACH state %u: speed %g", i, s.speed);
      if (s.transition_count > h.transition_count - transition)
        return Fail(err, ErrorCode::kBadLayout, "MACH state %u: its transitions run past the %u there are", i,
                    h.transition_count);
      for (std::uint32_t k2 = 0; k2 < s.transition_count; ++k2, ++transition)
        if (!CheckTransition(fmt::DecodeEntry<fmt::MachineTransitionEntry>(m->transitions, transition),
                             std::uint32_t(transition), first, e.state_count, kind == MachineStateKind::kPlay, *m,
                             &condition, err))
          return false;
    }
  }
  if (state != h.state_count || transition != h.transition_count || condition != h.condition_count)
    return Fail(err, ErrorCode::kBadLayout,
                "MACH's layers hold %llu states, %llu transitions and %llu conditions, not "
                "%u, %u and %u",
                (unsigned long long)state, (unsigned long long)transition, (unsigned long long)condition, h.state_count,
                h.transition_count, h.condition_count);
  m->present = true;
  return true;
}

void RigLoader::LayoutMachine(ArenaLayout& arena, const Machine& m, Rig* rig) {
  if (!m.present) return;
  const fmt::MachineHeader& h = m.h;
  auto* inputs = arena.Take<MachineInputView>(h.input_count);
  auto* layers = arena.Take<MachineLayerView>(h.layer_count);
  auto* states = arena.Take<MachineStateView>(h.state_count);
  auto* transitions = arena.Take<MachineTransitionView>(h.transition_count);
  auto* conditions = arena.Take<MachineConditionView>(h.condition_count);
  auto* opacities = arena.Take<MachinePartOpacityView>(m.part_colours);
  char* chars = arena.Take<char>(m.name_bytes);
  if (!layers) return;  // the sizing pass
  const unsigned char* name = m.names;
  auto next_name = [&] {
    std::uint32_t n = 0;
    fmt::FieldDecoder{name}(n);
    std::memcpy(chars, name + 4, n);
    const StringView v{chars, n};
    chars += n, name += 4 + n;
    return v;
  };
  for (std::uint32_t i = 0; i < h.input_count; ++i) {
    const auto e = fmt::DecodeEntry<fmt::MachineInputEntry>(m.inputs, i);
    inputs[i] = MachineInputView{next_name(), MachineInputType(e.type), e.default_x, e.default_y};
  }
  for (std::uint32_t i = 0; i < h.state_count; ++i) states[i].name = next_name();
  for (std::uint32_t k = 0; k < h.condition_count; ++k) {
    const auto e = fmt::DecodeEntry<fmt::MachineConditionEntry>(m.conditions, k);
    conditions[k] = MachineConditionView{e.input, MachineOp(e.op), e.value};
  }
  std::uint32_t condition = 0;
  for (std::uint32_t t = 0; t < h.transition_count; ++t) {
    const auto e = fmt::DecodeEntry<fmt::MachineTransitionEntry>(m.transitions, t);
    MachineTransitionView& v = transitions[t];
    v.to = e.to;
    v.conditions = {conditions + condition, e.condition_count};
    condition += e.condition_count;
    v.mix = e.mix;
    v.has_exit_time = (e.flags & fmt::kMachineTransitionExitTime) != 0;
    v.exit_time = e.exit_time;
  }
  std::uint32_t state = 0, transition = 0;
  for (std::uint32_t l = 0; l < h.layer_count; ++l) {
    const auto e = fmt::DecodeEntry<fmt::MachineLayerEntry>(m.layers, l);
    MachineLayerView& layer = layers[l];
    const auto b = fmt::DecodeEntry<fmt::MachineBehavioursEntry>(m.behaviours, l);
    MachineBehavioursView& bv = layer.behaviours;
    bv.blink = (b.enabled & 1u) != 0, bv.breath = (b.enabled & 2u) != 0;
    bv.look_at = (b.enabled & 4u) != 0, bv.spring = (b.enabled & 8u) != 0;
    bv.blink_pose = b.blink_pose, bv.blink_interval = b.blink_interval, bv.blink_jitter = b.blink_jitter;
    bv.blink_duration = b.blink_duration, bv.blink_strength = b.blink_strength, bv.blink_seed = b.blink_seed;
    bv.breath_period = b.breath_period, bv.breath_x = b.breath_x, bv.breath_y = b.breath_y;
    bv.look_input = b.look_input == 0xFFFFFFFFu ? -1 : int(b.look_input);
    bv.look_smoothing = b.look_smoothing, bv.look_strength = b.look_strength;
    bv.spring_frequency = b.spring_frequency, bv.spring_damping = b.spring_damping;
    bv.spring_strength = b.spring_strength;
    layer.channel = e.channel;
    layer.first_state = state;
    layer.state_count = e.state_count;
    layer.initial = state + e.initial;
    layer.any = {transitions + transition, e.any_count};
    transition += e.any_count;
    for (std::uint32_t k = 0; k < e.state_count; ++k, ++state) {
      const auto s = fmt::DecodeEntry<fmt::MachineStateEntry>(m.states, state);
      MachineStateView& v = states[state];
      v.layer = l;
      v.kind = MachineStateKind(s.kind);
      v.path = s.path;
      v.input = s.input;
      v.loop = (s.flags & fmt::kMachineStateLoopGiven) ? ((s.flags & fmt::kMachineStateLoop) ? 1 : 0) : -1;
      v.speed = s.speed;
      v.transitions = {transitions + transition, s.transition_count};
      transition += s.transition_count;
      for (float& c : v.colour) c = 1;  // as drawn, unless a colour entry below says otherwise
      v.part_opacities = {};
    }
  }
  for (std::uint32_t k = 0, part = 0; k < h.colour_count; ++k) {  // sorted by state: each state's parts in a run
    const auto c = fmt::DecodeEntry<fmt::MachineColourEntry>(m.colours, k);
    MachineStateView& s = states[c.state];
    if (c.part == fmt::MachineColourEntry::kCharacter) {
      s.colour[0] = float(c.r), s.colour[1] = float(c.g), s.colour[2] = float(c.b), s.colour[3] = float(c.a);
      continue;
    }
    if (s.part_opacities.size == 0) s.part_opacities.data = opacities + part;
    opacities[part++] = MachinePartOpacityView{c.part, float(c.a)};
    ++s.part_opacities.size;
  }
  rig->machine_inputs_ = {inputs, h.input_count};
  rig->machine_layers_ = {layers, h.layer_count};
  rig->machine_states_ = {states, h.state_count};
}

bool RigLoader::CheckMachinePaths(const Rig& rig, Error* err) {
  for (std::size_t i = 0; i < rig.machine_states_.size; ++i)
    for (const MachinePartOpacityView& p : rig.machine_states_[i].part_opacities)
      if (p.part >= rig.part_count() || rig.part_count() < 2)
        return Fail(err, ErrorCode::kBadValue, "MACH state %u: an opacity for part %u of a rig with %u part(s)",
                    unsigned(i), p.part, rig.part_count() < 2 ? 0u : rig.part_count());
  for (std::size_t l = 0; l < rig.machine_layers_.size; ++l) {
    const MachineLayerView& layer = rig.machine_layers_[l];
    const Rig* crig = rig.channel_rig(layer.channel);
    if (layer.behaviours.blink && (!crig || layer.behaviours.blink_pose >= crig->pose_count()))
      return Fail(err, ErrorCode::kBadValue, "MACH layer %u's behaviours: blink pose %u of channel %u, which has %u",
                  unsigned(l), layer.behaviours.blink_pose, layer.channel, crig ? crig->pose_count() : 0u);
  }
  for (std::size_t i = 0; i < rig.machine_states_.size; ++i) {
    const MachineStateView& s = rig.machine_states_[i];
    if (s.kind != MachineStateKind::kPlay && s.kind != MachineStateKind::kBlend) continue;
    const std::uint32_t channel = rig.machine_layers_[s.layer].channel;
    const Rig* crig = rig.channel_rig(channel);
    if (!crig || s.path >= crig->path_count())
      return Fail(err, ErrorCode::kBadValue, "MACH state %u: path %u of channel %u, which has %u", unsigned(i), s.path,
                  channel, crig ? crig->path_count() : 0u);
  }
  return true;
}

}  // namespace posemorph
