#version 450
// Impostors (seed 003, 3.3.4; render/modules/impostors/impostors.h): a far particle cloud drawn as one
// quad with its image from the atlas, where it was drawn from this eye (its right and up are
// the image's). Six vertices an impostor, from draw.info.x on.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"

layout(location = 0) out vec2 uv_out;             // [0, 1]^2 across the quad, v down
layout(location = 1) flat out int impostor_out;

layout(push_constant) uniform DrawBlock { DrawConstants draw; };

const vec2 kCorners[6] = vec2[6](vec2(-1.0f, -1.0f), vec2(1.0f, -1.0f), vec2(1.0f, 1.0f),
                                 vec2(-1.0f, -1.0f), vec2(1.0f, 1.0f), vec2(-1.0f, 1.0f));

void main() {
  int index = draw.info.x + gl_VertexIndex / 6;
  ImpostorGpu im = impostor_list[index];
  vec2 c = kCorners[gl_VertexIndex % 6];
  vec3 corner = im.center_half.xyz + c.x * im.right.xyz + c.y * im.up.xyz;
  float z = dot(corner, draw.forward.xyz);
  gl_Position = vec4(dot(corner, draw.right.xyz) / (draw.forward.w * draw.right.w),
                     -dot(corner, draw.up.xyz) / draw.forward.w, z - 1.0f, z);
  uv_out = vec2(0.5f + 0.5f * c.x, 0.5f - 0.5f * c.y);
  impostor_out = index;
}
