#version 450
// Pass 2b: the multiple-scattering LUT Psi_ms (Hillaire 2020, section 5.5.2;
// common/atmosphere_lut_inc.glsl), from the transmittance LUT; recomputed only when the
// atmosphere or the ground albedo change.
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
  if (texel.x >= MS_LUT_W || texel.y >= MS_LUT_H) return;
  vec2 uv = (vec2(texel) + 0.5f) / vec2(MS_LUT_W, MS_LUT_H);
  vec3 psi = ms_lut_texel(frame_atmosphere(), transmittance_lut, uv, frame.sky_model.y);
  imageStore(ms_lut_out, texel, vec4(psi, 1.0f));
}
