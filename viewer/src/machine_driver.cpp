// SPDX-License-Identifier: MIT
#include "machine_driver.h"

#include <algorithm>
#include <cstdio>
#include <optional>

#include "posemorph/bake/command_line.h"

namespace posemorph::viewer {
namespace {

std::string Name(StringView v) { return std::string(v.data, v.size); }

const char* TypeName(MachineInputType t) {
  switch (t) {
    case MachineInputType::kBool:
      return "a bool: NAME, !NAME or NAME=true|false";
    case MachineInputType::kNumber:
      return "a number: NAME=VALUE";
    case MachineInputType::kTrigger:
      return "a trigger: NAME (or NAME=true) fires it";
    case MachineInputType::kPoint:
      return "a point: NAME=X,Y";
  }
  return "";
}

// One "T:NAME[=VALUE]" entry.
bool ParseEntry(const Rig& rig, const std::string& entry, InputCommand* c, std::string* error) {
  const std::size_t colon = entry.find(':');
  const std::optional<double> time =
      colon == std::string::npos ? std::nullopt : bake::ParseNumber(entry.substr(0, colon));
  if (!time || !(*time >= 0 && *time <= 1e6)) {
    *error = "--inputs entry \"" + entry + "\": wants TIME:NAME[=VALUE], TIME in seconds 0..1e6";
    return false;
  }
  std::string name = entry.substr(colon + 1), value;
  const std::size_t eq = name.find('=');
  if (eq != std::string::npos) value = name.substr(eq + 1), name.resize(eq);
  const bool negated = !name.empty() && name[0] == '!';
  if (negated) name.erase(0, 1);
  const int input = rig.FindMachineInput(name.c_str());
  if (input < 0) {
    std::string names;
    for (const MachineInputView& in : rig.machine_inputs()) names += (names.empty() ? "" : ", ") + Name(in.name);
    *error = "--inputs entry \"" + entry + "\": the rig's state machine has no input \"" + name + "\" (" + names + ")";
    return false;
  }
  const MachineInputType type = rig.machine_inputs()[std::size_t(input)].type;
  c->time = *time, c->input = std::uint32_t(input);
  bool ok = false;
  if (type == MachineInputType::kBool) {
    ok = negated ? value.empty() : (value.empty() || value == "true" || value == "false");
    c->x = negated || value == "false" ? 0 : 1;
  } else if (type == MachineInputType::kTrigger) {
    ok = !negated && (value.empty() || value == "true");  // NAME=true fires it too
  } else if (!negated) {
    const std::optional<std::vector<double>> v = bake::ParseNumbers(value, ',');
    const std::size_t want = type == MachineInputType::kPoint ? 2 : 1;
    ok = v && v->size() == want && std::all_of(v->begin(), v->end(), [](double d) { return d >= -1e9 && d <= 1e9; });
    if (ok) c->x = (*v)[0], c->y = want == 2 ? (*v)[1] : 0;
  }
  if (!ok) *error = "--inputs entry \"" + entry + "\": \"" + name + "\" is " + TypeName(type);
  return ok;
}

}  // namespace

bool ParseInputTimeline(const Rig& rig, const std::string& text, std::vector<InputCommand>* out, std::string* error) {
  out->clear();
  if (rig.machine_layers().size == 0) {
    *error = "--inputs needs a rig with a state machine (the description's \"state_machine\")";
    return false;
  }
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t end = std::min(text.find(';', at), text.size());
    const std::string entry = text.substr(at, end - at);
    at = end + 1;
    if (entry.empty()) continue;
    if (out->size() >= 100000) {
      *error = "--inputs holds more than 100000 entries";
      return false;
    }
    InputCommand c;
    if (!ParseEntry(rig, entry, &c, error)) return false;
    out->push_back(c);
  }
  std::stable_sort(out->begin(), out->end(),
                   [](const InputCommand& a, const InputCommand& b) { return a.time < b.time; });
  return true;
}

bool MachineDriver::Init(const Rig& rig, std::uint32_t count, std::string* error) {
  if (rig.machine_layers().size == 0 || count == 0) {
    *error = "the rig has no state machine";
    return false;
  }
  rig_ = &rig;
  count_ = count;
  clock_ = 0, next_command_ = 0, started_ = false;
  const std::size_t C = rig.channel_count(), N = rig.pose_count(), W = rig.attached_weight_count();
  machines_.assign(count, MachineInstance{});
  tracks_.assign(count * C, AnimatorTrack{});
  for (std::uint32_t k = 0; k < count; ++k) {
    MachineReset(rig, &machines_[k]);
    AnimatorReset(rig, {tracks_.data() + k * C, C});
  }
  for (std::vector<double>* w : {&raw_, &limited_, &texture_}) w->assign(count * N, 0.0);
  for (std::vector<double>* w : {&attached_raw_, &attached_limited_, &attached_texture_}) w->assign(count * W, 0.0);
  parts_ = rig.part_count() > 1 ? rig.part_count() : 0;
  colours_.assign(count, Colour{});
  part_opacities_.assign(std::size_t(count) * parts_, 1.0f);
  changes_.resize(std::size_t(count) * rig.machine_layers().size);
  events_.resize(256);
  log_.clear();
  return true;
}

void MachineDriver::Apply(const InputCommand& c) {
  if (!rig_ || c.input >= rig_->machine_inputs().size) return;
  for (MachineInstance& m : machines_) {
    switch (rig_->machine_inputs()[c.input].type) {
      case MachineInputType::kBool:
        MachineSetBool(*rig_, &m, c.input, c.x != 0);
        break;
      case MachineInputType::kNumber:
        MachineSetNumber(*rig_, &m, c.input, c.x);
        break;
      case MachineInputType::kTrigger:
        MachineFire(*rig_, &m, c.input);
        break;
      case MachineInputType::kPoint:
        MachineSetPoint(*rig_, &m, c.input, c.x, c.y);
        break;
    }
  }
}

bool MachineDriver::Advance(double dt, const std::vector<InputCommand>& timeline, bool all) {
  if (!rig_) return false;
  const Rig& rig = *rig_;
  // Entries due by now (with a little slack for the frame clock's
  // rounding) take effect in this update, which starts now.
  const double until = clock_ + 1e-9;
  for (; next_command_ < timeline.size() && timeline[next_command_].time <= until; ++next_command_)
    Apply(timeline[next_command_]);
  std::size_t changed = 0, written = 0;
  std::uint64_t missed_changes = 0, missed_events = 0;
  MachineStepJob step;
  step.rig = &rig, step.count = count_;
  step.machines = MakeSpan(machines_), step.tracks = MakeSpan(tracks_);
  step.changes = MakeSpan(changes_), step.change_count = &changed, step.changes_missed = &missed_changes;
  AnimatorUpdateJob update;
  const double step_dt = started_ ? dt : 0;  // the first frame enters the initial states at time 0
  update.rig = &rig, update.count = count_, update.dt = step_dt;
  update.tracks = MakeSpan(tracks_);
  update.weights = MakeSpan(raw_), update.limited_weights = MakeSpan(limited_),
  update.texture_weights = MakeSpan(texture_);
  if (rig.attachment_count() > 0) {
    update.attached_weights = MakeSpan(attached_raw_), update.attached_limited_weights = MakeSpan(attached_limited_);
    update.attached_texture_weights = MakeSpan(attached_texture_);
  }
  update.events = MakeSpan(events_), update.event_count = &written, update.events_missed = &missed_events;
  MachineColourJob colour;  // the colours the states set, faded by the same dt
  colour.rig = &rig, colour.count = count_, colour.dt = step_dt;
  colour.machines = MakeSpan(machines_), colour.colours = MakeSpan(colours_);
  if (parts_ > 0) colour.part_opacities = MakeSpan(part_opacities_);
  if (!step.Run() || !update.Run() || !colour.Run()) return false;
  const double start = clock_;  // the update's start: changes happen then, events within it
  clock_ += step_dt;
  started_ = true;

  char line[512];
  auto layer_name = [&](std::uint32_t l) {
    const std::uint32_t channel = rig.machine_layers()[l].channel;
    return rig.channel_count() > 1 ? Name(rig.channel_name(channel)) : std::string("layer ") + std::to_string(l);
  };
  auto who = [&](std::uint32_t k) { return count_ > 1 ? "character " + std::to_string(k) + " " : std::string(); };
  for (std::size_t i = 0; i < changed; ++i) {
    const MachineChange& c = changes_[i];
    if (!all && c.character != 0) continue;
    const std::string to = Name(rig.machine_states()[c.to].name);
    const std::string from = c.from == c.to ? "(start)" : Name(rig.machine_states()[c.from].name);
    std::snprintf(line, sizeof line, "%8.3f s  %s%s: %s -> %s", start, who(c.character).c_str(),
                  layer_name(c.layer).c_str(), from.c_str(), to.c_str());
    log_.push_back(line);
  }
  for (std::size_t i = 0; i < written; ++i) {
    const AnimatorEvent& e = events_[i];
    if (!all && e.character != 0) continue;
    const Rig& crig = *rig.channel_rig(e.channel);
    const EventView ev = crig.event(e.event);
    const std::string channel = rig.channel_count() > 1 ? Name(rig.channel_name(e.channel)) : std::string("body");
    std::snprintf(line, sizeof line, "%8.3f s  %sevent \"%s\" (%s, path \"%s\"%s)", start + e.time,
                  who(e.character).c_str(), Name(ev.name).c_str(), channel.c_str(),
                  Name(crig.path(ev.path).name).c_str(), e.outgoing ? ", outgoing" : "");
    log_.push_back(line);
  }
  if (missed_changes + missed_events > 0) log_.push_back("(more changes and events than the log holds this frame)");
  return true;
}

void MachineDriver::Bind(DrawListJob* job) const {
  job->points = {};
  job->weights = MakeSpan(raw_), job->limited_weights = MakeSpan(limited_), job->texture_weights = MakeSpan(texture_);
  if (rig_->attachment_count() > 0) {
    job->channel_points = {};
    job->attached_weights = MakeSpan(attached_raw_), job->attached_limited_weights = MakeSpan(attached_limited_);
    job->attached_texture_weights = MakeSpan(attached_texture_);
  }
}

}  // namespace posemorph::viewer
