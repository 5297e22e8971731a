// SPDX-License-Identifier: MIT
#include "offscreen_target.h"

#include <cstring>

namespace posemorph::viewer {

OffscreenTarget::~OffscreenTarget() {
  if (!gpu_) return;
  gpu_->Destroy(color_);
  gpu_->Destroy(readback_);
}

void OffscreenTarget::Init(Gpu& gpu, std::uint32_t width, std::uint32_t height) {
  gpu_ = &gpu;
  width_ = width;
  height_ = height;
  color_ =
      gpu.CreateImage(kFormat, width, height, 1, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  readback_ = gpu.CreateBuffer(4ull * width * height, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
}

void OffscreenTarget::Render(const std::function<void(VkCommandBuffer)>& draw, const float background[4]) {
  gpu_->RunOnce([&](VkCommandBuffer cmd) {
    Transition(cmd, color_.image, 1, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    color.imageView = color_.view;
    color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    std::memcpy(color.clearValue.color.float32, background, 4 * sizeof(float));
    VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
    ri.renderArea = {{0, 0}, {width_, height_}};
    ri.layerCount = 1;
    ri.colorAttachmentCount = 1;
    ri.pColorAttachments = &color;
    vkCmdBeginRendering(cmd, &ri);
    draw(cmd);
    vkCmdEndRendering(cmd);
    Transition(cmd, color_.image, 1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {width_, height_, 1};
    vkCmdCopyImageToBuffer(cmd, color_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.buffer, 1, &copy);
  });
}

}  // namespace posemorph::viewer
