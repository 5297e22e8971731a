// SPDX-License-Identifier: MIT
// The structs the shaders read (shaders/shared_layout.h, one declaration for
// GLSL and C++), here with GLM types, and checks that C++ lays them out
// exactly as the shaders' scalar block layout does: each member at the sum
// of the sizes before it (no padding), 4-byte alignment. A member added,
// moved or retyped on one side fails to compile here instead of drawing
// garbage.
#pragma once
#include <cstddef>
#include <cstdint>

#include <glm/mat2x2.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

namespace posemorph::viewer::gpu {

using glm::ivec4;
using glm::mat2;
using glm::uvec2;
using glm::vec2;
using glm::vec4;
using uint = std::uint32_t;

#include "shared_layout.h"

// GLSL scalar layout: vec2/uvec2 8 bytes, mat2 two vec2 columns (16), ivec4/vec4 16, all 4-aligned.
static_assert(sizeof(mat2) == 16 && sizeof(vec2) == 8 && sizeof(uvec2) == 8 && sizeof(vec4) == 16 &&
                  sizeof(ivec4) == 16,
              "GLM types must be tightly packed (no GLM_FORCE_ALIGNED / GLM_FORCE_DEFAULT_ALIGNED_GENTYPES)");
static_assert(offsetof(Instance, linear) == 0, "Instance.linear");
static_assert(offsetof(Instance, translation) == 16, "Instance.translation");
static_assert(offsetof(Instance, layers) == 24, "Instance.layers");
static_assert(offsetof(Instance, weights) == 56, "Instance.weights");
static_assert(offsetof(Instance, tint) == 88, "Instance.tint");
static_assert(sizeof(Instance) == 104 && alignof(Instance) == 4, "Instance: 104 bytes, array stride 104");
static_assert(offsetof(PushData, positions) == 0, "PushData.positions");
static_assert(offsetof(PushData, uvs) == 8, "PushData.uvs");
static_assert(offsetof(PushData, instances) == 16, "PushData.instances");
static_assert(offsetof(PushData, view_scale) == 24, "PushData.view_scale");
static_assert(offsetof(PushData, view_offset) == 32, "PushData.view_offset");
static_assert(offsetof(PushData, vertex_count) == 40, "PushData.vertex_count");
static_assert(offsetof(PushData, flat_colour) == 44, "PushData.flat_colour");
static_assert(offsetof(PushData, only_slot) == 48, "PushData.only_slot");
static_assert(offsetof(PushData, pose_count) == 52, "PushData.pose_count");
static_assert(offsetof(PushData, opacities) == 56, "PushData.opacities");
static_assert(offsetof(PushData, part) == 64, "PushData.part");
static_assert(offsetof(PushData, part_count) == 68, "PushData.part_count");
static_assert(offsetof(PushData, regions) == 72, "PushData.regions");
static_assert(sizeof(PushData) == 80, "PushData: 80 bytes (push constants: at most 128)");
static_assert(offsetof(Region, page) == 16 && sizeof(Region) == 20 && alignof(Region) == 4, "Region: 20 bytes");

// A buffer device address as the shaders' uvec2 (low, high).
inline uvec2 Address(std::uint64_t a) { return uvec2(std::uint32_t(a), std::uint32_t(a >> 32)); }

}  // namespace posemorph::viewer::gpu
