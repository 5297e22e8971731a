// SPDX-License-Identifier: MIT
#include "gpu.h"

#include <cstdio>
#include <cstring>

namespace posemorph::viewer {

void VkCheck(VkResult result, const char* call) {
  if (result == VK_SUCCESS) return;
  const char* what = result == VK_ERROR_OUT_OF_HOST_MEMORY      ? "out of host memory"
                     : result == VK_ERROR_OUT_OF_DEVICE_MEMORY  ? "out of GPU memory"
                     : result == VK_ERROR_DEVICE_LOST           ? "the GPU device was lost"
                     : result == VK_ERROR_INITIALIZATION_FAILED ? "initialisation failed"
                     : result == VK_ERROR_TOO_MANY_OBJECTS      ? "too many objects"
                     : result == VK_ERROR_FORMAT_NOT_SUPPORTED  ? "format not supported"
                                                                : "failed";
  throw GpuError(std::string("Vulkan ") + call + ": " + what + " (VkResult " + std::to_string(int(result)) + ")");
}

VKAPI_ATTR VkBool32 VKAPI_CALL Gpu::OnMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data, void* self) {
  if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
    ++static_cast<Gpu*>(self)->messages_;
    std::fprintf(stderr, "posemorph-view: validation: %s\n", data->pMessage);
  }
  return VK_FALSE;
}

bool Gpu::Init(const GpuOptions& options, std::string* error) {
  return CreateInstance(options, error) && PickDevice(error) && CreateDevice(options, error);
}

// The instance (Vulkan 1.3), with the validation layer and its message
// callback when asked for.
bool Gpu::CreateInstance(const GpuOptions& options, std::string* error) {
  auto fail = [&](const std::string& what) {
    *error = what;
    return false;
  };
  std::uint32_t api = 0;
  if (vkEnumerateInstanceVersion(&api) != VK_SUCCESS || api < VK_API_VERSION_1_3)
    return fail("Vulkan 1.3 is not available (install mesa-vulkan-drivers for the lavapipe software driver)");

  std::vector<const char*> layers, extensions = options.instance_extensions;
  if (options.validation) {
    std::uint32_t n = 0;
    VkCheck(vkEnumerateInstanceLayerProperties(&n, nullptr), "vkEnumerateInstanceLayerProperties");
    std::vector<VkLayerProperties> available(n);
    VkCheck(vkEnumerateInstanceLayerProperties(&n, available.data()), "vkEnumerateInstanceLayerProperties");
    bool found = false;
    for (const auto& l : available) found |= std::strcmp(l.layerName, "VK_LAYER_KHRONOS_validation") == 0;
    if (!found) return fail("the Vulkan validation layer is not installed (Debian: vulkan-validationlayers)");
    layers.push_back("VK_LAYER_KHRONOS_validation");
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "posemorph-view";
  app.apiVersion = VK_API_VERSION_1_3;
  VkDebugUtilsMessengerCreateInfoEXT messenger{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  messenger.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                          VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messenger.pfnUserCallback = &Gpu::OnMessage;
  messenger.pUserData = this;
  VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ici.pApplicationInfo = &app;
  ici.enabledLayerCount = std::uint32_t(layers.size());
  ici.ppEnabledLayerNames = layers.data();
  ici.enabledExtensionCount = std::uint32_t(extensions.size());
  ici.ppEnabledExtensionNames = extensions.data();
  if (options.validation) ici.pNext = &messenger;
  if (vkCreateInstance(&ici, nullptr, &instance_) != VK_SUCCESS) return fail("cannot create a Vulkan instance");
  if (options.validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    if (!create || create(instance_, &messenger, nullptr, &messenger_) != VK_SUCCESS)
      return fail("cannot install the validation message callback");
  }
  return true;
}

// The first device with Vulkan 1.3 and a graphics queue; a discrete GPU if there is one.
bool Gpu::PickDevice(std::string* error) {
  auto fail = [&](const std::string& what) {
    *error = what;
    return false;
  };
  std::uint32_t n = 0;
  VkCheck(vkEnumeratePhysicalDevices(instance_, &n, nullptr), "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> devices(n);
  VkCheck(vkEnumeratePhysicalDevices(instance_, &n, devices.data()), "vkEnumeratePhysicalDevices");
  int best_rank = -1;
  for (VkPhysicalDevice d : devices) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(d, &p);
    if (p.apiVersion < VK_API_VERSION_1_3) continue;
    std::uint32_t qn = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(d, &qn, nullptr);
    std::vector<VkQueueFamilyProperties> qs(qn);
    vkGetPhysicalDeviceQueueFamilyProperties(d, &qn, qs.data());
    for (std::uint32_t q = 0; q < qn; ++q) {
      if (!(qs[q].queueFlags & VK_QUEUE_GRAPHICS_BIT)) continue;
      const int rank = p.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU     ? 2
                       : p.deviceType == VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU ? 1
                                                                                : 0;
      if (rank > best_rank) best_rank = rank, physical_ = d, family_ = q, device_name_ = p.deviceName;
      break;
    }
  }
  if (!physical_) return fail("no Vulkan 1.3 device with a graphics queue");
  return true;
}

// The logical device (dynamic rendering, buffer device addresses, scalar
// layouts; wireframe where supported), its queue and a command pool.
bool Gpu::CreateDevice(const GpuOptions& options, std::string* error) {
  auto fail = [&](const std::string& what) {
    *error = what;
    return false;
  };
  const float priority = 1;
  VkDeviceQueueCreateInfo qci{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qci.queueFamilyIndex = family_;
  qci.queueCount = 1;
  qci.pQueuePriorities = &priority;
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  f13.dynamicRendering = VK_TRUE;
  f13.synchronization2 = VK_TRUE;
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  f12.bufferDeviceAddress = VK_TRUE;
  f12.scalarBlockLayout = VK_TRUE;
  f12.pNext = &f13;
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  VkPhysicalDeviceFeatures supported;
  vkGetPhysicalDeviceFeatures(physical_, &supported);
  features.features.fillModeNonSolid = supported.fillModeNonSolid;
  features.pNext = &f12;
  const char* swapchain = VK_KHR_SWAPCHAIN_EXTENSION_NAME;
  VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  dci.pNext = &features;
  dci.queueCreateInfoCount = 1;
  dci.pQueueCreateInfos = &qci;
  dci.enabledExtensionCount = options.swapchain ? 1 : 0;
  dci.ppEnabledExtensionNames = options.swapchain ? &swapchain : nullptr;
  if (vkCreateDevice(physical_, &dci, nullptr, &device_) != VK_SUCCESS)
    return fail("cannot create a Vulkan device on " + device_name_);
  vkGetDeviceQueue(device_, family_, 0, &queue_);
  VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pci.queueFamilyIndex = family_;
  if (vkCreateCommandPool(device_, &pci, nullptr, &pool_) != VK_SUCCESS) return fail("cannot create a command pool");
  return true;
}

Gpu::~Gpu() {
  if (device_) {
    vkDeviceWaitIdle(device_);  // in a destructor: nothing to report to
    if (pool_) vkDestroyCommandPool(device_, pool_, nullptr);
    vkDestroyDevice(device_, nullptr);
  }
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance_, messenger_, nullptr);
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
}

// Memory of the first type that fits `req` and has `flags`.
VkDeviceMemory Gpu::Allocate(const VkMemoryRequirements& req, VkMemoryPropertyFlags flags, const void* next) const {
  VkPhysicalDeviceMemoryProperties mp;
  vkGetPhysicalDeviceMemoryProperties(physical_, &mp);
  VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  mai.pNext = next;
  mai.allocationSize = req.size;
  for (std::uint32_t i = 0; i < mp.memoryTypeCount; ++i)
    if ((req.memoryTypeBits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & flags) == flags) {
      mai.memoryTypeIndex = i;
      break;
    }
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkCheck(vkAllocateMemory(device_, &mai, nullptr, &memory), "vkAllocateMemory");
  return memory;
}

Buffer Gpu::CreateBuffer(VkDeviceSize size, VkBufferUsageFlags usage) {
  Buffer b;
  b.size = size;
  VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bci.size = size;
  bci.usage = usage;
  VkCheck(vkCreateBuffer(device_, &bci, nullptr, &b.buffer), "vkCreateBuffer");
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(device_, b.buffer, &req);
  VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
  flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
  b.memory = Allocate(req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                      (usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) ? &flags : nullptr);
  VkCheck(vkBindBufferMemory(device_, b.buffer, b.memory, 0), "vkBindBufferMemory");
  VkCheck(vkMapMemory(device_, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped), "vkMapMemory");
  if (usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) {
    VkBufferDeviceAddressInfo info{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    info.buffer = b.buffer;
    b.address = vkGetBufferDeviceAddress(device_, &info);
  }
  return b;
}

void Gpu::Destroy(Buffer& b) {
  if (b.buffer) vkDestroyBuffer(device_, b.buffer, nullptr);
  if (b.memory) vkFreeMemory(device_, b.memory, nullptr);
  b = Buffer{};
}

Image Gpu::CreateImage(VkFormat format, std::uint32_t width, std::uint32_t height, std::uint32_t layers,
                       VkImageUsageFlags usage) {
  Image im;
  VkImageCreateInfo ici{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ici.imageType = VK_IMAGE_TYPE_2D;
  ici.format = format;
  ici.extent = {width, height, 1};
  ici.mipLevels = 1;
  ici.arrayLayers = layers;
  ici.samples = VK_SAMPLE_COUNT_1_BIT;
  ici.tiling = VK_IMAGE_TILING_OPTIMAL;
  ici.usage = usage;
  ici.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkCheck(vkCreateImage(device_, &ici, nullptr, &im.image), "vkCreateImage");
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(device_, im.image, &req);
  im.memory = Allocate(req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, nullptr);
  VkCheck(vkBindImageMemory(device_, im.image, im.memory, 0), "vkBindImageMemory");
  VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vci.image = im.image;
  vci.viewType =
      layers > 1 || (usage & VK_IMAGE_USAGE_SAMPLED_BIT) ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
  vci.format = format;
  vci.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, layers};
  VkCheck(vkCreateImageView(device_, &vci, nullptr, &im.view), "vkCreateImageView");
  return im;
}

void Gpu::Destroy(Image& i) {
  if (i.view) vkDestroyImageView(device_, i.view, nullptr);
  if (i.image) vkDestroyImage(device_, i.image, nullptr);
  if (i.memory) vkFreeMemory(device_, i.memory, nullptr);
  i = Image{};
}

void Gpu::RunOnce(const std::function<void(VkCommandBuffer)>& record) {
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = pool_;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd;
  VkCheck(vkAllocateCommandBuffers(device_, &ai, &cmd), "vkAllocateCommandBuffers");
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VkCheck(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
  record(cmd);
  VkCheck(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  VkCheck(vkQueueSubmit(queue_, 1, &si, VK_NULL_HANDLE), "vkQueueSubmit");
  VkCheck(vkQueueWaitIdle(queue_), "vkQueueWaitIdle");
  vkFreeCommandBuffers(device_, pool_, 1, &cmd);
}

void Transition(VkCommandBuffer cmd, VkImage image, std::uint32_t layers, VkImageLayout from, VkImageLayout to) {
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  b.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  b.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
  b.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  b.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, layers};
  VkDependencyInfo d{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  d.imageMemoryBarrierCount = 1;
  d.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &d);
}

}  // namespace posemorph::viewer
