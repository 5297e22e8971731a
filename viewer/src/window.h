// SPDX-License-Identifier: MIT
// The interactive viewer window (GLFW + Vulkan swapchain + Dear ImGui).
#pragma once
#include <cstdint>
#include <string>

#include <vector>

#include "machine_driver.h"
#include "scene.h"
#include "watch_bake.h"

namespace posemorph::viewer {

struct WindowOptions {
  std::uint32_t width = 1280, height = 760;
  bool validation = false;
  std::string smoke_test;  // non-empty: drive the pad for `smoke_frames` frames, save this screenshot, exit
  std::uint32_t smoke_frames = 60;
  std::string description;   // rig description to save recorded gestures into
  bool show_joints = false;  // a layered character's joints marked over the frame
  // A rig with a state machine: --inputs was given (the machine drives the
  // characters from the first frame), and its timeline.
  bool machine = false;
  std::vector<InputCommand> timeline;
  // --watch: the description's re-bakes, swapped in as they finish; the
  // smoke test goes on past its frames until `smoke_rebakes` of them have
  // finished (swapped in or failed), for at most 10 minutes.
  WatchedBake* watch = nullptr;
  std::uint32_t smoke_rebakes = 0;
};

// True when this build has edit mode and saving into the description
// (POSEMORPH_VIEWER_EDIT=ON: window_edit.cpp; else window_edit_off.cpp, or
// window_none.cpp in a viewer without a window).
bool EditModeBuilt();

// Runs until the window closes; returns the process exit status.
int RunWindow(const Rig& rig, const Drawings& drawings, Scene scene, const WindowOptions& options);

}  // namespace posemorph::viewer
