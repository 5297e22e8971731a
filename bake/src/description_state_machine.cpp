// SPDX-License-Identifier: MIT
// "state_machine" (bake/RIG_DESCRIPTION.md): inputs, and per channel a
// layer of states and transitions. Every name is resolved here, and every
// inconsistency fails with one line naming the layer, state, transition or
// input: an unknown name, an input of the wrong type, a transition to
// nowhere or one that always fires, a state no transition reaches.
#include <algorithm>
#include <cstdio>
#include <set>

#include "description_reader.h"
#include "posemorph/rig_format.h"

namespace posemorph::bake::description {
namespace {

std::string Quoted(const std::string& s) { return "\"" + s + "\""; }

const char* TypeName(MachineInputType t) {
  switch (t) {
    case MachineInputType::kBool:
      return "bool";
    case MachineInputType::kNumber:
      return "number";
    case MachineInputType::kTrigger:
      return "trigger";
    case MachineInputType::kPoint:
      return "point";
  }
  return "?";
}

std::string Name(const Reader& r, const json& j, const std::string& where) {
  const std::string name = r.String(j, where);
  if (name.empty() || name.size() > format::kMaxMachineName)
    r.Fail(where, "a name of 1 to " + std::to_string(format::kMaxMachineName) + " bytes");
  return name;
}

std::vector<MachineInputDescription> ParseInputs(const Reader& r, const json& inputs) {
  std::vector<MachineInputDescription> out;
  if (inputs.size() > format::kMaxMachineInputs)
    r.Fail("state_machine.inputs", std::to_string(inputs.size()) + " inputs, more than the format's " +
                                       std::to_string(format::kMaxMachineInputs));
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const std::string w = "state_machine.inputs[" + std::to_string(i) + "]";
    const json& j = inputs[i];
    if (!j.is_object()) r.Fail(w, "expected {\"name\", \"type\"}");
    MachineInputDescription in;
    if (!j.contains("name")) r.Fail(w, "missing \"name\"");
    in.name = Name(r, j["name"], w + ".name");
    for (const MachineInputDescription& e : out)
      if (e.name == in.name) r.Fail(w, "input " + Quoted(in.name) + " is declared twice");
    if (!j.contains("type")) r.Fail(w, "missing \"type\": \"bool\", \"number\", \"trigger\" or \"point\"");
    const std::string type = r.String(j["type"], w + ".type");
    if (type == "bool")
      in.type = MachineInputType::kBool;
    else if (type == "number")
      in.type = MachineInputType::kNumber;
    else if (type == "trigger")
      in.type = MachineInputType::kTrigger;
    else if (type == "point")
      in.type = MachineInputType::kPoint;
    else
      r.Fail(w + ".type", Quoted(type) + ": expected \"bool\", \"number\", \"trigger\" or \"point\"");
    if (j.contains("default")) {
      const json& d = j["default"];
      const std::string wd = w + ".default";
      if (in.type == MachineInputType::kBool) {
        if (!d.is_boolean()) r.Fail(wd, "expected true or false");
        in.default_x = d.get<bool>() ? 1 : 0;
      } else if (in.type == MachineInputType::kNumber) {
        in.default_x = r.Number(d, wd);
        if (!(std::fabs(in.default_x) <= 1e9)) r.Fail(wd, "beyond +-1e9");
      } else if (in.type == MachineInputType::kPoint) {
        const Eigen::Vector2d p = r.Point(d, wd);
        if (!(p.cwiseAbs().maxCoeff() <= 1e9)) r.Fail(wd, "beyond +-1e9");
        in.default_x = p.x(), in.default_y = p.y();
      } else {
        r.Fail(wd, "a trigger has no default");
      }
    }
    out.push_back(in);
  }
  return out;
}

std::uint32_t FindInput(const Reader& r, const std::vector<MachineInputDescription>& inputs, const std::string& name,
                        const std::string& where) {
  for (std::size_t i = 0; i < inputs.size(); ++i)
    if (inputs[i].name == name) return std::uint32_t(i);
  r.Fail(where, "unknown input " + Quoted(name) + " (state_machine.inputs declares the inputs)");
}

// "name" (a bool is true, a trigger fired), "!name" (false, not fired), or
// [name, op, value] (a number compared; a bool == / != true or false).
MachineConditionDescription ParseCondition(const Reader& r, const std::vector<MachineInputDescription>& inputs,
                                           const json& j, const std::string& w) {
  MachineConditionDescription c;
  if (j.is_string()) {
    std::string name = j.get<std::string>();
    const bool negated = !name.empty() && name[0] == '!';
    if (negated) name.erase(0, 1);
    c.input = FindInput(r, inputs, name, w);
    const MachineInputType t = inputs[c.input].type;
    if (t != MachineInputType::kBool && t != MachineInputType::kTrigger)
      r.Fail(w,
             "input " + Quoted(name) + " is a " + TypeName(t) + ": compare it, as [" + Quoted(name) + ", \">\", 0.5]");
    c.op = negated ? MachineOp::kIsFalse : MachineOp::kIsTrue;
    return c;
  }
  if (!j.is_array() || j.size() != 3 || !j[0].is_string() || !j[1].is_string())
    r.Fail(w, "expected \"input\", \"!input\" or [\"input\", \"op\", value]");
  const std::string name = j[0].get<std::string>(), op = j[1].get<std::string>();
  c.input = FindInput(r, inputs, name, w);
  const MachineInputType t = inputs[c.input].type;
  if (t == MachineInputType::kBool) {
    if (!j[2].is_boolean() || (op != "==" && op != "!="))
      r.Fail(w, "input " + Quoted(name) + " is a bool: [" + Quoted(name) + ", \"==\", true] or \"" + name + "\"");
    c.op = (j[2].get<bool>() == (op == "==")) ? MachineOp::kIsTrue : MachineOp::kIsFalse;
    return c;
  }
  if (t != MachineInputType::kNumber)
    r.Fail(w, "input " + Quoted(name) + " is a " + TypeName(t) + " and cannot be compared" +
                  (t == MachineInputType::kTrigger ? ": write \"" + name + "\"" : std::string()));
  const char* ops[] = {"==", "!=", "<", "<=", ">", ">="};
  const MachineOp codes[] = {MachineOp::kEqual,     MachineOp::kNotEqual, MachineOp::kLess,
                             MachineOp::kLessEqual, MachineOp::kGreater,  MachineOp::kGreaterEqual};
  bool found = false;
  for (int k = 0; k < 6; ++k)
    if (op == ops[k]) c.op = codes[k], found = true;
  if (!found) r.Fail(w, "operator " + Quoted(op) + ": expected ==, !=, <, <=, > or >=");
  c.value = r.Number(j[2], w + "[2]");
  if (!(std::fabs(c.value) <= 1e9)) r.Fail(w + "[2]", "beyond +-1e9");
  return c;
}

std::uint32_t FindPath(const Reader& r, const std::vector<PathDescription>& paths, const std::string& name,
                       const std::string& channel, const std::string& where) {
  for (std::size_t i = 0; i < paths.size(); ++i)
    if (paths[i].name == name) return std::uint32_t(i);
  r.Fail(where, "unknown path " + Quoted(name) + (channel.empty() ? "" : " in channel " + Quoted(channel)));
}

// A component of a colour in [0, 1].
double Unit(const Reader& r, const json& j, const std::string& w) {
  const double v = r.Number(j, w);
  if (!(v >= 0 && v <= 1)) r.Fail(w, "outside 0..1");
  return v;
}

// A state's "colour", "opacity" and "parts" (format 1.10). `body_parts`:
// the names of the parts the first channel drives, in the body's order.
void ParseStateColour(const Reader& r, const json& j, const std::vector<std::string>& body_parts,
                      MachineStateDescription* s, const std::string& w) {
  if (j.contains("colour")) {
    const json& c = j["colour"];
    if (!c.is_array() || c.size() < 3 || c.size() > 4)
      r.Fail(w + ".colour", "expected [r, g, b] or [r, g, b, a], each 0..1 (a tint: the drawing's colour times it)");
    for (std::size_t k = 0; k < c.size(); ++k) s->colour[k] = Unit(r, c[k], w + ".colour[" + std::to_string(k) + "]");
  }
  if (j.contains("opacity")) s->colour[3] *= Unit(r, j["opacity"], w + ".opacity");
  if (!j.contains("parts")) return;
  const json& parts = j["parts"];
  if (!parts.is_object()) r.Fail(w + ".parts", "expected {\"part\": opacity, ...}");
  if (body_parts.size() < 2)
    r.Fail(w + ".parts", "the character has no parts on its first channel (a state sets body parts' opacities)");
  for (auto it = parts.begin(); it != parts.end(); ++it) {
    const std::string wp = w + ".parts." + it.key();
    std::uint32_t index = 0;
    while (index < body_parts.size() && body_parts[index] != it.key()) ++index;
    if (index == body_parts.size()) {
      std::string names;
      for (const std::string& n : body_parts) names += (names.empty() ? "" : ", ") + Quoted(n);
      r.Fail(wp, "no body part " + Quoted(it.key()) + " (the first channel's parts: " + names + ")");
    }
    s->part_opacities.emplace_back(index, Unit(r, it.value(), wp));
  }
  std::sort(s->part_opacities.begin(), s->part_opacities.end());
}

MachineStateDescription ParseState(const Reader& r, const StateMachineDescription& m, const json& j,
                                   const std::vector<PathDescription>& paths, const std::string& channel,
                                   const std::vector<std::string>& body_parts, const std::string& w) {
  if (!j.is_object()) r.Fail(w, "expected {\"name\", and one of \"play\", \"pad\", \"blend\", \"stop\"}");
  MachineStateDescription s;
  if (!j.contains("name")) r.Fail(w, "missing \"name\"");
  s.name = Name(r, j["name"], w + ".name");
  const int kinds =
      int(j.contains("play")) + int(j.contains("pad")) + int(j.contains("blend")) + int(j.contains("stop"));
  if (kinds != 1)
    r.Fail(w, "state " + Quoted(s.name) + ": give exactly one of \"play\": path, \"pad\": point input, " +
                  "\"blend\": path with \"by\": number input, \"stop\": true");
  if (j.contains("play")) {
    s.kind = MachineStateKind::kPlay;
    s.path = FindPath(r, paths, r.String(j["play"], w + ".play"), channel, w + ".play");
    if (j.contains("loop")) {
      if (!j["loop"].is_boolean()) r.Fail(w + ".loop", "expected true or false");
      s.loop = j["loop"].get<bool>() ? 1 : 0;
    }
    if (j.contains("speed")) {
      s.speed = r.Number(j["speed"], w + ".speed");
      if (!(s.speed >= 0 && s.speed <= 1e6)) r.Fail(w + ".speed", "outside 0..1e6");
    }
  } else if (j.contains("pad")) {
    s.kind = MachineStateKind::kPad;
    s.input = FindInput(r, m.inputs, r.String(j["pad"], w + ".pad"), w + ".pad");
    if (m.inputs[s.input].type != MachineInputType::kPoint)
      r.Fail(w + ".pad", "input " + Quoted(m.inputs[s.input].name) + " is a " + TypeName(m.inputs[s.input].type) +
                             ": a pad follows a point input");
  } else if (j.contains("blend")) {
    s.kind = MachineStateKind::kBlend;
    s.path = FindPath(r, paths, r.String(j["blend"], w + ".blend"), channel, w + ".blend");
    if (!j.contains("by")) r.Fail(w, "state " + Quoted(s.name) + ": a blend needs \"by\": a number input (0..1)");
    s.input = FindInput(r, m.inputs, r.String(j["by"], w + ".by"), w + ".by");
    if (m.inputs[s.input].type != MachineInputType::kNumber)
      r.Fail(w + ".by", "input " + Quoted(m.inputs[s.input].name) + " is a " + TypeName(m.inputs[s.input].type) +
                            ": a blend moves along its path by a number input");
  } else if (!j["stop"].is_boolean() || !j["stop"].get<bool>()) {
    r.Fail(w + ".stop", "expected true");
  }
  if (s.kind != MachineStateKind::kPlay && (j.contains("loop") || j.contains("speed")))
    r.Fail(w, "state " + Quoted(s.name) + ": \"loop\" and \"speed\" belong to a state that plays a path");
  ParseStateColour(r, j, body_parts, &s, w);
  return s;
}

std::string Num(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", v);
  return text;
}

// A number at `key` of `j` within [lo, hi], or `fallback` when absent.
double Within(const Reader& r, const json& j, const char* key, double lo, double hi, double fallback,
              const std::string& w) {
  if (!j.contains(key)) return fallback;
  const double v = r.Number(j[key], w + "." + key);
  if (!(v >= lo && v <= hi))
    r.Fail(w + "." + key, "outside " + Num(lo) + ".." + Num(hi) + " (animator.h gives the ranges)");
  return v;
}

// "behaviours": {"blink", "breath", "look_at", "spring"}, each an object of
// the parameters animator.h names.
MachineBehavioursView ParseBehaviours(const Reader& r, const StateMachineDescription& m, const json& j,
                                      const std::vector<PoseDescription>& poses, const std::string& w) {
  MachineBehavioursView b;
  if (!j.is_object()) r.Fail(w, "expected {\"blink\", \"breath\", \"look_at\", \"spring\"}");
  for (const auto& item : j.items())
    if (item.key() != "blink" && item.key() != "breath" && item.key() != "look_at" && item.key() != "spring")
      r.Fail(w, "unknown behaviour " + Quoted(item.key()) + ": \"blink\", \"breath\", \"look_at\" or \"spring\"");
  if (j.contains("blink")) {
    const json& k = j["blink"];
    const std::string wk = w + ".blink";
    if (!k.is_object() || !k.contains("pose")) r.Fail(wk, "expected {\"pose\": the pose it closes toward, ...}");
    const std::string pose = r.String(k["pose"], wk + ".pose");
    bool found = false;
    for (std::size_t i = 0; i < poses.size(); ++i)
      if (poses[i].name == pose) b.blink_pose = std::uint32_t(i), found = true;
    if (!found) r.Fail(wk + ".pose", "unknown pose " + Quoted(pose) + " in the layer's channel");
    b.blink = true;
    b.blink_interval = Within(r, k, "interval", 0.02, 1e6, b.blink_interval, wk);
    b.blink_jitter = Within(r, k, "jitter", 0, 0.95, b.blink_jitter, wk);
    b.blink_duration = Within(r, k, "duration", 0.001, 60, b.blink_duration, wk);
    b.blink_strength = Within(r, k, "strength", 0, 1, b.blink_strength, wk);
    if (k.contains("seed")) {
      if (!k["seed"].is_number_unsigned()) r.Fail(wk + ".seed", "expected a non-negative integer");
      b.blink_seed = k["seed"].get<std::uint64_t>();
    }
  }
  if (j.contains("breath")) {
    const json& k = j["breath"];
    const std::string wk = w + ".breath";
    if (!k.is_object() || !k.contains("offset")) r.Fail(wk, "expected {\"period\", \"offset\": [x, y]}");
    b.breath = true;
    b.breath_period = Within(r, k, "period", 0.05, 1e6, b.breath_period, wk);
    const Eigen::Vector2d o = r.Point(k["offset"], wk + ".offset");
    if (!(o.cwiseAbs().maxCoeff() <= 1e3)) r.Fail(wk + ".offset", "beyond +-1e3 pose-space units");
    b.breath_x = o.x(), b.breath_y = o.y();
  }
  if (j.contains("look_at")) {
    const json& k = j["look_at"];
    const std::string wk = w + ".look_at";
    if (!k.is_object()) r.Fail(wk, "expected {\"target\": a point input, \"smoothing\", \"strength\"}");
    b.look_at = true;
    if (k.contains("target")) {
      const std::uint32_t in = FindInput(r, m.inputs, r.String(k["target"], wk + ".target"), wk + ".target");
      if (m.inputs[in].type != MachineInputType::kPoint)
        r.Fail(wk + ".target", "input " + Quoted(m.inputs[in].name) + " is a " + TypeName(m.inputs[in].type) +
                                   ": look-at follows a point input");
      b.look_input = int(in);
    }
    b.look_smoothing = Within(r, k, "smoothing", 0, 1e3, b.look_smoothing, wk);
    b.look_strength = Within(r, k, "strength", 0, 1, b.look_strength, wk);
  }
  if (j.contains("spring")) {
    const json& k = j["spring"];
    const std::string wk = w + ".spring";
    if (!k.is_object()) r.Fail(wk, "expected {\"frequency\", \"damping\", \"strength\"}");
    b.spring = true;
    b.spring_frequency = Within(r, k, "frequency", 0.01, 20, b.spring_frequency, wk);
    b.spring_damping = Within(r, k, "damping", 0, 100, b.spring_damping, wk);
    b.spring_strength = Within(r, k, "strength", 0, 4, b.spring_strength, wk);
  }
  return b;
}

}  // namespace

StateMachineDescription ParseStateMachine(const Reader& r, const json& j, const RigDescription& rig) {
  StateMachineDescription m;
  if (!j.is_object()) r.Fail("state_machine", "expected {\"inputs\", \"layers\"}");
  if (j.contains("inputs")) m.inputs = ParseInputs(r, r.Array(j, "inputs", "state_machine"));
  const json& layers = r.Array(j, "layers", "state_machine");
  const std::size_t channels = rig.channels.empty() ? 1 : rig.channels.size();
  if (layers.empty() || layers.size() > channels)
    r.Fail("state_machine.layers", "give 1 to " + std::to_string(channels) + " layers, one per channel");
  std::set<std::string> state_names;
  std::vector<bool> has_layer(channels, false);
  std::size_t states_total = 0, transitions_total = 0, conditions_total = 0;
  std::vector<std::string> body_parts;  // the parts the first channel drives, in the body's order
  for (const PartDescription& part : rig.parts)
    if (part.channel == 0) body_parts.push_back(part.name);
  for (std::size_t l = 0; l < layers.size(); ++l) {
    const std::string wl = "state_machine.layers[" + std::to_string(l) + "]";
    const json& jl = layers[l];
    if (!jl.is_object()) r.Fail(wl, "expected {\"channel\", \"initial\", \"states\", \"transitions\"}");
    MachineLayerDescription layer;
    std::string channel_name;
    if (jl.contains("channel")) {
      channel_name = r.String(jl["channel"], wl + ".channel");
      bool found = false;
      for (std::size_t c = 0; c < rig.channels.size(); ++c)
        if (rig.channels[c].name == channel_name) layer.channel = std::uint32_t(c), found = true;
      if (!found) r.Fail(wl + ".channel", "unknown channel " + Quoted(channel_name));
    } else if (rig.channels.size() > 1) {
      r.Fail(wl, "missing \"channel\": this rig has channels");
    }
    if (has_layer[layer.channel]) r.Fail(wl + ".channel", "a second layer for channel " + Quoted(channel_name));
    has_layer[layer.channel] = true;
    const std::vector<PathDescription>& paths = rig.channels.empty() ? rig.paths : rig.channels[layer.channel].paths;
    const json& states = r.Array(jl, "states", wl);
    if (states.empty()) r.Fail(wl + ".states", "a layer has at least one state");
    for (std::size_t i = 0; i < states.size(); ++i) {
      const std::string ws = wl + ".states[" + std::to_string(i) + "]";
      layer.states.push_back(ParseState(r, m, states[i], paths, channel_name, body_parts, ws));
      if (!state_names.insert(layer.states.back().name).second)
        r.Fail(ws, "state " + Quoted(layer.states.back().name) + " is declared twice (state names are unique)");
    }
    auto find_state = [&](const std::string& name, const std::string& where) -> std::uint32_t {
      for (std::size_t i = 0; i < layer.states.size(); ++i)
        if (layer.states[i].name == name) return std::uint32_t(i);
      r.Fail(where, "unknown state " + Quoted(name) + " in this layer");
    };
    if (jl.contains("behaviours")) {
      const std::vector<PoseDescription>& poses = rig.channels.empty() ? rig.poses : rig.channels[layer.channel].poses;
      layer.behaviours = ParseBehaviours(r, m, jl["behaviours"], poses, wl + ".behaviours");
    }
    if (!jl.contains("initial")) r.Fail(wl, "missing \"initial\": the state the layer starts in");
    layer.initial = find_state(r.String(jl["initial"], wl + ".initial"), wl + ".initial");
    const json empty = json::array();
    const json& transitions = jl.contains("transitions") ? r.Array(jl, "transitions", wl) : empty;
    for (std::size_t t = 0; t < transitions.size(); ++t) {
      const std::string wt = wl + ".transitions[" + std::to_string(t) + "]";
      const json& jt = transitions[t];
      if (!jt.is_object()) r.Fail(wt, "expected {\"from\", \"to\", \"when\", \"mix\", \"exit_time\"}");
      MachineTransitionDescription tr;
      if (!jt.contains("from")) r.Fail(wt, "missing \"from\": a state, or \"*\" for any");
      const std::string from = r.String(jt["from"], wt + ".from");
      tr.any = from == "*";
      if (!tr.any) tr.from = find_state(from, wt + ".from");
      if (!jt.contains("to")) r.Fail(wt, "a transition to nowhere: missing \"to\"");
      tr.to = find_state(r.String(jt["to"], wt + ".to"), wt + ".to");
      if (jt.contains("when")) {
        const json& when = jt["when"];
        if (!when.is_array()) r.Fail(wt + ".when", "expected a list of conditions");
        for (std::size_t k = 0; k < when.size(); ++k)
          tr.when.push_back(ParseCondition(r, m.inputs, when[k], wt + ".when[" + std::to_string(k) + "]"));
      }
      if (jt.contains("mix")) {
        tr.mix = r.Number(jt["mix"], wt + ".mix");
        if (!(tr.mix >= 0 && tr.mix <= 1e6)) r.Fail(wt + ".mix", "outside 0..1e6 seconds");
      }
      if (jt.contains("exit_time")) {
        tr.has_exit_time = true;
        tr.exit_time = r.Number(jt["exit_time"], wt + ".exit_time");
        if (!(tr.exit_time >= 0 && tr.exit_time <= 1))
          r.Fail(wt + ".exit_time", "outside 0..1 (the share of the state's path played)");
        if (tr.any || layer.states[tr.from].kind != MachineStateKind::kPlay)
          r.Fail(wt + ".exit_time", "only a transition from a state that plays a path has an exit time");
      }
      if (tr.when.empty() && !tr.has_exit_time)
        r.Fail(wt, "no \"when\" and no \"exit_time\": the transition would fire at every step");
      conditions_total += tr.when.size();
      layer.transitions.push_back(tr);
    }
    // Every state is reachable from the initial one.
    std::vector<bool> reached(layer.states.size(), false);
    reached[layer.initial] = true;
    for (bool grew = true; grew;) {
      grew = false;
      for (const MachineTransitionDescription& tr : layer.transitions)
        if ((tr.any || reached[tr.from]) && !reached[tr.to]) reached[tr.to] = grew = true;
    }
    for (std::size_t i = 0; i < layer.states.size(); ++i)
      if (!reached[i])
        r.Fail(wl + ".states[" + std::to_string(i) + "]", "state " + Quoted(layer.states[i].name) +
                                                              " is unreachable: no transition leads to it from " +
                                                              Quoted(layer.states[layer.initial].name));
    states_total += layer.states.size();
    transitions_total += layer.transitions.size();
    m.layers.push_back(std::move(layer));
  }
  if (states_total > format::kMaxMachineStates || transitions_total > format::kMaxMachineTransitions ||
      conditions_total > format::kMaxMachineConditions)
    r.Fail("state_machine",
           std::to_string(states_total) + " states, " + std::to_string(transitions_total) + " transitions and " +
               std::to_string(conditions_total) + " conditions: above the format's limits of " +
               std::to_string(format::kMaxMachineStates) + ", " + std::to_string(format::kMaxMachineTransitions) +
               " and " + std::to_string(format::kMaxMachineConditions));
  return m;
}

}  // namespace posemorph::bake::description
