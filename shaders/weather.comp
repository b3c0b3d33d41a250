#version 450
// Pass 1c: procedural weather map (seed 000, 2.2.2), 2D RGBA, tiles: R low-altitude coverage,
// G high-altitude coverage, B maximum cloud height (fraction of the layer), A density.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/noise_inc.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  ivec2 size = imageSize(weather_out);
  ivec2 id = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(id, size))) return;
  vec3 uv = vec3((vec2(id) + 0.5f) / vec2(size), 0.0f);
  uint seed = uint(frame.size.w) * 101u + 13u;
  // Clusters of cumulus cells: Perlin fBm modulated by Worley cells, contrast-stretched.
  float cells = worley_fbm(uv, 12, seed + 1u);
  float field = perlin_fbm01(uv, 6, 4, seed + 2u);
  float low = saturate(remap(field * 0.55f + cells * 0.65f, 0.45f, 1.0f, 0.0f, 1.0f));
  float high = saturate(remap(perlin_fbm01(uv, 4, 3, seed + 3u), 0.35f, 0.75f, 0.0f, 1.0f));
  float height = mix(0.55f, 1.0f, perlin_fbm01(uv, 8, 2, seed + 4u));
  float density = mix(0.6f, 1.0f, perlin_fbm01(uv, 5, 2, seed + 5u));
  imageStore(weather_out, id, vec4(low, high, height, density));
}
