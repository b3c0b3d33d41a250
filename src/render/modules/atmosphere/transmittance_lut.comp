#version 450
// Pass 2a: the transmittance LUT (Hillaire 2020, section 4; common/atmosphere_lut_inc.glsl),
// recomputed only when the atmosphere changes.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/phase_inc.glsl"
#include "common/atmosphere_inc.glsl"
#include "common/atmosphere_lut_inc.glsl"
#include "frame_atmosphere_inc.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (texel.x >= TRANSMITTANCE_LUT_W || texel.y >= TRANSMITTANCE_LUT_H) return;
  vec2 uv = (vec2(texel) + 0.5f) / vec2(TRANSMITTANCE_LUT_W, TRANSMITTANCE_LUT_H);
  imageStore(transmittance_lut_out, texel, vec4(transmittance_lut_texel(frame_atmosphere(), uv), 1.0f));
}
