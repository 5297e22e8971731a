// SPDX-License-Identifier: MIT
// The window's smoke test (--smoke-test OUT.png): a scripted session of
// options.smoke_frames frames, driven from outside the viewer through its
// parts. It drags the pad and records the drag as a gesture, zooms and pans
// the camera, edits a pose, resizes the window half-way, saves what it
// authored, and writes the last frame (with --joints, fitted to the
// character again, its joint markers checked in the shot).
#pragma once
#include <chrono>
#include <cstdint>

#include "window_viewer.h"

namespace posemorph::viewer::window_impl {

class SmokeDriver {
 public:
  explicit SmokeDriver(Parts& parts)
      : w_(parts), timing_start_(std::chrono::steady_clock::now()), started_(timing_start_) {}

  // The scripted input of the current frame, before ImGui::NewFrame.
  void Input();
  // After the panel is built: the wheel steps of this frame, if any.
  void AfterPanel();
  // The scripted frames' last; with --watch, the session then goes on
  // (frames without input) until --rebakes re-bakes have finished.
  bool ScriptEnd() const { return frame_ + 1 == w_.options.smoke_frames; }
  bool LastFrame() const { return frame_ + 1 >= w_.options.smoke_frames && WatchDone(); }
  // On the scripted frames' last, with --description: saves the gesture and
  // the edited pose, printing what was done (Input drags pose 1's point a
  // quarter to the right on that frame, which the panel saves).
  void SaveAuthored();
  // After the frame is presented: timing, and half-way the resize that
  // rebuilds the swapchain under validation. True when the session is over.
  bool AfterFrame();
  // The last frame as a PNG and the session's summary; the exit status.
  int WriteShot();

 private:
  // True without --watch; with it, once `smoke_rebakes` re-bakes finished
  // or 10 minutes passed.
  bool WatchDone() const;

  // --watch on a rig without parts, once the first re-bake is in: edit
  // mode's landmarks, a click on the outline's upper right (a landmark in
  // every pose), then out.
  void WatchScript();

  Parts& w_;
  std::uint32_t frame_ = 0;
  int watch_step_ = 0;
  std::chrono::steady_clock::time_point timing_start_, started_;
  double fps_ = 0;  // frames 10 .. half-way (before the resize)
};

}  // namespace posemorph::viewer::window_impl
