// The sky's light in a direction, from the frame's sky-view table. GLSL only; the includer
// includes bindings_inc.glsl.
#ifndef NEPHELE_SKY_LIGHT_INC
#define NEPHELE_SKY_LIGHT_INC

#extension GL_GOOGLE_include_directive : require
#include "common/sky_view_inc.glsl"

// The radiance that reaches the camera's place from direction d (per unit key-light
// illuminance), from the sky-view table: its sky rows, and below the horizon its ground rows too
// (the ground lit by the sun). The sun's and the moon's discs are not in it.
vec3 sky_radiance(SkyViewFrame f, vec3 d) {
  vec2 uv = sky_view_uv(f, d);
  float rows = float(textureSize(sky_view_lut, 0).y / 2);
  vec3 sky = textureLod(sky_view_lut, sky_view_texcoord(uv, rows, 0.0f), 0.0f).rgb;
  vec3 ground = uv.y < 0.5f ? textureLod(sky_view_lut, sky_view_texcoord(uv, rows, 1.0f), 0.0f).rgb : vec3(0.0f);
  return sky + ground;
}

#endif
