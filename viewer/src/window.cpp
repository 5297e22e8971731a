// SPDX-License-Identifier: MIT
// The interactive viewer: a GLFW window with a Vulkan swapchain. The rig is
// drawn with dynamic rendering, then Dear ImGui (its 1.86 Vulkan backend
// wants a render pass) draws the panel on top: the pose-space pad, gestures,
// stored paths, and the controls. This file: opening and closing the window
// and the main loop; the smoke test's script is in window_smoke.cpp and the
// rest of the window in window_*.cpp (window_impl.h).
#include "window_impl.h"

namespace posemorph::viewer {
namespace window_impl {

// The window, the device, the swapchain, the renderer and the frame's sync
// objects. False (with a message) when any of them cannot be had.
bool Viewer::Open() {
  glfwSetErrorCallback([](int, const char* text) { std::fprintf(stderr, "posemorph-view: GLFW: %s\n", text); });
  if (!glfwInit()) {
    std::fprintf(stderr, "posemorph-view: error: no display to open a window on (use --headless -o OUT.png)\n");
    return false;
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  window_ = glfwCreateWindow(int(options_.width), int(options_.height), "posemorph", nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    std::fprintf(stderr, "posemorph-view: error: cannot open a window\n");
    return false;
  }
  glfwSetWindowUserPointer(window_, this);
  glfwSetFramebufferSizeCallback(
      window_, [](GLFWwindow* w, int, int) { static_cast<Viewer*>(glfwGetWindowUserPointer(w))->resized_ = true; });
  GpuOptions go;
  go.validation = options_.validation;
  go.swapchain = true;
  std::uint32_t n = 0;
  const char** needed = glfwGetRequiredInstanceExtensions(&n);
  go.instance_extensions.assign(needed, needed + n);
  std::string problem;
  if (!gpu_.Init(go, &problem) || glfwCreateWindowSurface(gpu_.instance(), window_, nullptr, &surface_) != VK_SUCCESS) {
    std::fprintf(stderr, "posemorph-view: error: %s\n",
                 problem.empty() ? "cannot create a window surface" : problem.c_str());
    glfwDestroyWindow(window_);
    glfwTerminate();
    return false;
  }
  VkBool32 present = VK_FALSE;
  vkGetPhysicalDeviceSurfaceSupportKHR(gpu_.physical(), gpu_.queue_family(), surface_, &present);
  if (!present || !CreateSwapchain()) {
    std::fprintf(stderr, "posemorph-view: error: the device cannot present to this window\n");
    return false;
  }
  renderer_ = std::make_unique<RigRenderer>();
  if (!renderer_->Init(gpu_, rig_, drawings_, sc_.format, kMaxCharacters, SceneFilter(rig_, scene_), &problem)) {
    std::fprintf(stderr, "posemorph-view: error: %s\n", problem.c_str());
    return false;
  }
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = gpu_.command_pool();
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCheck(vkAllocateCommandBuffers(gpu_.device(), &ai, &cmd_), "vkAllocateCommandBuffers");
  VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  fi.flags = VK_FENCE_CREATE_SIGNALED_BIT;
  VkCheck(vkCreateFence(gpu_.device(), &fi, nullptr, &fence_), "vkCreateFence");
  VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  VkCheck(vkCreateSemaphore(gpu_.device(), &si, nullptr, &acquired_), "vkCreateSemaphore");
  return true;
}

void Viewer::InitUi() {
  // Dear ImGui on the window and the swapchain's render pass.
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;
  ImGui::StyleColorsLight();
  ImGui_ImplGlfw_InitForVulkan(window_, true);
  VkDescriptorPoolSize ps{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16};
  VkDescriptorPoolCreateInfo dp{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  dp.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  dp.maxSets = 16;
  dp.poolSizeCount = 1;
  dp.pPoolSizes = &ps;
  VkCheck(vkCreateDescriptorPool(gpu_.device(), &dp, nullptr, &ui_pool_), "vkCreateDescriptorPool");
  ImGui_ImplVulkan_InitInfo ii{};
  ii.Instance = gpu_.instance();
  ii.PhysicalDevice = gpu_.physical();
  ii.Device = gpu_.device();
  ii.QueueFamily = gpu_.queue_family();
  ii.Queue = gpu_.queue();
  ii.DescriptorPool = ui_pool_;
  ii.MinImageCount = ii.ImageCount = std::uint32_t(sc_.images.size());
  ii.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  ImGui_ImplVulkan_Init(&ii, ui_pass_);
  gpu_.RunOnce([](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  ImGui_ImplVulkan_DestroyFontUploadObjects();
}

Viewer::PadField Viewer::PadFieldOf(const Rig& rig) const {
  // The pad's domain: the baked grid, a square around it; its weight-field colours.
  PadField f;
  const PoseSpaceGrid& g = rig.grid();
  const double gw = g.cell * g.cells_x, gh = g.cell * g.cells_y;
  f.span = std::max(gw, gh) * 1.1;
  f.x0 = g.origin_x + gw / 2 - f.span / 2;
  f.y0 = g.origin_y + gh / 2 - f.span / 2;
  const std::uint32_t N = rig.pose_count();
  std::vector<double> w(N);
  f.colours.resize(std::size_t(field_cells_) * field_cells_);
  for (int j = 0; j < field_cells_; ++j)
    for (int i = 0; i < field_cells_; ++i) {
      WeightsJob wj;
      wj.rig = &rig;
      wj.x = f.x0 + (i + 0.5) / field_cells_ * f.span;
      wj.y = f.y0 + (j + 0.5) / field_cells_ * f.span;
      wj.raw = {w.data(), N};
      wj.Run();
      const std::uint32_t top = std::uint32_t(std::max_element(w.begin(), w.end()) - w.begin());
      f.colours[std::size_t(j) * field_cells_ + i] = PoseColour(top, int(60 + 120 * std::clamp(w[top], 0.0, 1.0)));
    }
  return f;
}

void Viewer::BuildPadField() {
  PadField body = PadFieldOf(rig_);
  field_ = std::move(body.colours);
  pad_x0_ = body.x0, pad_y0_ = body.y0, pad_span_ = body.span;
  channel_fields_.clear();
  for (std::uint32_t c = 1; c < rig_.channel_count(); ++c) channel_fields_.push_back(PadFieldOf(*rig_.channel_rig(c)));
  if (rig_.channel_count() > 1 && scene_.channels.size() < rig_.channel_count() - 1) {
    const std::size_t given = scene_.channels.size();
    scene_.channels.resize(rig_.channel_count() - 1);
    for (std::size_t c = given; c < scene_.channels.size(); ++c) {
      const Rig& channel = *rig_.channel_rig(std::uint32_t(c + 1));
      scene_.channels[c].x = channel.pose_points()[0], scene_.channels[c].y = channel.pose_points()[1];
    }
  }
  play_channel_.assign(scene_.channels.size(), 0);
  for (std::size_t c = 0; c < scene_.channels.size(); ++c)
    if (!scene_.channels[c].path.empty()) play_channel_[c] = 1;
}

int Viewer::Run() {
  if (!Open()) return 1;
  InitUi();
  BuildPadField();
  const bool smoke = !options_.smoke_test.empty();
  int status = 0;
  auto last = std::chrono::steady_clock::now();
  smoke_timing_start_ = last;
  while (!glfwWindowShouldClose(window_)) {
    glfwPollEvents();
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window_, &fw, &fh);
    if (fw == 0 || fh == 0) {  // minimised: wait for the window to come back
      glfwWaitEvents();
      continue;
    }
    const auto now = std::chrono::steady_clock::now();
    clock_ += smoke ? 1.0 / 60 : std::chrono::duration<double>(now - last).count();
    last = now;
    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    if (smoke) SmokeInput();
    ImGui::NewFrame();
    BuildUi();
    if (smoke && smoke_frame_ == options_.smoke_frames / 2 + 2) {
      ImGui::GetIO().MouseWheel = 3;  // the cursor was put in the view before NewFrame
    }
    if (sc_.extent.width > kPanelWidth + 8) {
      CameraInput(std::int32_t(kPanelWidth), sc_.extent.width - std::uint32_t(kPanelWidth), sc_.extent.height);
      if (edit_.on)
        EditInput(std::int32_t(kPanelWidth), sc_.extent.width - std::uint32_t(kPanelWidth), sc_.extent.height);
    }
    std::uint32_t index = 0, count = 0;
    Scene shown;
    const bool drawing = BeginFrame(&index, &count, &shown);
    JointOverlay(drawing ? count : 0);
    ImGui::Render();
    const bool last_frame = smoke && smoke_frame_ + 1 >= options_.smoke_frames;
    if (last_frame && !options_.description.empty()) {
      // The smoke test saves what it authored: the gesture and the edited pose.
      SaveGesture();
      std::printf("%s\n", status_.c_str());
      SavePose();
      std::printf("%s\n", status_.c_str());
    }
    if (drawing) EndFrame(index, count, shown, last_frame);
    if (smoke) SmokeAfterFrame();
    if (smoke && ++smoke_frame_ >= options_.smoke_frames) {
      status = WriteSmokeShot();
      break;
    }
  }
  const int closed = Close();
  return closed != 0 ? closed : status;
}

// Everything Open and InitUi made, in reverse; 3 when the validation layer spoke.
int Viewer::Close() {
  VkCheck(vkDeviceWaitIdle(gpu_.device()), "vkDeviceWaitIdle");
  ImGui_ImplVulkan_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  if (shot_.buffer) gpu_.Destroy(shot_);
  vkDestroyDescriptorPool(gpu_.device(), ui_pool_, nullptr);
  vkDestroySemaphore(gpu_.device(), acquired_, nullptr);
  vkDestroyFence(gpu_.device(), fence_, nullptr);
  DestroySwapchain();
  vkDestroyRenderPass(gpu_.device(), ui_pass_, nullptr);
  renderer_.reset();
  vkDestroySurfaceKHR(gpu_.instance(), surface_, nullptr);
  glfwDestroyWindow(window_);
  glfwTerminate();
  if (gpu_.validation_messages() > 0) {
    std::fprintf(stderr, "posemorph-view: %d validation message(s)\n", gpu_.validation_messages());
    return 3;
  }
  return 0;
}

}  // namespace window_impl

int RunWindow(const Rig& rig, const Drawings& drawings, Scene scene, const WindowOptions& options) {
  window_impl::Viewer viewer(rig, drawings, scene, options);
  return viewer.Run();
}

}  // namespace posemorph::viewer
