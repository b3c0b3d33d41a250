#version 450
// Pass 2b': one iteration of the multiple-scattering light field (common/atmosphere_lut_inc.glsl,
// ms_field_texel) from the transmittance and Psi_ms tables and the iteration before: the sky
// seen at each altitude and sun zenith angle as spherical harmonics of degree <= 2, which view
// rays scatter through the true phase functions. Dispatched MS_FIELD_ITERATIONS times (the
// specialization constant ITERATION) with the other atmosphere tables.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/phase_inc.glsl"
#include "common/atmosphere_inc.glsl"
#include "common/atmosphere_lut_inc.glsl"
#include "frame_atmosphere_inc.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const int ITERATION = 0;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (texel.x >= MS_FIELD_W || texel.y >= MS_FIELD_H) return;
  vec2 uv = (vec2(texel) + 0.5f) / vec2(MS_FIELD_W, MS_FIELD_H);
  MsFieldCoefficients t = ms_field_texel(frame_atmosphere(), transmittance_lut, ms_lut, ms_field,
                                         ITERATION, uv, frame.sky_model.y);
  int row = (ITERATION % 2) * MS_FIELD_H + texel.y;
  for (int k = 0; k < MS_FIELD_COEFFS; ++k)
    imageStore(ms_field_out, ivec2(k * MS_FIELD_W + texel.x, row), vec4(t.c[k], 1.0f));
}
