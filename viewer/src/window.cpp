// SPDX-License-Identifier: MIT
// The interactive viewer: a GLFW window with a Vulkan swapchain. The rig is
// drawn with dynamic rendering, then Dear ImGui (its 1.86 Vulkan backend
// wants a render pass) draws the panel on top: the pose-space pad, gestures,
// stored paths, and the controls. This file: the main loop and the smoke
// test it can run; the rest of the window is in window_*.cpp (window_impl.h).
#include "window_impl.h"

namespace posemorph::viewer {
namespace window_impl {

int Viewer::Run() {
  glfwSetErrorCallback([](int, const char* text) { std::fprintf(stderr, "posemorph-view: GLFW: %s\n", text); });
  if (!glfwInit()) {
    std::fprintf(stderr, "posemorph-view: error: no display to open a window on (use --headless -o OUT.png)\n");
    return 1;
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  window_ = glfwCreateWindow(int(options_.width), int(options_.height), "posemorph", nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    std::fprintf(stderr, "posemorph-view: error: cannot open a window\n");
    return 1;
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
  int status = 0;
  if (!gpu_.Init(go, &problem) || glfwCreateWindowSurface(gpu_.instance(), window_, nullptr, &surface_) != VK_SUCCESS) {
    std::fprintf(stderr, "posemorph-view: error: %s\n",
                 problem.empty() ? "cannot create a window surface" : problem.c_str());
    glfwDestroyWindow(window_);
    glfwTerminate();
    return 1;
  }
  VkBool32 present = VK_FALSE;
  vkGetPhysicalDeviceSurfaceSupportKHR(gpu_.physical(), gpu_.queue_family(), surface_, &present);
  if (!present || !CreateSwapchain()) {
    std::fprintf(stderr, "posemorph-view: error: the device cannot present to this window\n");
    return 1;
  }
  renderer_ = std::make_unique<RigRenderer>();
  if (!renderer_->Init(gpu_, rig_, drawings_, sc_.format, kMaxCharacters, SceneFilter(rig_, scene_), &problem)) {
    std::fprintf(stderr, "posemorph-view: error: %s\n", problem.c_str());
    return 1;
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

  // The pad's domain: the baked grid, a square around it; its weight-field colours.
  const PoseSpaceGrid& g = rig_.grid();
  const double gw = g.cell * g.cells_x, gh = g.cell * g.cells_y;
  pad_span_ = std::max(gw, gh) * 1.1;
  pad_x0_ = g.origin_x + gw / 2 - pad_span_ / 2;
  pad_y0_ = g.origin_y + gh / 2 - pad_span_ / 2;
  const std::uint32_t N = rig_.pose_count();
  std::vector<double> w(N);
  field_.resize(std::size_t(field_cells_) * field_cells_);
  for (int j = 0; j < field_cells_; ++j)
    for (int i = 0; i < field_cells_; ++i) {
      WeightsJob wj;
      wj.rig = &rig_;
      wj.x = pad_x0_ + (i + 0.5) / field_cells_ * pad_span_;
      wj.y = pad_y0_ + (j + 0.5) / field_cells_ * pad_span_;
      wj.raw = {w.data(), N};
      wj.Run();
      const std::uint32_t top = std::uint32_t(std::max_element(w.begin(), w.end()) - w.begin());
      field_[std::size_t(j) * field_cells_ + i] = PoseColour(top, int(60 + 120 * std::clamp(w[top], 0.0, 1.0)));
    }

  const bool smoke = !options_.smoke_test.empty();
  auto last = std::chrono::steady_clock::now();
  auto timing_start = last;  // frames 10 .. half-way (before the resize), for the smoke test's fps
  double fps = 0;
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
    if (smoke) {
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
      if (smoke_frame_ == options_.smoke_frames * 3 / 4 && rig_.vertex_count() > 2) {
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
        edit_.targets = {Eigen::Vector2d(p.data[0], p.data[1]), Eigen::Vector2d(p.data[2 * far], p.data[2 * far + 1])};
      }
      if (edit_.on && edit_.targets.size() == 2)
        edit_.targets[1].x() += 0.2 * rig_.bounding_box_diagonal() / options_.smoke_frames;
    }
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
    ImGui::Render();
    const bool last_frame = smoke && smoke_frame_ + 1 >= options_.smoke_frames;
    if (last_frame && !options_.description.empty()) {
      // The smoke test saves what it authored: the gesture and the edited pose.
      SaveGesture();
      std::printf("%s\n", status_.c_str());
      SavePose();
      std::printf("%s\n", status_.c_str());
    }
    Frame(last_frame);
    if (smoke && smoke_frame_ == 10) timing_start = std::chrono::steady_clock::now();
    // Half-way, the smoke test resizes the window: the swapchain is rebuilt under validation.
    if (smoke && smoke_frame_ == options_.smoke_frames / 2) {
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - timing_start).count();
      if (smoke_frame_ > 10) fps = (smoke_frame_ - 10) / seconds;
      glfwSetWindowSize(window_, int(options_.width) - 100, int(options_.height) - 60);
    }
    if (smoke && ++smoke_frame_ >= options_.smoke_frames) {
      VkCheck(vkWaitForFences(gpu_.device(), 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
      if (!shot_.buffer) {
        std::fprintf(stderr, "posemorph-view: error: no frame was drawn\n");
        status = 1;
      } else {
        // Swapchain images are BGRA or RGBA; the PNG wants RGBA.
        std::vector<unsigned char> rgba(static_cast<unsigned char*>(shot_.mapped),
                                        static_cast<unsigned char*>(shot_.mapped) + shot_.size);
        if (sc_.format == VK_FORMAT_B8G8R8A8_UNORM || sc_.format == VK_FORMAT_B8G8R8A8_SRGB)
          for (std::size_t p = 0; p < rgba.size(); p += 4) std::swap(rgba[p], rgba[p + 2]);
        if (!WritePng(options_.smoke_test, rgba.data(), sc_.extent.width, sc_.extent.height, &problem)) {
          std::fprintf(stderr, "posemorph-view: error: %s\n", problem.c_str());
          status = 1;
        } else {
          std::printf(
              "wrote %s (%ux%u window, %u frames, pad dragged to (%.3f, %.3f), %u character(s), %.1f fps at %ux%u, "
              "%s)\n",
              options_.smoke_test.c_str(), sc_.extent.width, sc_.extent.height, smoke_frame_, scene_.x, scene_.y,
              SceneCharacters(rig_, scene_), fps, options_.width, options_.height, gpu_.device_name().c_str());
          std::printf("camera: zoom %.4g pixels per unit at (%.2f, %.2f), %s\n", camera_.zoom, camera_.centre.x,
                      camera_.centre.y, fit_ == Fit::kNone ? "zoomed and panned by the user" : "fitted");
        }
      }
      break;
    }
  }

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
  return status;
}

}  // namespace window_impl

int RunWindow(const Rig& rig, const Drawings& drawings, Scene scene, const WindowOptions& options) {
  window_impl::Viewer viewer(rig, drawings, scene, options);
  return viewer.Run();
}

}  // namespace posemorph::viewer
