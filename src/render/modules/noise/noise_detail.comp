#version 450
// Pass 1b: detail noise, 32^3 RGB (seed 000, table 2.1): Worley at low, mid and high frequency
// (fBm of 2, 4 cells per tile; a single 8-cell octave, the most 32 texels resolve). Tiles.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/noise_inc.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

void main() {
  ivec3 size = imageSize(detail_noise_out);
  ivec3 id = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(id, size))) return;
  vec3 uvw = (vec3(id) + 0.5f) / vec3(size);
  uint seed = uint(frame.size.w) * 101u + 7u;
  vec4 texel;
  texel.r = worley_fbm(uvw, 2, seed + 61u);
  texel.g = worley_fbm(uvw, 4, seed + 71u);
  texel.b = worley_tiled(uvw * 8.0f, 8, seed + 83u);
  texel.a = 1.0f;
  imageStore(detail_noise_out, id, texel);
}
