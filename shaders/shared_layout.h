// SPDX-License-Identifier: MIT
// The data the viewer's shaders read, declared once for GLSL (included by
// skin.vert and blend.frag) and C++ (with GLM types, viewer/src/gpu_layout.h,
// which checks every size and offset against the scalar layout the shaders
// declare). Written in the subset both languages parse: no initialisers, no
// qualifiers.
#ifdef __cplusplus
#pragma once
#endif

// One character of an instanced draw.
struct Instance {
  mat2 linear;       // rig units -> world: columns (a, b) and (c, d) of posemorph::Transform2D
  vec2 translation;  // (tx, ty)
  ivec4 layers[2];   // the drawings shown: their poses (the vertex shader finds each one's page and region)
  vec4 weights[2];   // their texture weights, renormalised; 0 for unused slots
  vec4 tint;         // DrawList::colour premultiplied: (r a, g a, b a, a); each sample is multiplied by it
};

// Push constants of both stages.
struct PushData {
  uvec2 positions;  // buffer address: instance-major vec2 x V per instance, rig units
  uvec2 uvs;        // buffer address: pose-major vec2 x V per pose
  uvec2 instances;  // buffer address: Instance per character
  vec2 view_scale;  // world -> clip: the camera
  vec2 view_offset;
  uint vertex_count;
  uint flat_colour;  // 1: one flat colour (the wireframe overlay)
  int only_slot;     // >= 0: only this drawing slot, at weight / (sum of the weights up to it):
                     // one pass of the sequential "over" approximation (blend.frag)
  uint pose_count;   // N: the regions are part-major, part * N + pose
  uvec2 opacities;   // buffer address: float x part_count per instance, DrawList::part_opacity
  uint part;         // the part drawn (its opacity: opacities[instance * part_count + part])
  uint part_count;
  uvec2 regions;  // buffer address: Region x part_count x N (Rig::part_region)
};

// Where a part's drawing in a pose lies: array layer `page`, sampled at uv * map.xz + map.yw.
struct Region {
  vec4 map;  // scale_u, offset_u, scale_v, offset_v
  int page;
};
