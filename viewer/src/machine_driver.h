// SPDX-License-Identifier: MIT
// The viewer's state machine: a rig's machine (format 1.9) run for every
// character of a scene by the runtime's MachineStepJob and
// AnimatorUpdateJob, its inputs set by a timeline (--inputs) or by the
// window's controls, its weights handed to DrawListJob, and what happened
// (state changes, path events) written as lines of a log.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "posemorph/animator.h"
#include "posemorph/draw_list.h"
#include "posemorph/state_machine.h"

namespace posemorph::viewer {

// One entry of an input timeline: at `time` seconds, set input `input` to
// (x, y) (a bool's 0/1, a number, a point) or fire it (a trigger).
struct InputCommand {
  double time = 0;
  std::uint32_t input = 0;
  double x = 0, y = 0;
};

// Parses "T:NAME[=VALUE];T:NAME=VALUE;..." (docs/viewer.md): T seconds >= 0,
// NAME an input of the rig's machine; VALUE true/false for a bool (NAME
// alone: true, !NAME: false), a number for a number, X,Y for a point, none
// or true for a trigger (fired). Sorted by time, ties in the order given. False
// with a message naming the entry and what it wants.
bool ParseInputTimeline(const Rig& rig, const std::string& text, std::vector<InputCommand>* out, std::string* error);

class MachineDriver {
 public:
  // `count` characters of `rig` (which must have a state machine), each
  // with its own machine and tracks, at their initial states once stepped.
  bool Init(const Rig& rig, std::uint32_t count, std::string* error);
  bool active() const { return rig_ != nullptr; }
  std::uint32_t count() const { return count_; }
  double clock() const { return clock_; }

  // Sets an input on every character (a trigger fires), as the timeline or
  // the window's controls say.
  void Apply(const InputCommand& command);
  // One frame: the timeline's entries due by now (clock()) are applied,
  // the machines step (a change of state happens now) and the animators
  // and colours advance by dt to clock() + dt, the time the frame shows
  // (the first call, at 0, steps the machines into their initial states
  // and advances nothing). Writes the log lines of what changed, in time
  // order (character 0's, or every character's with `all`).
  bool Advance(double dt, const std::vector<InputCommand>& timeline, bool all = false);

  // What the last Advance gave, for a DrawListJob of all count() characters
  // (the later channels' weights are channel by channel, AttachJob's layout).
  void Bind(DrawListJob* job) const;
  // Character k's colour and body part opacities (part_count() of them, or
  // none for a rig without parts) that its states set (format 1.10).
  const Colour& colour(std::uint32_t k) const { return colours_[k]; }
  const float* part_opacities(std::uint32_t k) const { return part_opacities_.data() + std::size_t(k) * parts_; }
  std::uint32_t part_count() const { return parts_; }
  // Character k's input values and each layer's state (index in the machine).
  const MachineInstance& machine(std::uint32_t k) const { return machines_[k]; }
  // The log: every line written so far ("1.000 s  body: idle -> waving").
  const std::vector<std::string>& log() const { return log_; }

 private:
  const Rig* rig_ = nullptr;
  std::uint32_t count_ = 0;
  double clock_ = 0;
  std::size_t next_command_ = 0;
  bool started_ = false;
  std::vector<MachineInstance> machines_;
  std::vector<AnimatorTrack> tracks_;
  std::vector<double> raw_, limited_, texture_, attached_raw_, attached_limited_, attached_texture_;
  std::uint32_t parts_ = 0;  // body parts with an opacity (rig.part_count() for a rig with parts, else 0)
  std::vector<Colour> colours_;
  std::vector<float> part_opacities_;
  std::vector<MachineChange> changes_;
  std::vector<AnimatorEvent> events_;
  std::vector<std::string> log_;
};

}  // namespace posemorph::viewer
