// SPDX-License-Identifier: MIT
// The window's presenter: the GLFW window, the device, the swapchain (rebuilt
// on resize), the renderer of the characters and Dear ImGui's Vulkan
// backend. Each frame it acquires an image, records the characters and then
// the panel into it, and presents; on request it keeps a copy of the image
// (a screenshot). It knows nothing of the pad, edit mode or the smoke test.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "gpu.h"
#include "rig_renderer.h"
#include "window.h"
#include "window_common.h"

namespace posemorph::viewer::window_impl {

class Presenter {
 public:
  // The window, the device, the swapchain, the renderer (up to
  // kMaxCharacters of `rig` with `filter`), the frame's sync objects and
  // Dear ImGui on them. False, with a message on stderr, when any of them
  // cannot be had (then Close is not needed).
  bool Open(const WindowOptions& options, const Rig& rig, const Drawings& drawings, TextureFilter filter);
  // Everything Open made, in reverse; 3 when the validation layer spoke, else 0.
  int Close();
  // Another rig to draw (a --watch re-bake): a new renderer for it, made
  // after the device is idle; the old one stays, and false comes back with
  // the message, when the new one cannot be made.
  bool SwapRig(const Rig& rig, const Drawings& drawings, TextureFilter filter, std::string* problem);

  GLFWwindow* window() const { return window_; }
  VkExtent2D extent() const { return sc_.extent; }
  RigRenderer& renderer() { return *renderer_; }
  const std::string& device_name() const { return gpu_.device_name(); }
  // The window's size in screen coordinates (the swapchain follows it).
  void Resize(int width, int height) { glfwSetWindowSize(window_, width, height); }

  // Waits for the last frame, rebuilds the swapchain after a resize and
  // acquires an image; false when there is none to draw into this time.
  bool Acquire(std::uint32_t* index);
  // Records `count` characters seen through `camera` in the view right of
  // the panel, then ImGui's draw data, into image `index`, submits and
  // presents it; with `screenshot`, a copy of the image is kept.
  void Present(std::uint32_t index, std::uint32_t count, const Camera& camera, bool wireframe, bool screenshot);
  // The last kept copy as RGBA rows (waiting for the GPU); false when none was kept.
  bool Screenshot(std::vector<unsigned char>* rgba);

 private:
  struct Swapchain {
    VkSwapchainKHR handle = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent2D extent{0, 0};
    std::vector<VkImage> images;
    std::vector<VkImageView> views;
    std::vector<VkFramebuffer> framebuffers;
    std::vector<VkSemaphore> rendered;  // one per image: presentation waits on it
  };
  void InitUi();
  bool CreateSwapchain();  // window_swapchain.cpp
  void CreateUiPass();
  void CreateImageViews();
  void DestroySwapchain();
  void Record(std::uint32_t index, std::uint32_t count, const Camera& camera, bool wireframe, bool screenshot);
  void SubmitAndPresent(std::uint32_t index);

  GLFWwindow* window_ = nullptr;
  Gpu gpu_;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  Swapchain sc_;
  VkRenderPass ui_pass_ = VK_NULL_HANDLE;
  VkDescriptorPool ui_pool_ = VK_NULL_HANDLE;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkSemaphore acquired_ = VK_NULL_HANDLE;
  std::unique_ptr<RigRenderer> renderer_;  // released before the device goes
  Buffer shot_;
  bool resized_ = false;
};

}  // namespace posemorph::viewer::window_impl
