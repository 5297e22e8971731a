// SPDX-License-Identifier: MIT
// The presenter (window_presenter.h): opening and closing the window, the
// device and Dear ImGui's backend, and each frame's acquire, record, submit
// and present. The swapchain itself is in window_swapchain.cpp.
#include "window_presenter.h"

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_vulkan.h>

#include <cstdio>
#include <cstring>
#include <utility>

namespace posemorph::viewer::window_impl {

bool Presenter::Open(const WindowOptions& options, const Rig& rig, const Drawings& drawings, TextureFilter filter) {
  glfwSetErrorCallback([](int, const char* text) { std::fprintf(stderr, "posemorph-view: GLFW: %s\n", text); });
  if (!glfwInit()) {
    std::fprintf(stderr, "posemorph-view: error: no display to open a window on (use --headless -o OUT.png)\n");
    return false;
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  window_ = glfwCreateWindow(int(options.width), int(options.height), "posemorph", nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    std::fprintf(stderr, "posemorph-view: error: cannot open a window\n");
    return false;
  }
  glfwSetWindowUserPointer(window_, this);
  glfwSetFramebufferSizeCallback(
      window_, [](GLFWwindow* w, int, int) { static_cast<Presenter*>(glfwGetWindowUserPointer(w))->resized_ = true; });
  GpuOptions go;
  go.validation = options.validation;
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
  if (!renderer_->Init(gpu_, rig, drawings, sc_.format, kMaxCharacters, filter, &problem)) {
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
  InitUi();
  return true;
}

bool Presenter::SwapRig(const Rig& rig, const Drawings& drawings, TextureFilter filter, std::string* problem) {
  VkCheck(vkDeviceWaitIdle(gpu_.device()), "vkDeviceWaitIdle");
  auto renderer = std::make_unique<RigRenderer>();
  if (!renderer->Init(gpu_, rig, drawings, sc_.format, kMaxCharacters, filter, problem)) return false;
  renderer_ = std::move(renderer);
  return true;
}

// Dear ImGui on the window and the swapchain's render pass.
void Presenter::InitUi() {
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

int Presenter::Close() {
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

bool Presenter::Acquire(std::uint32_t* index) {
  VkDevice dev = gpu_.device();
  VkCheck(vkWaitForFences(dev, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  if (resized_ || sc_.handle == VK_NULL_HANDLE) {
    resized_ = false;
    if (!CreateSwapchain()) return false;
    ImGui_ImplVulkan_SetMinImageCount(std::uint32_t(sc_.images.size()));
  }
  const VkResult acquired = vkAcquireNextImageKHR(dev, sc_.handle, UINT64_MAX, acquired_, VK_NULL_HANDLE, index);
  if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
    resized_ = true;
    return false;
  }
  VkCheck(vkResetFences(dev, 1, &fence_), "vkResetFences");
  return true;
}

void Presenter::Present(std::uint32_t index, std::uint32_t count, const Camera& camera, bool wireframe,
                        bool screenshot) {
  Record(index, count, camera, wireframe, screenshot);
  SubmitAndPresent(index);
}

// The characters, then the panel; and a copy of the image for a screenshot.
void Presenter::Record(std::uint32_t index, std::uint32_t count, const Camera& camera, bool wireframe,
                       bool screenshot) {
  const std::uint32_t view_w = sc_.extent.width > kPanelWidth ? sc_.extent.width - std::uint32_t(kPanelWidth) : 1;
  VkCheck(vkResetCommandBuffer(cmd_, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VkCheck(vkBeginCommandBuffer(cmd_, &bi), "vkBeginCommandBuffer");
  const VkImage image = sc_.images[index];
  Transition(cmd_, image, 1, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  VkRenderingAttachmentInfo colour{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  colour.imageView = sc_.views[index];
  colour.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  colour.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  colour.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  std::memcpy(colour.clearValue.color.float32, kBackground, sizeof kBackground);
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = {{0, 0}, sc_.extent};
  ri.layerCount = 1;
  ri.colorAttachmentCount = 1;
  ri.pColorAttachments = &colour;
  vkCmdBeginRendering(cmd_, &ri);
  const std::int32_t x0 = std::int32_t(kPanelWidth);
  if (count > 0 && sc_.extent.width > kPanelWidth + 8)
    renderer_->Record(cmd_, count, camera, view_w, sc_.extent.height, wireframe, x0, 0);
  vkCmdEndRendering(cmd_);
  VkRenderPassBeginInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  rp.renderPass = ui_pass_;
  rp.framebuffer = sc_.framebuffers[index];
  rp.renderArea = {{0, 0}, sc_.extent};
  vkCmdBeginRenderPass(cmd_, &rp, VK_SUBPASS_CONTENTS_INLINE);
  ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd_);
  vkCmdEndRenderPass(cmd_);
  if (screenshot) {
    if (shot_.buffer) gpu_.Destroy(shot_);
    shot_ = gpu_.CreateBuffer(4ull * sc_.extent.width * sc_.extent.height, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    Transition(cmd_, image, 1, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {sc_.extent.width, sc_.extent.height, 1};
    vkCmdCopyImageToBuffer(cmd_, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, shot_.buffer, 1, &copy);
    Transition(cmd_, image, 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
  }
  VkCheck(vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");
}

void Presenter::SubmitAndPresent(std::uint32_t index) {
  const VkPipelineStageFlags wait_stage = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.waitSemaphoreCount = 1;
  si.pWaitSemaphores = &acquired_;
  si.pWaitDstStageMask = &wait_stage;
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd_;
  si.signalSemaphoreCount = 1;
  si.pSignalSemaphores = &sc_.rendered[index];
  VkCheck(vkQueueSubmit(gpu_.queue(), 1, &si, fence_), "vkQueueSubmit");
  VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  pi.waitSemaphoreCount = 1;
  pi.pWaitSemaphores = &sc_.rendered[index];
  pi.swapchainCount = 1;
  pi.pSwapchains = &sc_.handle;
  pi.pImageIndices = &index;
  const VkResult presented = vkQueuePresentKHR(gpu_.queue(), &pi);
  if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR) resized_ = true;
}

bool Presenter::Screenshot(std::vector<unsigned char>* rgba) {
  VkCheck(vkWaitForFences(gpu_.device(), 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  if (!shot_.buffer) return false;
  // Swapchain images are BGRA or RGBA; the PNG wants RGBA.
  rgba->assign(static_cast<unsigned char*>(shot_.mapped), static_cast<unsigned char*>(shot_.mapped) + shot_.size);
  if (sc_.format == VK_FORMAT_B8G8R8A8_UNORM || sc_.format == VK_FORMAT_B8G8R8A8_SRGB)
    for (std::size_t p = 0; p < rgba->size(); p += 4) std::swap((*rgba)[p], (*rgba)[p + 2]);
  return true;
}

}  // namespace posemorph::viewer::window_impl
