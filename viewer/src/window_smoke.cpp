// SPDX-License-Identifier: MIT
// The window's smoke test (--smoke-test OUT.png): a scripted session of
// options_.smoke_frames frames that drags the pad and records the drag as a
// gesture, zooms and pans the camera, edits a pose, resizes the window
// half-way, saves what it authored, and writes the last frame (with
// --joints, fitted to the character again, its joint markers checked).
#include "window_impl.h"

namespace posemorph::viewer::window_impl {

// The scripted input of the current frame, before ImGui::NewFrame.
void Viewer::SmokeInput() {
  // Drag the pad programmatically: press on it and move around a circle.
  ImGuiIO& io = ImGui::GetIO();
  const float size = kPanelWidth - 24, cx = 8 + 12 + size / 2, cy = 40 + size / 2;
  const float a = float(smoke_frame_) / float(options_.smoke_frames) * 6.2831853f;
  io.MousePos = ImVec2(cx + 0.3f * size * std::cos(a), cy + 0.3f * size * std::sin(a));
  io.MouseDown[0] = smoke_frame_ > 0 && smoke_frame_ < options_.smoke_frames / 2;
  // The camera: three wheel steps in at the middle of the view, then a right drag of 4 x 10 px.
  if (smoke_frame_ == options_.smoke_frames / 2 + 2)
    io.MousePos = ImVec2(kPanelWidth + (sc_.extent.width - kPanelWidth) / 2.0f, sc_.extent.height / 2.0f);
  const std::uint32_t drag = smoke_frame_ - options_.smoke_frames / 2;
  if (smoke_frame_ >= options_.smoke_frames / 2 + 3 && drag <= 7) {
    io.MousePos = ImVec2(kPanelWidth + 100.0f + 10.0f * float(drag - 3), 300.0f);
    io.MouseDown[1] = drag < 7;
  }
  // The drag is recorded as a gesture for the first half.
  if (smoke_frame_ == 1) gesture_ = Gesture{}, gesture_.recording = true, gesture_.start = clock_;
  if (smoke_frame_ == options_.smoke_frames / 2) gesture_.recording = false;
  if (smoke_frame_ == options_.smoke_frames * 3 / 4 && rig_.vertex_count() > 2 && EditModeBuilt()) {
    // Then edit mode: pin vertex 0, drag the vertex farthest from it.
    edit_.on = true;
    const Span<const double> p = rig_.pose_positions(0);
    std::uint32_t far = 1;
    double best = 0;
    for (std::uint32_t v = 1; v < rig_.vertex_count(); ++v) {
      const double d = std::hypot(p.data[2 * v] - p.data[0], p.data[2 * v + 1] - p.data[1]);
      if (d > best) best = d, far = v;
    }
    edit_.handles = {0, far};
    edit_.targets = {glm::dvec2(p.data[0], p.data[1]), glm::dvec2(p.data[2 * far], p.data[2 * far + 1])};
  }
  if (edit_.on && edit_.targets.size() == 2)
    edit_.targets[1].x += 0.2 * rig_.bounding_box_diagonal() / options_.smoke_frames;
  // With --joints, the last frame leaves edit mode and fits the camera to the
  // character again (the "fit character" button): every joint is on screen
  // for the shot to be checked against.
  if (show_joints_ && smoke_frame_ + 1 >= options_.smoke_frames) edit_.on = false, fit_ = Fit::kCharacter;
}

// After a frame: timing, and half-way the resize that rebuilds the swapchain under validation.
void Viewer::SmokeAfterFrame() {
  if (smoke_frame_ == 10) smoke_timing_start_ = std::chrono::steady_clock::now();
  // Half-way, the smoke test resizes the window: the swapchain is rebuilt under validation.
  if (smoke_frame_ == options_.smoke_frames / 2) {
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - smoke_timing_start_).count();
    if (smoke_frame_ > 10) smoke_fps_ = (smoke_frame_ - 10) / seconds;
    glfwSetWindowSize(window_, int(options_.width) - 100, int(options_.height) - 60);
  }
}

// The last frame as a PNG and the session's summary; the exit status.
int Viewer::WriteSmokeShot() {
  std::string problem;
  VkCheck(vkWaitForFences(gpu_.device(), 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  if (!shot_.buffer) {
    std::fprintf(stderr, "posemorph-view: error: no frame was drawn\n");
    return 1;
  } else {
    // Swapchain images are BGRA or RGBA; the PNG wants RGBA.
    std::vector<unsigned char> rgba(static_cast<unsigned char*>(shot_.mapped),
                                    static_cast<unsigned char*>(shot_.mapped) + shot_.size);
    if (sc_.format == VK_FORMAT_B8G8R8A8_UNORM || sc_.format == VK_FORMAT_B8G8R8A8_SRGB)
      for (std::size_t p = 0; p < rgba.size(); p += 4) std::swap(rgba[p], rgba[p + 2]);
    if (!WritePng(options_.smoke_test, rgba.data(), sc_.extent.width, sc_.extent.height, &problem)) {
      std::fprintf(stderr, "posemorph-view: error: %s\n", problem.c_str());
      return 1;
    } else {
      std::printf(
          "wrote %s (%ux%u window, %u frames, pad dragged to (%.3f, %.3f), %u character(s), %.1f fps at %ux%u, "
          "%s)\n",
          options_.smoke_test.c_str(), sc_.extent.width, sc_.extent.height, smoke_frame_, scene_.x, scene_.y,
          SceneCharacters(rig_, scene_), smoke_fps_, options_.width, options_.height, gpu_.device_name().c_str());
      std::printf("camera: zoom %.4g pixels per unit at (%.2f, %.2f), %s\n", camera_.zoom, camera_.centre.x,
                  camera_.centre.y, fit_ == Fit::kNone ? "zoomed and panned by the user" : "fitted");
      if (show_joints_) {
        // Each joint marker of the last frame, found again in the shot: its
        // centre pixel is the marker's fill (magenta: no sample draws it).
        std::size_t seen = 0;
        for (const ImVec2& m : joint_marks_) {
          const std::size_t at = (std::size_t(m.y) * sc_.extent.width + std::size_t(m.x)) * 4;
          seen += at + 2 < rgba.size() && rgba[at] > 200 && rgba[at + 1] < 80 && rgba[at + 2] > 200;
        }
        std::printf("joints: %zu marker(s) on screen for %zu joint(s), %zu seen in the shot\n", joint_marks_.size(),
                    joints_.size() + rig_.attachment_count(), seen);
        if (seen != joint_marks_.size() || joint_marks_.empty()) {
          std::fprintf(stderr, "posemorph-view: error: %zu of %zu joint markers are missing from the shot\n",
                       joint_marks_.size() - seen, joint_marks_.size());
          return 1;
        }
      }
    }
  }
  return 0;
}

}  // namespace posemorph::viewer::window_impl
