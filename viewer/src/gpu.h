// SPDX-License-Identifier: MIT
// A Vulkan 1.3 device for drawing rigs: instance (optionally with the
// Khronos validation layer, whose messages are counted), one graphics queue,
// buffers with device addresses, one-shot command submission.
#pragma once
#include <vulkan/vulkan.h>

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace posemorph::viewer {

// A Vulkan call that failed: which call and what it returned (out of host or
// device memory says so). Everything that creates or submits checks its
// result through VkCheck; posemorph-view turns the exception into one line
// naming the rig and an exit status of 1.
struct GpuError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
void VkCheck(VkResult result, const char* call);

struct GpuOptions {
  bool validation = false;                       // enable VK_LAYER_KHRONOS_validation; its messages are counted
  std::vector<const char*> instance_extensions;  // e.g. what GLFW needs for a surface
  bool swapchain = false;                        // enable VK_KHR_swapchain on the device
};

struct Buffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;
  VkDeviceAddress address = 0;
  VkDeviceSize size = 0;
};

struct Image {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
};

class Gpu {
 public:
  Gpu() = default;
  Gpu(const Gpu&) = delete;
  Gpu& operator=(const Gpu&) = delete;
  ~Gpu();

  // False with a message when no Vulkan 1.3 device (or the requested layer) is there.
  bool Init(const GpuOptions& options, std::string* error);

  // Host-visible, mapped, with a device address when usage asks for one.
  Buffer CreateBuffer(VkDeviceSize size, VkBufferUsageFlags usage);
  void Destroy(Buffer& b);
  Image CreateImage(VkFormat format, std::uint32_t width, std::uint32_t height, std::uint32_t layers,
                    VkImageUsageFlags usage);
  void Destroy(Image& i);
  // Records into a fresh command buffer, submits it and waits.
  void RunOnce(const std::function<void(VkCommandBuffer)>& record);

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physical() const { return physical_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  std::uint32_t queue_family() const { return family_; }
  VkCommandPool command_pool() const { return pool_; }
  const std::string& device_name() const { return device_name_; }
  // Validation-layer messages of severity warning or error so far.
  int validation_messages() const { return messages_; }

 private:
  // Init's steps.
  bool CreateInstance(const GpuOptions& options, std::string* error);
  bool PickDevice(std::string* error);
  bool CreateDevice(const GpuOptions& options, std::string* error);
  VkDeviceMemory Allocate(const VkMemoryRequirements& req, VkMemoryPropertyFlags flags, const void* next) const;
  static VKAPI_ATTR VkBool32 VKAPI_CALL OnMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                  VkDebugUtilsMessageTypeFlagsEXT type,
                                                  const VkDebugUtilsMessengerCallbackDataEXT* data, void* self);

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  std::uint32_t family_ = 0;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  std::string device_name_;
  int messages_ = 0;
};

// Layout transition of a colour image (all layers) inside a command buffer.
void Transition(VkCommandBuffer cmd, VkImage image, std::uint32_t layers, VkImageLayout from, VkImageLayout to);

}  // namespace posemorph::viewer
