// SPDX-License-Identifier: MIT
// An image to render into and read back: the headless capture and the frame tests.
#pragma once
#include <cstdint>
#include <functional>

#include "gpu.h"

namespace posemorph::viewer {

class OffscreenTarget {
 public:
  static constexpr VkFormat kFormat = VK_FORMAT_R8G8B8A8_UNORM;
  OffscreenTarget() = default;
  OffscreenTarget(const OffscreenTarget&) = delete;
  OffscreenTarget& operator=(const OffscreenTarget&) = delete;
  ~OffscreenTarget();
  void Init(Gpu& gpu, std::uint32_t width, std::uint32_t height);
  // Clears to an opaque background, lets `draw` record, copies the result out; waits.
  void Render(const std::function<void(VkCommandBuffer)>& draw, const float background[4]);
  const unsigned char* pixels() const { return static_cast<const unsigned char*>(readback_.mapped); }
  std::uint32_t width() const { return width_; }
  std::uint32_t height() const { return height_; }

 private:
  Gpu* gpu_ = nullptr;
  std::uint32_t width_ = 0, height_ = 0;
  Image color_;
  Buffer readback_;
};

}  // namespace posemorph::viewer
