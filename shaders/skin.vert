// SPDX-License-Identifier: MIT
#version 460
// GPU skinning: the runtime's vertex positions for every character arrive in
// one buffer; this shader picks its vertex by gl_VertexIndex and its
// character by gl_InstanceIndex, so a whole crowd is one instanced draw,
// placed by each character's transform (a mirrored one turns the triangles
// clockwise: the pipeline does not cull). It passes on each vertex's uv in
// every drawing the character shows (up to 8, those with the largest
// texture weights; all of them for N <= 8), mapped onto the drawing's page
// (Rig::part_region: the atlas, or the drawing itself), and the colour the part draws
// with: the character's premultiplied tint times the part's opacity.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#extension GL_EXT_scalar_block_layout : require
#extension GL_GOOGLE_include_directive : require
#include "shared_layout.h"

layout(buffer_reference, scalar) readonly buffer Vec2s { vec2 v[]; };
layout(buffer_reference, scalar) readonly buffer Instances { Instance i[]; };
layout(buffer_reference, scalar) readonly buffer Floats { float f[]; };
layout(buffer_reference, scalar) readonly buffer Regions { Region r[]; };
layout(push_constant, scalar) uniform Push { PushData pc; };

layout(location = 0) out vec4 uv01;
layout(location = 1) out vec4 uv23;
layout(location = 2) out vec4 uv45;
layout(location = 3) out vec4 uv67;
layout(location = 4) flat out vec4 weights0;
layout(location = 5) flat out vec4 weights1;
layout(location = 6) flat out ivec4 layers0;
layout(location = 7) flat out ivec4 layers1;
layout(location = 8) flat out vec4 tint;

// The drawn part's drawing in `pose`: where it lies on its page (an atlas
// page, or the drawing itself with an identity map).
Region RegionOf(int pose) { return Regions(pc.regions).r[pc.part * pc.pose_count + uint(pose)]; }
vec2 Uv(int pose, uint v) {
  const Region r = RegionOf(pose);
  return Vec2s(pc.uvs).v[uint(pose) * pc.vertex_count + v] * r.map.xz + r.map.yw;
}
ivec4 Pages(ivec4 poses) {
  return ivec4(RegionOf(poses.x).page, RegionOf(poses.y).page, RegionOf(poses.z).page, RegionOf(poses.w).page);
}

void main() {
  const uint v = uint(gl_VertexIndex);
  const Instance inst = Instances(pc.instances).i[gl_InstanceIndex];
  const vec2 p = inst.linear * Vec2s(pc.positions).v[uint(gl_InstanceIndex) * pc.vertex_count + v] + inst.translation;
  gl_Position = vec4(p * pc.view_scale + pc.view_offset, 0.0, 1.0);
  uv01 = vec4(Uv(inst.layers[0].x, v), Uv(inst.layers[0].y, v));
  uv23 = vec4(Uv(inst.layers[0].z, v), Uv(inst.layers[0].w, v));
  uv45 = vec4(Uv(inst.layers[1].x, v), Uv(inst.layers[1].y, v));
  uv67 = vec4(Uv(inst.layers[1].z, v), Uv(inst.layers[1].w, v));
  weights0 = inst.weights[0];
  weights1 = inst.weights[1];
  layers0 = Pages(inst.layers[0]);
  layers1 = Pages(inst.layers[1]);
  const float part_opacity = Floats(pc.opacities).f[uint(gl_InstanceIndex) * pc.part_count + pc.part];
  tint = inst.tint * part_opacity;
}
