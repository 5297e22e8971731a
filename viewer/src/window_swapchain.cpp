// SPDX-License-Identifier: MIT
// The window's Vulkan swapchain: created for the framebuffer size, rebuilt on resize.
#include <algorithm>
#include <vector>

#include "window_presenter.h"

namespace posemorph::viewer::window_impl {

bool Presenter::CreateSwapchain() {
  VkSurfaceCapabilitiesKHR caps;
  vkGetPhysicalDeviceSurfaceCapabilitiesKHR(gpu_.physical(), surface_, &caps);
  int fw = 0, fh = 0;
  glfwGetFramebufferSize(window_, &fw, &fh);
  if (fw == 0 || fh == 0) return false;  // minimised
  VkExtent2D extent =
      caps.currentExtent.width != 0xFFFFFFFFu ? caps.currentExtent : VkExtent2D{std::uint32_t(fw), std::uint32_t(fh)};
  if (extent.width == 0 || extent.height == 0) return false;
  std::uint32_t n = 0;
  vkGetPhysicalDeviceSurfaceFormatsKHR(gpu_.physical(), surface_, &n, nullptr);
  std::vector<VkSurfaceFormatKHR> formats(n);
  vkGetPhysicalDeviceSurfaceFormatsKHR(gpu_.physical(), surface_, &n, formats.data());
  VkSurfaceFormatKHR chosen = formats[0];
  for (const auto& f : formats)  // UNORM like the headless frames, so both look the same
    if (f.format == VK_FORMAT_B8G8R8A8_UNORM || f.format == VK_FORMAT_R8G8B8A8_UNORM) chosen = f;
  const std::uint32_t count =
      std::min(caps.maxImageCount ? caps.maxImageCount : 8u, std::max(caps.minImageCount + 1, 2u));
  VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  ci.surface = surface_;
  ci.minImageCount = count;
  ci.imageFormat = chosen.format;
  ci.imageColorSpace = chosen.colorSpace;
  ci.imageExtent = extent;
  ci.imageArrayLayers = 1;
  ci.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.preTransform = caps.currentTransform;
  ci.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  ci.presentMode = VK_PRESENT_MODE_FIFO_KHR;
  ci.clipped = VK_TRUE;
  ci.oldSwapchain = sc_.handle;
  VkSwapchainKHR fresh = VK_NULL_HANDLE;
  if (vkCreateSwapchainKHR(gpu_.device(), &ci, nullptr, &fresh) != VK_SUCCESS) return false;
  DestroySwapchain();
  sc_.handle = fresh;
  sc_.extent = extent;
  const bool format_changed = sc_.format != chosen.format;
  sc_.format = chosen.format;
  vkGetSwapchainImagesKHR(gpu_.device(), sc_.handle, &n, nullptr);
  sc_.images.resize(n);
  vkGetSwapchainImagesKHR(gpu_.device(), sc_.handle, &n, sc_.images.data());

  if (format_changed || !ui_pass_) CreateUiPass();
  CreateImageViews();
  return true;
}

// The panel's render pass: it loads what the characters' pass drew and
// leaves the image ready to present.
void Presenter::CreateUiPass() {
  if (ui_pass_) vkDestroyRenderPass(gpu_.device(), ui_pass_, nullptr);
  VkAttachmentDescription at{};
  at.format = sc_.format;
  at.samples = VK_SAMPLE_COUNT_1_BIT;
  at.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;  // the rig is already there
  at.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  at.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  at.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  at.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  at.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription sub{};
  sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  sub.colorAttachmentCount = 1;
  sub.pColorAttachments = &ref;
  VkSubpassDependency dep{};
  dep.srcSubpass = VK_SUBPASS_EXTERNAL;
  dep.dstSubpass = 0;
  dep.srcStageMask = dep.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  dep.srcAccessMask = dep.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_COLOR_ATTACHMENT_READ_BIT;
  VkRenderPassCreateInfo rp{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  rp.attachmentCount = 1;
  rp.pAttachments = &at;
  rp.subpassCount = 1;
  rp.pSubpasses = &sub;
  rp.dependencyCount = 1;
  rp.pDependencies = &dep;
  VkCheck(vkCreateRenderPass(gpu_.device(), &rp, nullptr, &ui_pass_), "vkCreateRenderPass");
}

// Per swapchain image: a view, the panel's framebuffer and the semaphore its
// rendering signals.
void Presenter::CreateImageViews() {
  const VkExtent2D extent = sc_.extent;
  for (VkImage image : sc_.images) {
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = image;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = sc_.format;
    vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView view;
    VkCheck(vkCreateImageView(gpu_.device(), &vi, nullptr, &view), "vkCreateImageView");
    sc_.views.push_back(view);
    VkFramebufferCreateInfo fi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fi.renderPass = ui_pass_;
    fi.attachmentCount = 1;
    fi.pAttachments = &view;
    fi.width = extent.width;
    fi.height = extent.height;
    fi.layers = 1;
    VkFramebuffer fb;
    VkCheck(vkCreateFramebuffer(gpu_.device(), &fi, nullptr, &fb), "vkCreateFramebuffer");
    sc_.framebuffers.push_back(fb);
    VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore s;
    VkCheck(vkCreateSemaphore(gpu_.device(), &si, nullptr, &s), "vkCreateSemaphore");
    sc_.rendered.push_back(s);
  }
}

void Presenter::DestroySwapchain() {
  VkDevice dev = gpu_.device();
  VkCheck(vkDeviceWaitIdle(dev), "vkDeviceWaitIdle");
  for (VkFramebuffer f : sc_.framebuffers) vkDestroyFramebuffer(dev, f, nullptr);
  for (VkImageView v : sc_.views) vkDestroyImageView(dev, v, nullptr);
  for (VkSemaphore s : sc_.rendered) vkDestroySemaphore(dev, s, nullptr);
  if (sc_.handle) vkDestroySwapchainKHR(dev, sc_.handle, nullptr);
  sc_.framebuffers.clear(), sc_.views.clear(), sc_.rendered.clear(), sc_.images.clear();
  sc_.handle = VK_NULL_HANDLE;
}

}  // namespace posemorph::viewer::window_impl
