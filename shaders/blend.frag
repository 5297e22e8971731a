// SPDX-License-Identifier: MIT
#version 460
// Cross-fades a character's drawings: each pose's own drawing sampled
// through that pose's uvs, weighted by the texture weights w''
// (premultiplied alpha, so the sum is a premultiplied colour too).
#extension GL_EXT_scalar_block_layout : require

layout(set = 0, binding = 0) uniform sampler2DArray drawings;

layout(push_constant, scalar) uniform Push {
  uvec2 positions, uvs, instances;  // addresses, used by the vertex stage
  vec2 view_scale;
  vec2 view_offset;
  uint vertex_count;
  uint flat_colour;
} pc;

layout(location = 0) in vec4 uv01;
layout(location = 1) in vec4 uv23;
layout(location = 2) in vec4 uv45;
layout(location = 3) in vec4 uv67;
layout(location = 4) flat in vec4 weights0;
layout(location = 5) flat in vec4 weights1;
layout(location = 6) flat in ivec4 layers0;
layout(location = 7) flat in ivec4 layers1;
layout(location = 0) out vec4 colour;

vec4 Drawing(float w, vec2 uv, int layer) {
  return w == 0.0 ? vec4(0.0) : w * texture(drawings, vec3(uv, float(layer)));
}

void main() {
  if (pc.flat_colour != 0u) {
    colour = vec4(0.06, 0.06, 0.06, 0.6);
    return;
  }
  colour = Drawing(weights0.x, uv01.xy, layers0.x) + Drawing(weights0.y, uv01.zw, layers0.y) +
           Drawing(weights0.z, uv23.xy, layers0.z) + Drawing(weights0.w, uv23.zw, layers0.w) +
           Drawing(weights1.x, uv45.xy, layers1.x) + Drawing(weights1.y, uv45.zw, layers1.y) +
           Drawing(weights1.z, uv67.xy, layers1.z) + Drawing(weights1.w, uv67.zw, layers1.w);
}
