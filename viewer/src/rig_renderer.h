// SPDX-License-Identifier: MIT
// Draws characters of one baked rig: the runtime's positions for K
// characters go into one buffer that the vertex shader reads (GPU skinning,
// one instanced draw for the crowd); the fragment shader cross-fades the
// character's drawings with its texture weights (premultiplied alpha).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "camera.h"
#include "gpu.h"
#include "drawings.h"
#include "gpu_layout.h"
#include "offscreen_target.h"
#include "png_io.h"
#include "posemorph/draw_list.h"
#include "posemorph/image_reference.h"
#include "posemorph/rig.h"

namespace posemorph::viewer {

constexpr std::uint32_t kDrawingsPerCharacter = kMaxBlendDrawings;
using gpu::Instance;
// The GPU form of a character's draw list: its transform, drawings (unused
// slots repeat the first drawing at weight 0) and premultiplied colour.
Instance ToInstance(const DrawList& list);

// How the drawings of a character are combined (docs/runtime.md "Drawing a character").
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
  // Character k's drawings, colour and parts' opacities and, for a layered
  // character, the order its parts are drawn in (list.parts, which points
  // into the rig).
  void SetCharacter(std::uint32_t k, const DrawList& list);
  // A character with control channels: attachment a's renderer (its own
  // positions, instances and drawings; PrepareScene fills them), or null.
  RigRenderer* attachment(std::uint32_t a) { return a < attachments_.size() ? attachments_[a].get() : nullptr; }
  std::uint32_t attachment_count() const { return std::uint32_t(attachments_.size()); }
  // Parts not drawn: bit p hides part p (a layered character's toggles);
  // an attachment a is "part" part_count + a.
  void SetHiddenParts(std::uint64_t mask) { hidden_parts_ = mask; }
  std::uint64_t hidden_parts() const { return hidden_parts_; }
  std::uint32_t max_instances() const { return max_instances_; }
  // Inside dynamic rendering on a target of the format given to Init: the
  // camera looks at the world through the viewport of `width` x `height`
  // pixels at (x, y) of the target. A rig without parts is one instanced
  // draw for the whole crowd; a layered character is drawn one character
  // after the other (the crowd is sorted back to front), its parts in its
  // draw list's order, each sampling its own drawings; a character with
  // attachments draws them among its parts by their draw orders (ties: the
  // body's parts first, then the attachments in order).
  void Record(VkCommandBuffer cmd, std::uint32_t instance_count, const Camera& camera, std::uint32_t width,
              std::uint32_t height, bool wireframe, std::int32_t x = 0, std::int32_t y = 0,
              Blend blend = Blend::kExact) const;

 private:
  // Init's steps.
  void UploadDrawings(const Drawings& drawings, std::uint32_t pose_count);
  void CreateDescriptors(TextureFilter filter);
  bool CreatePipelines(VkFormat target_format, std::string* error);
  // Binds this renderer's pipeline, drawings and buffers and draws part p of
  // character k (the viewport is set).
  void DrawPart(VkCommandBuffer cmd, std::uint32_t k, std::uint32_t p, gpu::PushData push, Blend blend) const;
  // The wireframe of `count` characters (the lines pipeline, flat colour in push).
  void RecordLines(VkCommandBuffer cmd, std::uint32_t count, gpu::PushData push) const;
  Gpu* gpu_ = nullptr;
  std::uint32_t vertex_count_ = 0, index_count_ = 0, max_instances_ = 0, pose_count_ = 0;
  struct PartRange {
    std::uint32_t first_index = 0, index_count = 0;
  };
  std::vector<PartRange> parts_;                 // one per part (one for a rig without parts)
  std::vector<const std::uint32_t*> sequences_;  // per character: its parts back to front
  std::vector<DrawList> lists_;                  // per character: its list (the draw order's inputs)
  const Rig* rig_ = nullptr;
  std::vector<std::unique_ptr<RigRenderer>> attachments_;
  std::uint64_t hidden_parts_ = 0;
  Buffer indices_, uvs_, positions_, instances_;
  Buffer regions_;    // gpu::Region per part and pose
  Buffer opacities_;  // per character: each part's opacity (DrawList::part_opacity)
  Image drawings_;
  VkSampler sampler_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline fill_ = VK_NULL_HANDLE, lines_ = VK_NULL_HANDLE;
};

}  // namespace posemorph::viewer
