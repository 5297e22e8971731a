// SPDX-License-Identifier: MIT
// The window's state machine panel (window_machine.h).
#include "window_machine.h"

#include <algorithm>

namespace posemorph::viewer::window_impl {
namespace {

std::string Name(StringView v) { return Printable(std::string(v.data, v.size), 40); }

}  // namespace

void MachinePanel::Build(const Rig& rig, std::vector<InputCommand> timeline, bool on) {
  timeline_ = std::move(timeline);
  on_ = on && rig.machine_layers().size > 0;
}

bool MachinePanel::Ui(const Rig& rig) {
  if (rig.machine_layers().size == 0) return false;
  if (ImGui::Checkbox("state machine drives the characters", &on_) && on_) driver_ = MachineDriver{};
  if (!on_ || !driver_.active()) return true;
  const MachineInstance& m = driver_.machine(0);
  // Each layer's state (character 0's).
  for (std::size_t l = 0; l < rig.machine_layers().size; ++l) {
    const std::uint32_t channel = rig.machine_layers()[l].channel, state = m.state[l];
    const std::string layer = rig.channel_count() > 1 ? Name(rig.channel_name(channel)) : "state";
    ImGui::Text("%s: %s  (%.2f s)", layer.c_str(),
                state < rig.machine_states().size ? Name(rig.machine_states()[state].name).c_str() : "?",
                driver_.clock());
  }
  // The inputs, set on every character.
  for (std::uint32_t i = 0; i < rig.machine_inputs().size; ++i) {
    const MachineInputView& in = rig.machine_inputs()[i];
    const std::string label = Name(in.name) + "##input" + std::to_string(i);
    InputCommand c;
    c.input = i;
    c.x = m.values[2 * i], c.y = m.values[2 * i + 1];
    bool changed = false;
    switch (in.type) {
      case MachineInputType::kBool: {
        bool v = c.x != 0;
        changed = ImGui::Checkbox(label.c_str(), &v);
        c.x = v ? 1 : 0;
        break;
      }
      case MachineInputType::kNumber: {
        float v = float(c.x);
        changed = ImGui::DragFloat(label.c_str(), &v, 0.01f);
        c.x = v;
        break;
      }
      case MachineInputType::kTrigger:
        changed = ImGui::Button(label.c_str());
        break;
      case MachineInputType::kPoint: {
        float v[2] = {float(c.x), float(c.y)};
        changed = ImGui::DragFloat2(label.c_str(), v, 0.01f);
        c.x = v[0], c.y = v[1];
        break;
      }
    }
    if (changed) driver_.Apply(c);
  }
  // The log, newest last, scrolled down as lines arrive.
  ImGui::TextUnformatted("state changes and events");
  ImGui::BeginChild("machine log", ImVec2(0, 130), true);
  const std::vector<std::string>& log = driver_.log();
  for (std::size_t k = log.size() > 200 ? log.size() - 200 : 0; k < log.size(); ++k)
    ImGui::TextUnformatted(log[k].c_str());
  if (log.size() != shown_log_) ImGui::SetScrollHereY(1.0f), shown_log_ = log.size();
  ImGui::EndChild();
  ImGui::TextWrapped("(the pads below do not drive the characters while the machine does)");
  return true;
}

void MachinePanel::Frame(const Rig& rig, double dt, Scene* shown, std::string* status) {
  if (!on_) return;
  shown->show_bases = shown->compare_linear = false;
  const std::uint32_t count = SceneCharacters(rig, *shown);
  if (!driver_.active() || driver_.count() != count) {
    if (!driver_.Init(rig, count, status)) {
      on_ = false;
      return;
    }
  }
  if (!driver_.Advance(dt, timeline_)) {
    *status = "the state machine's step failed";
    on_ = false;
    return;
  }
  shown->machine = &driver_;
}

}  // namespace posemorph::viewer::window_impl
