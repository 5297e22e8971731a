// SPDX-License-Identifier: MIT
#version 460
// Cross-fades a character's drawings (of the part drawn): each pose's own
// drawing sampled through that pose's uvs on its page (array layer: an
// atlas page, or the drawing itself; skin.vert maps the uvs and the layers), weighted by the texture weights w''
// (premultiplied alpha, so the sum is a premultiplied colour too). With
// only_slot = s >= 0 it draws one drawing instead, at opacity
// w_s / (w_0 + ... + w_s): drawn for s = 0, 1, ... each "over" the last,
// this is the sequential approximation a renderer that samples one texture
// per draw would use (exact where every drawing is opaque). Every sample is
// multiplied by the tint: the character's colour (r a, g a, b a, a) times
// its part's opacity (docs/runtime.md "Drawing a character", step 4).
#extension GL_EXT_scalar_block_layout : require
#extension GL_GOOGLE_include_directive : require
#include "shared_layout.h"

layout(set = 0, binding = 0) uniform sampler2DArray drawings;
layout(push_constant, scalar) uniform Push { PushData pc; };

layout(location = 0) in vec4 uv01;
layout(location = 1) in vec4 uv23;
layout(location = 2) in vec4 uv45;
layout(location = 3) in vec4 uv67;
layout(location = 4) flat in vec4 weights0;
layout(location = 5) flat in vec4 weights1;
layout(location = 6) flat in ivec4 layers0;
layout(location = 7) flat in ivec4 layers1;
layout(location = 8) flat in vec4 tint;
layout(location = 0) out vec4 colour;

vec4 Drawing(float w, vec2 uv, int layer) {
  return w == 0.0 ? vec4(0.0) : w * tint * texture(drawings, vec3(uv, float(layer)));
}

void main() {
  if (pc.flat_colour != 0u) {
    colour = vec4(0.06, 0.06, 0.06, 0.6);
    return;
  }
  if (pc.only_slot >= 0) {
    const int s = pc.only_slot;
    const vec2 uv = s == 0 ? uv01.xy : s == 1 ? uv01.zw : s == 2 ? uv23.xy : s == 3 ? uv23.zw :
                    s == 4 ? uv45.xy : s == 5 ? uv45.zw : s == 6 ? uv67.xy : uv67.zw;
    const int layer = s < 4 ? layers0[s] : layers1[s - 4];
    const float w[8] = float[8](weights0.x, weights0.y, weights0.z, weights0.w, weights1.x, weights1.y, weights1.z,
                                weights1.w);
    float sum = 0.0;
    for (int k = 0; k <= s; ++k) sum += w[k];
    colour = sum > 0.0 ? Drawing(w[s] / sum, uv, layer) : vec4(0.0);
    return;
  }
  colour = Drawing(weights0.x, uv01.xy, layers0.x) + Drawing(weights0.y, uv01.zw, layers0.y) +
           Drawing(weights0.z, uv23.xy, layers0.z) + Drawing(weights0.w, uv23.zw, layers0.w) +
           Drawing(weights1.x, uv45.xy, layers1.x) + Drawing(weights1.y, uv45.zw, layers1.y) +
           Drawing(weights1.z, uv67.xy, layers1.z) + Drawing(weights1.w, uv67.zw, layers1.w);
}
