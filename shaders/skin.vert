// SPDX-License-Identifier: MIT
#version 460
// GPU skinning: the runtime's vertex positions for every character arrive in
// one buffer; this shader picks its vertex by gl_VertexIndex and its
// character by gl_InstanceIndex, so a whole crowd is one instanced draw. It
// passes on each vertex's uv in every drawing the character shows (up to 8,
// those with the largest texture weights; all of them for N <= 8).
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require

struct Instance {
  vec2 offset;    // where the character stands, rig units
  float scale;
  float _pad;
  ivec4 layers[2];   // the drawings shown
  vec4 weights[2];   // their texture weights w''
};
layout(buffer_reference, scalar) readonly buffer Vec2s { vec2 v[]; };
layout(buffer_reference, scalar) readonly buffer Instances { Instance i[]; };

layout(push_constant, scalar) uniform Push {
  Vec2s positions;     // instance-major, V per instance
  Vec2s uvs;           // pose-major, V per pose
  Instances instances;
  vec2 view_scale;     // rig units -> clip space
  vec2 view_offset;
  uint vertex_count;
  uint flat_colour;    // 1: draw the mesh in one colour (wireframe overlay)
} pc;

layout(location = 0) out vec4 uv01;
layout(location = 1) out vec4 uv23;
layout(location = 2) out vec4 uv45;
layout(location = 3) out vec4 uv67;
layout(location = 4) flat out vec4 weights0;
layout(location = 5) flat out vec4 weights1;
layout(location = 6) flat out ivec4 layers0;
layout(location = 7) flat out ivec4 layers1;

vec2 Uv(int layer, uint v) { return pc.uvs.v[uint(layer) * pc.vertex_count + v]; }

void main() {
  const uint v = uint(gl_VertexIndex);
  const Instance inst = pc.instances.i[gl_InstanceIndex];
  const vec2 p = pc.positions.v[uint(gl_InstanceIndex) * pc.vertex_count + v] * inst.scale + inst.offset;
  gl_Position = vec4(p * pc.view_scale + pc.view_offset, 0.0, 1.0);
  uv01 = vec4(Uv(inst.layers[0].x, v), Uv(inst.layers[0].y, v));
  uv23 = vec4(Uv(inst.layers[0].z, v), Uv(inst.layers[0].w, v));
  uv45 = vec4(Uv(inst.layers[1].x, v), Uv(inst.layers[1].y, v));
  uv67 = vec4(Uv(inst.layers[1].z, v), Uv(inst.layers[1].w, v));
  weights0 = inst.weights[0];
  weights1 = inst.weights[1];
  layers0 = inst.layers[0];
  layers1 = inst.layers[1];
}
