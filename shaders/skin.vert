#version 460
// GPU skinning: the runtime's vertex positions for every character arrive in
// one buffer; this shader picks its vertex by gl_VertexIndex and its
// character by gl_InstanceIndex, so a whole crowd is one instanced draw.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_scalar_block_layout : require

struct Instance {
  vec2 offset;    // where the character stands, rig units after scaling
  float scale;
  float _pad;
  ivec4 layers;   // the four drawings with the largest texture weights
  vec4 weights;   // their weights w'', summing to 1
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

layout(location = 0) out vec2 uv0;
layout(location = 1) out vec2 uv1;
layout(location = 2) out vec2 uv2;
layout(location = 3) out vec2 uv3;
layout(location = 4) flat out vec4 weights;
layout(location = 5) flat out ivec4 layers;

void main() {
  const uint v = uint(gl_VertexIndex);
  const Instance inst = pc.instances.i[gl_InstanceIndex];
  const vec2 p = pc.positions.v[uint(gl_InstanceIndex) * pc.vertex_count + v] * inst.scale + inst.offset;
  gl_Position = vec4(p * pc.view_scale + pc.view_offset, 0.0, 1.0);
  uv0 = pc.uvs.v[uint(inst.layers.x) * pc.vertex_count + v];
  uv1 = pc.uvs.v[uint(inst.layers.y) * pc.vertex_count + v];
  uv2 = pc.uvs.v[uint(inst.layers.z) * pc.vertex_count + v];
  uv3 = pc.uvs.v[uint(inst.layers.w) * pc.vertex_count + v];
  weights = inst.weights;
  layers = inst.layers;
}
