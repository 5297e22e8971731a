// SPDX-License-Identifier: MIT
// The window's state machine panel: for a rig with a state machine, a
// switch that hands the characters to it, each layer's current state, the
// inputs as controls (a bool's checkbox, a number's slider, a point's pair,
// a trigger's button), the --inputs timeline playing on the window's clock,
// and the log of state changes and path events.
#pragma once
#include <string>
#include <vector>

#include "machine_driver.h"
#include "scene.h"
#include "window_common.h"

namespace posemorph::viewer::window_impl {

class MachinePanel {
 public:
  // `timeline` (--inputs) plays from the window's first frame; `on` starts
  // with the machine driving the characters.
  void Build(const Rig& rig, std::vector<InputCommand> timeline, bool on);
  // The panel's section (nothing for a rig without a machine: false).
  bool Ui(const Rig& rig);
  // Before a frame is evaluated: steps the machines by dt (started again
  // for a crowd of another size) and hands them to the frame's scene.
  void Frame(const Rig& rig, double dt, Scene* shown, std::string* status);
  bool on() const { return on_; }
  const MachineDriver& driver() const { return driver_; }

 private:
  MachineDriver driver_;
  std::vector<InputCommand> timeline_;
  bool on_ = false;
  std::size_t shown_log_ = 0;  // log lines the panel has scrolled to
};

}  // namespace posemorph::viewer::window_impl
