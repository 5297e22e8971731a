// SPDX-License-Identifier: MIT
// The interactive viewer: its parts, each its own object with its own file,
// and the loop that runs them (window.cpp):
//   Presenter   (window_presenter.h) the window, device, swapchain and frame;
//   PosePad     (window_pad.h)       the pads, gestures and stored paths;
//   Editor      (window_editor.h)    edit mode and saving into the description
//                                    (the one component that links the bake);
//   ViewCamera  (window_camera.h)    fit, zoom and pan;
//   MachinePanel (window_machine.h)  the state machine: states, inputs, log;
//   SmokeDriver (window_smoke.h)     the scripted session of --smoke-test,
//                                    driving the parts from outside the viewer.
// The panel and the frame's characters are window_frame.cpp.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "scene.h"
#include "window.h"
#include "window_camera.h"
#include "window_common.h"
#include "window_editor.h"
#include "window_machine.h"
#include "window_pad.h"
#include "window_presenter.h"

namespace posemorph::viewer::window_impl {

// The viewer's state: the rig and scene shown and every part. The viewer's
// loop and the smoke-test driver both work on it.
struct Parts {
  Parts(const Rig& r, const Drawings& d, Scene s, const WindowOptions& o)
      : rig(&r),
        drawings(&d),
        scene(std::move(s)),
        options(o),
        editor(r, o.description),
        joints(JointVertices(r)),
        show_joints(o.show_joints) {}

  const Rig* rig;  // what is shown: main's, or the last re-bake's with --watch
  const Drawings* drawings;
  Scene scene;  // what the user set (the pad's point, the panel's toggles)
  const WindowOptions options;
  Presenter presenter;
  PosePad pad;
  MachinePanel machine;
  Editor editor;
  ViewCamera view;
  SceneScratch scratch;
  std::string status;                             // the panel's last line: what a save did, or why a frame failed
  std::string watch_line;                         // --watch: the last re-bake's summary, or its failure
  std::uint32_t rebakes = 0, failed_rebakes = 0;  // --watch: re-bakes swapped in, and failed
  double clock = 0;                               // seconds since the window opened (1/60 a frame in the smoke test)
  double eval_ms = 0;                             // the runtime's time for the last frame's characters
  std::vector<std::uint32_t> joints;              // a layered character's joint vertices (JointVertices)
  bool show_joints = false;                       // markers on the joints (--joints, or the panel's toggle)
  // The last overlay's markers in window pixels (the smoke test finds them in its shot).
  std::vector<ImVec2> joint_marks;
};

class Viewer {
 public:
  Viewer(const Rig& rig, const Drawings& drawings, Scene scene, const WindowOptions& options)
      : parts_(rig, drawings, std::move(scene), options) {}
  // Runs until the window closes (or the smoke test ends); the exit status.
  int Run();

 private:
  void BuildUi();  // the panel (window_frame.cpp)
  // Evaluates the characters into the renderer's buffers (timed) and lets
  // the camera follow them; returns how many to draw.
  std::uint32_t PrepareCharacters(const Scene& shown);
  // A marker on every joint of the characters drawn (when show_joints is on).
  void JointOverlay(std::uint32_t count);
  // --watch: takes a finished re-bake; a rig is swapped in (window.cpp).
  void TakeRebake();
  // Shows `next` from now on: the renderer, the pads, the machine, edit
  // mode and the scene's per-rig settings follow it.
  void Swap(std::unique_ptr<BakedRig> next);

  Parts parts_;
  std::unique_ptr<BakedRig> shown_;  // the rig shown once a re-bake is swapped in
};

}  // namespace posemorph::viewer::window_impl
