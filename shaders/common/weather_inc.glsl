// The procedural weather map's state at one point (weather.comp): pure, also compiled as C++
// (src/render/glsl.h), so the CPU can compute the map a device should produce.
#ifndef NEPHELE_WEATHER_INC
#define NEPHELE_WEATHER_INC

// The weather at `uv` (xy the map in tiles [0, 1), z its time in units of 6 x the weather's
// time scale) for the scene's noise seed: R coverage, G storm cells, B cloud type around the
// layer's, A density (channels as in seed 002 and Schneider 2015).
vec4 weather_state(vec3 uv, uint noise_seed) {
  uint seed = noise_seed * 101u + 13u;
  // Clusters of cumulus cells: Perlin fBm modulated by Worley cells, contrast-stretched.
  float cells = worley_fbm(uv, 12, seed + 1u);
  float field = perlin_fbm01(uv, 6, 4, seed + 2u);
  float low = saturate(remap(field * 0.55f + cells * 0.65f, 0.45f, 1.0f, 0.0f, 1.0f));
  // A few storm cells, each some 10 km across (three lattice cells a tile: 13 km at the
  // default 40 km), where precipitation grows cumulonimbus; the type varies by +-0.1 around
  // the layer's.
  float storms = smoothstep(0.52f, 0.72f, perlin_fbm01(uv, 3, 2, seed + 3u));
  float type = mix(0.4f, 0.6f, perlin_fbm01(uv, 8, 2, seed + 4u));
  float density = mix(0.6f, 1.0f, perlin_fbm01(uv, 5, 2, seed + 5u));
  return vec4(low, storms, type, density);
}

#endif
