// SPDX-License-Identifier: MIT
// Draws characters of one baked rig: the runtime's positions for K
// characters go into one buffer that the vertex shader reads (GPU skinning,
// one instanced draw for the crowd); the fragment shader cross-fades the
// character's drawings with its texture weights (premultiplied alpha).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "camera.h"
#include "gpu.h"
#include "gpu_layout.h"
#include "posemorph/draw_list.h"
#include "posemorph/image_reference.h"
#include "posemorph/rig.h"

namespace posemorph::viewer {

// The rig's drawings, premultiplied RGBA8, all resampled to one size.
struct Drawings {
  std::uint32_t width = 0, height = 0;
  std::vector<std::vector<unsigned char>> rgba;  // one per pose
};
// Reads each pose's image (rig.pose_image) from `dir`. False with a message
// naming the file when one is missing or unreadable, or the rig has no uvs.
// Limits on the drawings the viewer loads (rig files are hostile input):
// each at most this many pixels, and so the texture array they share. Image
// references must stay inside `dir` (relative, no '..').
constexpr std::uint64_t kMaxDrawingPixels = std::uint64_t(1) << 24;  // 4096 x 4096
// (posemorph/image_reference.h: the runtime's check, which the bake's
// textured contact sheet uses too).
inline bool ImageReferenceStaysInside(const std::string& reference) {
  return posemorph::ImageReferenceStaysInside(StringView{reference.data(), reference.size()});
}
// Control characters as \xNN and at most `max` characters (then "..."):
// names from a rig file or the command line, before they reach a terminal.
std::string Printable(const std::string& text, std::size_t max = 200);
bool LoadDrawings(const Rig& rig, const std::string& dir, Drawings* out, std::string* error);

constexpr std::uint32_t kDrawingsPerCharacter = kMaxBlendDrawings;
using gpu::Instance;
// The GPU form of a character's draw list: its transform and drawings
// (unused slots repeat the first drawing at weight 0).
Instance ToInstance(const DrawList& list);

// How the drawings of a character are combined (README "Drawing a character").
enum class Blend {
  kExact,           // one pass, the weighted sum of every drawing shown (blend.frag)
  kSequentialOver,  // one pass per drawing, each "over" the last at w_k / (w_0 + ... + w_k)
};

class RigRenderer {
 public:
  RigRenderer() = default;
  RigRenderer(const RigRenderer&) = delete;
  RigRenderer& operator=(const RigRenderer&) = delete;
  ~RigRenderer();

  // The drawings are sampled with `filter` (nearest for pixel art).
  bool Init(Gpu& gpu, const Rig& rig, const Drawings& drawings, VkFormat target_format, std::uint32_t max_instances,
            TextureFilter filter, std::string* error);
  // Written by the caller before Record: instance-major float x, y per vertex.
  float* positions() { return static_cast<float*>(positions_.mapped); }
  Instance* instances() { return static_cast<Instance*>(instances_.mapped); }
  std::uint32_t max_instances() const { return max_instances_; }
  // Inside dynamic rendering on a target of the format given to Init: the
  // camera looks at the world through the viewport of `width` x `height`
  // pixels at (x, y) of the target.
  void Record(VkCommandBuffer cmd, std::uint32_t instance_count, const Camera& camera, std::uint32_t width,
              std::uint32_t height, bool wireframe, std::int32_t x = 0, std::int32_t y = 0,
              Blend blend = Blend::kExact) const;

 private:
  Gpu* gpu_ = nullptr;
  std::uint32_t vertex_count_ = 0, index_count_ = 0, max_instances_ = 0;
  Buffer indices_, uvs_, positions_, instances_;
  Image drawings_;
  VkSampler sampler_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline fill_ = VK_NULL_HANDLE, lines_ = VK_NULL_HANDLE;
};

// An image to render into and read back (headless capture).
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

bool WritePng(const std::string& path, const unsigned char* rgba, std::uint32_t width, std::uint32_t height,
              std::string* error);
// The tolerant comparison of two RGBA8 frames of the same size: a pixel
// differs when a channel is off by more than 3 of 255. `diff`, if given,
// becomes an image of the differences (white = equal, red = off by 32+).
struct FrameDifference {
  std::size_t differing = 0, pixels = 0;
  int worst = 0;
  double share() const { return pixels ? double(differing) / double(pixels) : 0.0; }
};
FrameDifference CompareFrames(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b,
                              std::vector<unsigned char>* diff = nullptr);

bool ReadPng(const std::string& path, std::vector<unsigned char>* rgba, std::uint32_t* width, std::uint32_t* height,
             std::string* error);

}  // namespace posemorph::viewer
