// SPDX-License-Identifier: MIT
// The interactive viewer: a GLFW window with a Vulkan swapchain. The rig is
// drawn with dynamic rendering, then Dear ImGui (its 1.86 Vulkan backend
// wants a render pass) draws the panel on top: the pose-space pad, gestures,
// stored paths, and the controls. This file: the main loop over the
// viewer's parts (window_viewer.h), each in its own file.
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>

#include "window_smoke.h"
#include "window_viewer.h"

namespace posemorph::viewer {
namespace window_impl {

void Viewer::TakeRebake() {
  Parts& w = parts_;
  if (!w.options.watch) return;
  std::unique_ptr<BakedRig> next;
  std::string message;
  switch (w.options.watch->Take(&next, &message)) {
    case WatchedBake::Result::kBaked:
      Swap(std::move(next));
      break;
    case WatchedBake::Result::kFailed:
      ++w.failed_rebakes;
      w.watch_line = "the re-bake failed; still showing the last rig: " + message;
      std::fprintf(stderr, "posemorph-view: %s\n", Printable(w.watch_line, 2000).c_str());
      break;
    case WatchedBake::Result::kNone:
      break;
  }
}

void Viewer::Swap(std::unique_ptr<BakedRig> next) {
  Parts& w = parts_;
  const Rig& rig = next->rig;
  Scene& scene = w.scene;
  std::string problem;
  if (!w.presenter.SwapRig(rig, next->drawings, SceneFilter(rig, scene), &problem)) {
    ++w.failed_rebakes;
    w.watch_line = "the re-bake cannot be drawn; still showing the last rig: " + problem;
    std::fprintf(stderr, "posemorph-view: %s\n", Printable(w.watch_line, 2000).c_str());
    return;
  }
  // The scene keeps what still means something for the new rig.
  if (!scene.path.empty() && rig.FindPath(scene.path.c_str()) < 0) scene.path.clear();
  const std::uint32_t bits = std::min<std::uint32_t>(64, rig.part_count() + rig.attachment_count());
  if (bits < 64) scene.hidden_parts &= (std::uint64_t(1) << bits) - 1;
  if (!scene.part_opacities.empty()) scene.part_opacities.resize(rig.part_count(), 1.0f);
  scene.channels.resize(rig.channel_count() > 1 ? rig.channel_count() - 1 : 0);
  for (ChannelInput& c : scene.channels)
    if (!c.path.empty()) c.path.clear();
  w.rig = &rig;
  w.drawings = &next->drawings;
  w.editor.Rebind(rig);
  w.joints = JointVertices(rig);
  w.pad = PosePad{};
  w.pad.Build(rig, &scene);
  w.machine = MachinePanel{};
  w.machine.Build(rig, w.options.timeline, w.options.machine);
  w.scratch = SceneScratch{};
  ++w.rebakes;
  w.watch_line = next->summary + "; swapped in";
  std::printf("posemorph-view: %s\n", Printable(w.watch_line, 2000).c_str());
  std::fflush(stdout);
  shown_ = std::move(next);  // the previous re-bake, if any, goes now: nothing refers to it
}

int Viewer::Run() {
  Parts& w = parts_;
  if (!w.presenter.Open(w.options, *w.rig, *w.drawings, SceneFilter(*w.rig, w.scene))) return 1;
  w.pad.Build(*w.rig, &w.scene);
  w.machine.Build(*w.rig, w.options.timeline, w.options.machine);
  w.editor.SetWatched(w.options.watch != nullptr);
  std::optional<SmokeDriver> smoke;
  if (!w.options.smoke_test.empty()) smoke.emplace(w);
  int status = 0;
  auto last = std::chrono::steady_clock::now();
  while (!glfwWindowShouldClose(w.presenter.window())) {
    glfwPollEvents();
    TakeRebake();
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(w.presenter.window(), &fw, &fh);
    if (fw == 0 || fh == 0) {  // minimised: wait for the window to come back
      glfwWaitEvents();
      continue;
    }
    const auto now = std::chrono::steady_clock::now();
    const double dt = smoke ? 1.0 / 60 : std::chrono::duration<double>(now - last).count();
    w.clock += dt;
    last = now;
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    if (smoke) smoke->Input();
    ImGui::NewFrame();
    BuildUi();
    if (smoke) smoke->AfterPanel();
    const VkExtent2D extent = w.presenter.extent();
    if (extent.width > kPanelWidth + 8) {
      const std::int32_t x0 = std::int32_t(kPanelWidth);
      const std::uint32_t view_w = extent.width - std::uint32_t(kPanelWidth);
      w.view.Input(w.presenter.window(), x0, view_w, extent.height);
      if (w.editor.on())
        w.editor.Input(ViewMap{w.view.camera(), x0, view_w, extent.height}, w.view.panning(), &w.status);
    }
    // The characters are evaluated before ImGui::Render, so that the
    // overlays follow this frame's characters.
    std::uint32_t index = 0, count = 0;
    Scene shown;
    const bool drawing = w.presenter.Acquire(&index);
    if (drawing) {
      shown = w.pad.Shown(*w.rig, &w.scene, w.clock);
      w.machine.Frame(*w.rig, dt, &shown, &w.status);
      count = PrepareCharacters(shown);
    }
    JointOverlay(drawing ? count : 0);
    ImGui::Render();
    if (smoke && smoke->ScriptEnd()) smoke->SaveAuthored();  // the smoke test saves what it authored
    const bool last_frame = smoke && smoke->LastFrame();
    if (drawing) w.presenter.Present(index, count, w.view.camera(), shown.wireframe, last_frame);
    if (smoke && smoke->AfterFrame()) {
      status = smoke->WriteShot();
      break;
    }
  }
  const int closed = w.presenter.Close();
  return closed != 0 ? closed : status;
}

}  // namespace window_impl

int RunWindow(const Rig& rig, const Drawings& drawings, Scene scene, const WindowOptions& options) {
  window_impl::Viewer viewer(rig, drawings, std::move(scene), options);
  return viewer.Run();
}

}  // namespace posemorph::viewer
