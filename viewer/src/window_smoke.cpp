// SPDX-License-Identifier: MIT
// The smoke test's script (window_smoke.h).
#include "window_smoke.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "png_io.h"

namespace posemorph::viewer::window_impl {

void SmokeDriver::Input() {
  const std::uint32_t frames = w_.options.smoke_frames;
  if (frame_ >= frames) return WatchScript();  // --watch: waiting for re-bakes
  const VkExtent2D extent = w_.presenter.extent();
  // Drag the pad programmatically: press on it and move around a circle.
  ImGuiIO& io = ImGui::GetIO();
  const float size = kPanelWidth - 24, cx = 8 + 12 + size / 2, cy = 40 + size / 2;
  const float a = float(frame_) / float(frames) * 6.2831853f;
  io.MousePos = ImVec2(cx + 0.3f * size * std::cos(a), cy + 0.3f * size * std::sin(a));
  io.MouseDown[0] = frame_ > 0 && frame_ < frames / 2;
  // The camera: three wheel steps in at the middle of the view, then a right drag of 4 x 10 px.
  if (frame_ == frames / 2 + 2)
    io.MousePos = ImVec2(kPanelWidth + (extent.width - kPanelWidth) / 2.0f, extent.height / 2.0f);
  const std::uint32_t drag = frame_ - frames / 2;
  if (frame_ >= frames / 2 + 3 && drag <= 7) {
    io.MousePos = ImVec2(kPanelWidth + 100.0f + 10.0f * float(drag - 3), 300.0f);
    io.MouseDown[1] = drag < 7;
  }
  // The drag is recorded as a gesture for the first half.
  Gesture& gesture = w_.pad.gesture();
  if (frame_ == 1) gesture = Gesture{}, gesture.recording = true, gesture.start = w_.clock;
  // With --description, on the last scripted frame: pose 1's point dragged
  // a quarter to the right, let go (the panel saves it this frame, as
  // SaveAuthored saves the rest: one re-bake takes them all with --watch).
  if (ScriptEnd() && !w_.options.description.empty() && w_.rig->pose_count() > 1)
    w_.pad.MovePose(1, w_.rig->pose_points().data[2] + 0.25, w_.rig->pose_points().data[3]);
  if (frame_ == frames / 2) gesture.recording = false;
  Edit& edit = w_.editor.state();
  const Rig& rig = *w_.rig;
  if (frame_ == frames * 3 / 4 && rig.vertex_count() > 2 && EditModeBuilt()) {
    // Then edit mode: pin vertex 0, drag the vertex farthest from it.
    edit.on = true;
    const Span<const double> p = rig.pose_positions(0);
    std::uint32_t far = 1;
    double best = 0;
    for (std::uint32_t v = 1; v < rig.vertex_count(); ++v) {
      const double d = std::hypot(p.data[2 * v] - p.data[0], p.data[2 * v + 1] - p.data[1]);
      if (d > best) best = d, far = v;
    }
    edit.handles = {0, far};
    edit.targets = {glm::dvec2(p.data[0], p.data[1]), glm::dvec2(p.data[2 * far], p.data[2 * far + 1])};
  }
  if (edit.on && edit.targets.size() == 2) edit.targets[1].x += 0.2 * rig.bounding_box_diagonal() / frames;
  // With --joints, the last frame leaves edit mode and fits the camera to the
  // character again (the "fit character" button): every joint is on screen
  // for the shot to be checked against.
  if (w_.show_joints && LastFrame()) edit.on = false, w_.view.set_fit(ViewCamera::Fit::kCharacter);
}

void SmokeDriver::WatchScript() {
  // (A layered rig's watch session is about its layered files: no click.)
  if (!w_.options.watch || !EditModeBuilt() || w_.options.description.empty() || w_.rig->part_count() > 1) return;
  ImGuiIO& io = ImGui::GetIO();
  Edit& edit = w_.editor.state();
  const Rig& rig = *w_.rig;
  if (watch_step_ == 0 && w_.rebakes >= 1) {
    edit.on = true, edit.pose = 0;
    w_.editor.SetClick(1);
    ++watch_step_;
  } else if (watch_step_ == 1 || watch_step_ == 2) {
    // The vertex farthest up and right on pose 0, where the view draws it.
    const Span<const double> p = rig.pose_positions(0);
    std::uint32_t best = 0;
    for (std::uint32_t v = 1; v < rig.vertex_count(); ++v)
      if (p.data[2 * v] + p.data[2 * v + 1] > p.data[2 * best] + p.data[2 * best + 1]) best = v;
    const VkExtent2D extent = w_.presenter.extent();
    const ViewMap map{w_.view.camera(), std::int32_t(kPanelWidth), extent.width - std::uint32_t(kPanelWidth),
                      extent.height};
    io.MousePos = map.ToScreen(glm::dvec2(p.data[2 * best], p.data[2 * best + 1]));
    io.MouseDown[0] = watch_step_ == 2;  // step 1 moves there, step 2 presses
    ++watch_step_;
  } else if (watch_step_ == 3) {
    io.MouseDown[0] = false;
    edit.on = false;
    w_.editor.SetClick(0);
    ++watch_step_;
  }
}

bool SmokeDriver::WatchDone() const {
  if (!w_.options.watch) return true;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  return w_.rebakes + w_.failed_rebakes >= w_.options.smoke_rebakes || seconds > 600;
}

void SmokeDriver::AfterPanel() {
  if (frame_ == w_.options.smoke_frames / 2 + 2)
    ImGui::GetIO().MouseWheel = 3;  // the cursor was put in the view before NewFrame
}

void SmokeDriver::SaveAuthored() {
  if (w_.options.description.empty()) return;
  w_.editor.SaveGesture(w_.pad.gesture(), &w_.status);
  std::printf("%s\n", w_.status.c_str());
  w_.editor.SavePose(w_.scene, &w_.status);
  std::printf("%s\n", w_.status.c_str());
}

bool SmokeDriver::AfterFrame() {
  const WindowOptions& o = w_.options;
  if (frame_ == 10) timing_start_ = std::chrono::steady_clock::now();
  // Half-way, the smoke test resizes the window: the swapchain is rebuilt under validation.
  if (frame_ == o.smoke_frames / 2) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - timing_start_).count();
    if (frame_ > 10) fps_ = (frame_ - 10) / seconds;
    w_.presenter.Resize(int(o.width) - 100, int(o.height) - 60);
  }
  ++frame_;
  // Waiting for re-bakes: a frame every 20 ms is enough, and leaves the
  // cores to the bake.
  if (frame_ >= o.smoke_frames && !WatchDone()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  return frame_ >= o.smoke_frames && WatchDone();
}

int SmokeDriver::WriteShot() {
  const WindowOptions& o = w_.options;
  std::vector<unsigned char> rgba;
  if (!w_.presenter.Screenshot(&rgba)) {
    std::fprintf(stderr, "posemorph-view: error: no frame was drawn\n");
    return 1;
  }
  const VkExtent2D extent = w_.presenter.extent();
  std::string problem;
  if (!WritePng(o.smoke_test, rgba.data(), extent.width, extent.height, &problem)) {
    std::fprintf(stderr, "posemorph-view: error: %s\n", problem.c_str());
    return 1;
  }
  std::printf(
      "wrote %s (%ux%u window, %u frames, pad dragged to (%.3f, %.3f), %u character(s), %.1f fps at %ux%u, %s)\n",
      o.smoke_test.c_str(), extent.width, extent.height, frame_, w_.scene.x, w_.scene.y,
      SceneCharacters(*w_.rig, w_.scene), fps_, o.width, o.height, w_.presenter.device_name().c_str());
  const Camera& camera = w_.view.camera();
  std::printf("camera: zoom %.4g pixels per unit at (%.2f, %.2f), %s\n", camera.zoom, camera.centre.x, camera.centre.y,
              w_.view.fit() == ViewCamera::Fit::kNone ? "zoomed and panned by the user" : "fitted");
  if (w_.machine.on()) {  // the state machine drove the frames: its log and each layer's state
    const MachineDriver& d = w_.machine.driver();
    for (const std::string& line : d.log()) std::printf("%s\n", line.c_str());
    std::string states;
    for (std::size_t l = 0; l < w_.rig->machine_layers().size; ++l) {
      const std::uint32_t s = d.machine(0).state[l];
      states +=
          (l ? ", " : "") + std::string(w_.rig->machine_states()[s].name.data, w_.rig->machine_states()[s].name.size);
    }
    std::printf("state machine: %zu log line(s) in %.3f s, states %s\n", d.log().size(), d.clock(), states.c_str());
  }
  if (!w_.show_joints) return 0;
  // Each joint marker of the last frame, found again in the shot: its
  // centre pixel is the marker's fill (magenta: no sample draws it).
  std::size_t seen = 0;
  for (const ImVec2& m : w_.joint_marks) {
    const std::size_t at = (std::size_t(m.y) * extent.width + std::size_t(m.x)) * 4;
    seen += at + 2 < rgba.size() && rgba[at] > 200 && rgba[at + 1] < 80 && rgba[at + 2] > 200;
  }
  std::printf("joints: %zu marker(s) on screen for %zu joint(s), %zu seen in the shot\n", w_.joint_marks.size(),
              w_.joints.size() + w_.rig->attachment_count(), seen);
  if (seen != w_.joint_marks.size() || w_.joint_marks.empty()) {
    std::fprintf(stderr, "posemorph-view: error: %zu of %zu joint markers are missing from the shot\n",
                 w_.joint_marks.size() - seen, w_.joint_marks.size());
    return 1;
  }
  return 0;
}

}  // namespace posemorph::viewer::window_impl
