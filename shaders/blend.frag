#version 460
// Cross-fades a character's drawings: each pose's own drawing sampled through
// that pose's uvs, weighted by the texture weights w'' (premultiplied alpha,
// so the sum is a premultiplied colour too).
#extension GL_EXT_scalar_block_layout : require

layout(set = 0, binding = 0) uniform sampler2DArray drawings;

layout(push_constant, scalar) uniform Push {
  uvec2 positions, uvs, instances;  // addresses, used by the vertex stage
  vec2 view_scale;
  vec2 view_offset;
  uint vertex_count;
  uint flat_colour;
} pc;

layout(location = 0) in vec2 uv0;
layout(location = 1) in vec2 uv1;
layout(location = 2) in vec2 uv2;
layout(location = 3) in vec2 uv3;
layout(location = 4) flat in vec4 weights;
layout(location = 5) flat in ivec4 layers;
layout(location = 0) out vec4 colour;

void main() {
  if (pc.flat_colour != 0u) {
    colour = vec4(0.1, 0.1, 0.1, 1.0) * 0.6;
    return;
  }
  vec4 c = weights.x * texture(drawings, vec3(uv0, float(layers.x)));
  c += weights.y * texture(drawings, vec3(uv1, float(layers.y)));
  c += weights.z * texture(drawings, vec3(uv2, float(layers.z)));
  c += weights.w * texture(drawings, vec3(uv3, float(layers.w)));
  colour = c;
}
