// SPDX-License-Identifier: MIT
#include "rig_renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "blend.frag.h"
#include "skin.vert.h"

namespace posemorph::viewer {

Instance ToInstance(const DrawList& list) {
  Instance inst{};
  const Transform2D& t = list.transform;
  inst.linear = gpu::mat2(t.a, t.b, t.c, t.d);  // column-major: (a, b), (c, d)
  inst.translation = gpu::vec2(t.tx, t.ty);
  for (std::uint32_t k = 0; k < kDrawingsPerCharacter; ++k) {
    const bool used = k < list.drawing_count;
    const std::int32_t layer = std::int32_t(list.drawings[used ? k : 0].pose);
    inst.layers[k / 4][int(k % 4)] = layer;
    inst.weights[k / 4][int(k % 4)] = used ? list.drawings[k].weight : 0.0f;
  }
  const Colour c = list.colour;  // premultiplied: the sample times (r, g, b, 1) x a
  inst.tint = gpu::vec4(c.r * c.a, c.g * c.a, c.b * c.a, c.a);
  return inst;
}

namespace {

using Push = gpu::PushData;

VkShaderModule Module(VkDevice device, const std::uint32_t* code, std::size_t bytes) {
  VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  ci.codeSize = bytes;
  ci.pCode = code;
  VkShaderModule m = VK_NULL_HANDLE;
  VkCheck(vkCreateShaderModule(device, &ci, nullptr, &m), "vkCreateShaderModule");
  return m;
}

}  // namespace

bool RigRenderer::Init(Gpu& gpu, const Rig& rig, const Drawings& drawings, VkFormat target_format,
                       std::uint32_t max_instances, TextureFilter filter, std::string* error) {
  gpu_ = &gpu;
  const std::uint32_t V = rig.vertex_count(), N = rig.pose_count();
  vertex_count_ = V;
  index_count_ = 3 * rig.triangle_count();
  max_instances_ = max_instances;
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;

  indices_ = gpu.CreateBuffer(4ull * index_count_, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
  std::memcpy(indices_.mapped, rig.triangles().data, 4ull * index_count_);
  uvs_ = gpu.CreateBuffer(8ull * V * N, storage);
  for (std::uint32_t i = 0; i < N; ++i)
    std::memcpy(static_cast<char*>(uvs_.mapped) + 8ull * V * i, rig.uvs(i).data, 8ull * V);
  pose_count_ = N;
  // Each part's drawing in each pose: its page and where on it (Rig::part_region).
  const std::uint32_t M = rig.part_count();
  regions_ = gpu.CreateBuffer(sizeof(gpu::Region) * M * N, storage);
  for (std::uint32_t p = 0; p < M; ++p)
    for (std::uint32_t i = 0; i < N; ++i) {
      const TextureRegion r = rig.part_region(p, i);
      static_cast<gpu::Region*>(regions_.mapped)[std::size_t(p) * N + i] =
          gpu::Region{gpu::vec4(r.scale_u, r.offset_u, r.scale_v, r.offset_v), std::int32_t(r.page)};
    }
  parts_.clear();
  for (std::uint32_t p = 0; p < rig.part_count(); ++p)
    parts_.push_back({3 * rig.part(p).first_triangle, 3 * rig.part(p).triangle_count});
  sequences_.assign(max_instances, rig.draw_sequence().data);
  lists_.assign(max_instances, DrawList{});
  rig_ = &rig;
  positions_ = gpu.CreateBuffer(8ull * V * max_instances, storage);
  instances_ = gpu.CreateBuffer(sizeof(Instance) * max_instances, storage);
  opacities_ = gpu.CreateBuffer(4ull * parts_.size() * max_instances, storage);
  std::fill_n(static_cast<float*>(opacities_.mapped), parts_.size() * max_instances, 1.0f);
  UploadDrawings(drawings, N);
  CreateDescriptors(filter);
  if (!CreatePipelines(target_format, error)) return false;
  attachments_.clear();
  for (std::uint32_t a = 0; a < rig.attachment_count(); ++a) {
    if (a >= drawings.attachments.size()) {
      *error = "no drawings for attachment " + std::to_string(a);
      return false;
    }
    attachments_.push_back(std::make_unique<RigRenderer>());
    if (!attachments_.back()->Init(gpu, *rig.attachment(a).rig, drawings.attachments[a], target_format, max_instances,
                                   filter, error))
      return false;
  }
  return true;
}

// The pages as one texture array (an atlas's pages, or every part's drawing in every pose).
void RigRenderer::UploadDrawings(const Drawings& drawings, std::uint32_t) {
  const std::uint32_t N = std::uint32_t(drawings.rgba.size());
  Gpu& gpu = *gpu_;
  const std::size_t layer_bytes = std::size_t(drawings.width) * drawings.height * 4;
  Buffer staging = gpu.CreateBuffer(layer_bytes * N, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  for (std::uint32_t i = 0; i < N; ++i)
    std::memcpy(static_cast<char*>(staging.mapped) + layer_bytes * i, drawings.rgba[i].data(), layer_bytes);
  drawings_ = gpu.CreateImage(VK_FORMAT_R8G8B8A8_UNORM, drawings.width, drawings.height, N,
                              VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
  gpu.RunOnce([&](VkCommandBuffer cmd) {
    Transition(cmd, drawings_.image, N, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, N};
    copy.imageExtent = {drawings.width, drawings.height, 1};
    vkCmdCopyBufferToImage(cmd, staging.buffer, drawings_.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
    Transition(cmd, drawings_.image, N, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  });
  gpu.Destroy(staging);
}

// The sampler (linear, or nearest for pixel art) and the drawings' descriptor set.
void RigRenderer::CreateDescriptors(TextureFilter filter) {
  VkDevice dev = gpu_->device();
  VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  sci.magFilter = sci.minFilter = filter == TextureFilter::kNearest ? VK_FILTER_NEAREST : VK_FILTER_LINEAR;
  sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
  sci.borderColor = VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;  // outside the drawing: nothing
  VkCheck(vkCreateSampler(dev, &sci, nullptr, &sampler_), "vkCreateSampler");

  VkDescriptorSetLayoutBinding binding{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT,
                                       nullptr};
  VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  lci.bindingCount = 1;
  lci.pBindings = &binding;
  VkCheck(vkCreateDescriptorSetLayout(dev, &lci, nullptr, &set_layout_), "vkCreateDescriptorSetLayout");
  VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1};
  VkDescriptorPoolCreateInfo dpi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  dpi.maxSets = 1;
  dpi.poolSizeCount = 1;
  dpi.pPoolSizes = &size;
  VkCheck(vkCreateDescriptorPool(dev, &dpi, nullptr, &pool_), "vkCreateDescriptorPool");
  VkDescriptorSetAllocateInfo dai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  dai.descriptorPool = pool_;
  dai.descriptorSetCount = 1;
  dai.pSetLayouts = &set_layout_;
  VkCheck(vkAllocateDescriptorSets(dev, &dai, &set_), "vkAllocateDescriptorSets");
  VkDescriptorImageInfo dii{sampler_, drawings_.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  write.dstSet = set_;
  write.descriptorCount = 1;
  write.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  write.pImageInfo = &dii;
  vkUpdateDescriptorSets(dev, 1, &write, 0, nullptr);
}

// The pipeline layout and the two pipelines: filled, and lines (wireframe)
// where the device can.
bool RigRenderer::CreatePipelines(VkFormat target_format, std::string* error) {
  VkDevice dev = gpu_->device();
  VkPushConstantRange range{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(Push)};
  VkPipelineLayoutCreateInfo pli{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pli.setLayoutCount = 1;
  pli.pSetLayouts = &set_layout_;
  pli.pushConstantRangeCount = 1;
  pli.pPushConstantRanges = &range;
  VkCheck(vkCreatePipelineLayout(dev, &pli, nullptr, &layout_), "vkCreatePipelineLayout");

  VkShaderModule vs = Module(dev, kSkinVert, sizeof kSkinVert), fs = Module(dev, kBlendFrag, sizeof kBlendFrag);
  VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                               {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vs;
  stages[0].pName = "main";
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = fs;
  stages[1].pName = "main";
  VkPipelineVertexInputStateCreateInfo vin{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  vp.viewportCount = vp.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  rs.polygonMode = VK_POLYGON_MODE_FILL;
  rs.cullMode = VK_CULL_MODE_NONE;
  rs.lineWidth = 1;
  VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  ms.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineColorBlendAttachmentState blend{};
  blend.blendEnable = VK_TRUE;  // premultiplied "over"
  blend.srcColorBlendFactor = blend.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
  blend.dstColorBlendFactor = blend.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
  blend.colorBlendOp = blend.alphaBlendOp = VK_BLEND_OP_ADD;
  blend.colorWriteMask = 0xF;
  VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  cb.attachmentCount = 1;
  cb.pAttachments = &blend;
  const VkDynamicState dyn[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  ds.dynamicStateCount = 2;
  ds.pDynamicStates = dyn;
  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = 1;
  rendering.pColorAttachmentFormats = &target_format;
  VkGraphicsPipelineCreateInfo gpi{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  gpi.pNext = &rendering;
  gpi.stageCount = 2;
  gpi.pStages = stages;
  gpi.pVertexInputState = &vin;
  gpi.pInputAssemblyState = &ia;
  gpi.pViewportState = &vp;
  gpi.pRasterizationState = &rs;
  gpi.pMultisampleState = &ms;
  gpi.pColorBlendState = &cb;
  gpi.pDynamicState = &ds;
  gpi.layout = layout_;
  const VkResult fill = vkCreateGraphicsPipelines(dev, VK_NULL_HANDLE, 1, &gpi, nullptr, &fill_);
  VkPhysicalDeviceFeatures features;
  vkGetPhysicalDeviceFeatures(gpu_->physical(), &features);
  if (features.fillModeNonSolid) {
    rs.polygonMode = VK_POLYGON_MODE_LINE;
    VkCheck(vkCreateGraphicsPipelines(dev, VK_NULL_HANDLE, 1, &gpi, nullptr, &lines_), "vkCreateGraphicsPipelines");
  }
  vkDestroyShaderModule(dev, vs, nullptr);
  vkDestroyShaderModule(dev, fs, nullptr);
  if (fill != VK_SUCCESS) {
    *error = "cannot create the drawing pipeline";
    return false;
  }
  return true;
}

RigRenderer::~RigRenderer() {
  if (!gpu_) return;
  VkDevice dev = gpu_->device();
  vkDeviceWaitIdle(dev);  // in a destructor: nothing to report to
  if (fill_) vkDestroyPipeline(dev, fill_, nullptr);
  if (lines_) vkDestroyPipeline(dev, lines_, nullptr);
  if (layout_) vkDestroyPipelineLayout(dev, layout_, nullptr);
  if (pool_) vkDestroyDescriptorPool(dev, pool_, nullptr);
  if (set_layout_) vkDestroyDescriptorSetLayout(dev, set_layout_, nullptr);
  if (sampler_) vkDestroySampler(dev, sampler_, nullptr);
  gpu_->Destroy(drawings_);
  for (Buffer* b : {&indices_, &uvs_, &positions_, &instances_, &opacities_, &regions_}) gpu_->Destroy(*b);
}

void RigRenderer::SetCharacter(std::uint32_t k, const DrawList& list) {
  instances()[k] = ToInstance(list);
  float* opacity = static_cast<float*>(opacities_.mapped) + std::size_t(k) * parts_.size();
  for (std::size_t p = 0; p < parts_.size(); ++p) opacity[p] = p < format::kMaxParts ? list.part_opacity[p] : 1.0f;
  if (k < sequences_.size() && list.parts.size == parts_.size()) sequences_[k] = list.parts.data;
  if (k < lists_.size()) lists_[k] = list;
}

void RigRenderer::DrawPart(VkCommandBuffer cmd, std::uint32_t k, std::uint32_t p, gpu::PushData push,
                           Blend blend) const {
  push.positions = gpu::Address(positions_.address);
  push.uvs = gpu::Address(uvs_.address);
  push.instances = gpu::Address(instances_.address);
  push.vertex_count = vertex_count_;
  push.pose_count = pose_count_;
  push.regions = gpu::Address(regions_.address);
  push.opacities = gpu::Address(opacities_.address);
  push.part = p;
  push.part_count = std::uint32_t(parts_.size());
  const VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &set_, 0, nullptr);
  vkCmdBindIndexBuffer(cmd, indices_.buffer, 0, VK_INDEX_TYPE_UINT32);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, fill_);
  for (std::int32_t slot = blend == Blend::kExact ? -1 : 0;
       slot < (blend == Blend::kExact ? 0 : std::int32_t(kDrawingsPerCharacter)); ++slot) {
    push.only_slot = slot;
    vkCmdPushConstants(cmd, layout_, stages, 0, sizeof push, &push);
    vkCmdDrawIndexed(cmd, parts_[p].index_count, 1, parts_[p].first_index, 0, k);
  }
}

void RigRenderer::Record(VkCommandBuffer cmd, std::uint32_t count, const Camera& camera, std::uint32_t width,
                         std::uint32_t height, bool wireframe, std::int32_t x, std::int32_t y, Blend blend) const {
  VkViewport viewport{float(x), float(y), float(width), float(height), 0, 1};
  VkRect2D scissor{{x, y}, {width, height}};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
  Push push{};
  push.positions = gpu::Address(positions_.address);
  push.uvs = gpu::Address(uvs_.address);
  push.instances = gpu::Address(instances_.address);
  ClipTransform(camera, width, height, &push.view_scale, &push.view_offset);
  push.vertex_count = vertex_count_;
  push.pose_count = pose_count_;
  push.regions = gpu::Address(regions_.address);
  push.only_slot = -1;
  push.opacities = gpu::Address(opacities_.address);
  push.part_count = std::uint32_t(parts_.size());
  const VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &set_, 0, nullptr);
  vkCmdBindIndexBuffer(cmd, indices_.buffer, 0, VK_INDEX_TYPE_UINT32);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, fill_);
  // One range of triangles for `instances` characters from `first`: one
  // draw, or one per drawing slot for the sequential blend.
  const auto draw = [&](std::uint32_t first_index, std::uint32_t indices, std::uint32_t first,
                        std::uint32_t instances) {
    if (blend == Blend::kExact) {
      push.only_slot = -1;
      vkCmdPushConstants(cmd, layout_, stages, 0, sizeof push, &push);
      vkCmdDrawIndexed(cmd, indices, instances, first_index, 0, first);
      return;
    }
    for (std::int32_t slot = 0; slot < std::int32_t(kDrawingsPerCharacter); ++slot) {
      push.only_slot = slot;
      vkCmdPushConstants(cmd, layout_, stages, 0, sizeof push, &push);
      vkCmdDrawIndexed(cmd, indices, instances, first_index, 0, first);
    }
  };
  if (!attachments_.empty()) {
    // Character by character, back to front: the body's parts and the
    // attachments' in the order the runtime gives (CharacterDrawSteps).
    std::vector<DrawList> attached(attachments_.size());
    std::vector<DrawStep> steps;
    const std::size_t P = parts_.size();
    for (std::uint32_t k = 0; k < count && k < lists_.size(); ++k) {
      for (std::size_t a = 0; a < attachments_.size(); ++a) attached[a] = attachments_[a]->lists_[k];
      steps.resize(CharacterDrawSteps(*rig_, lists_[k], attached.data(), {}));
      CharacterDrawSteps(*rig_, lists_[k], attached.data(), {steps.data(), steps.size()});
      for (const DrawStep& step : steps) {
        const std::size_t bit = step.list == 0 ? step.part : P + step.list - 1;
        if (bit < 64 && (hidden_parts_ >> bit) & 1) continue;
        if (step.list == 0)
          DrawPart(cmd, k, step.part, push, blend);
        else
          attachments_[step.list - 1]->DrawPart(cmd, k, step.part, push, blend);
      }
    }
  } else if (parts_.size() <= 1) {
    if (!(hidden_parts_ & 1)) draw(0, index_count_, 0, count);
  } else {
    // Character by character, back to front, each one's parts in its order.
    for (std::uint32_t k = 0; k < count && k < sequences_.size(); ++k)
      for (std::size_t s = 0; s < parts_.size(); ++s) {
        const std::uint32_t p = sequences_[k][s];
        if (p >= parts_.size() || (p < 64 && (hidden_parts_ >> p) & 1)) continue;
        push.part = p;
        draw(parts_[p].first_index, parts_[p].index_count, k, 1);
      }
    push.part = 0;
  }
  push.only_slot = -1;
  if (wireframe && lines_) {
    push.flat_colour = 1;
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &set_, 0, nullptr);
    vkCmdBindIndexBuffer(cmd, indices_.buffer, 0, VK_INDEX_TYPE_UINT32);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, lines_);
    vkCmdPushConstants(cmd, layout_, stages, 0, sizeof push, &push);
    vkCmdDrawIndexed(cmd, index_count_, count, 0, 0, 0);
    for (const auto& a : attachments_) a->RecordLines(cmd, count, push);
  }
}

void RigRenderer::RecordLines(VkCommandBuffer cmd, std::uint32_t count, gpu::PushData push) const {
  if (!lines_) return;
  push.positions = gpu::Address(positions_.address);
  push.uvs = gpu::Address(uvs_.address);
  push.instances = gpu::Address(instances_.address);
  push.vertex_count = vertex_count_;
  push.pose_count = pose_count_;
  push.regions = gpu::Address(regions_.address);
  push.opacities = gpu::Address(opacities_.address);
  push.part = 0;
  push.part_count = std::uint32_t(parts_.size());
  const VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &set_, 0, nullptr);
  vkCmdBindIndexBuffer(cmd, indices_.buffer, 0, VK_INDEX_TYPE_UINT32);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, lines_);
  vkCmdPushConstants(cmd, layout_, stages, 0, sizeof push, &push);
  vkCmdDrawIndexed(cmd, index_count_, count, 0, 0, 0);
}

}  // namespace posemorph::viewer
