#version 450
// Pass 1a: base shape noise, 128^3 RGBA (seed 000, table 2.1): R low-frequency Perlin-Worley,
// G, B, A Worley fBm at low, mid and high frequency. Every channel tiles.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/noise_inc.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

void main() {
  ivec3 size = imageSize(base_noise_out);
  ivec3 id = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(id, size))) return;
  vec3 uvw = (vec3(id) + 0.5f) / vec3(size);
  uint seed = uint(frame.size.w) * 101u;
  vec4 texel;
  texel.r = perlin_worley(uvw, 4, seed);
  texel.g = worley_fbm(uvw, 4, seed + 31u);
  texel.b = worley_fbm(uvw, 8, seed + 41u);
  texel.a = worley_fbm(uvw, 16, seed + 53u);
  imageStore(base_noise_out, id, texel);
}
