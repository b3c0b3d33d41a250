// Tileable noise (seed 000, section 1.2.3 and table 2.1): Perlin gradient noise and Worley
// cellular noise whose lattices wrap with an integer period, so textures built from them tile
// seamlessly. Pure functions, also compiled as C++ for tests (see math_inc.glsl).
#ifndef NEPHELE_NOISE_INC
#define NEPHELE_NOISE_INC

// pcg3d (Jarzynski & Olano, "Hash Functions for GPU Rendering", 2020).
uvec3 pcg3d(uvec3 v) {
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v = v ^ (v >> 16u);
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  return v;
}

// Three uniform values in [0, 1] for an integer lattice cell, different for each seed.
vec3 hash_cell(ivec3 cell, uint seed) {
  uvec3 h = pcg3d(uvec3(cell) + uvec3(seed * 0x9E3779B9u, seed * 0x85EBCA6Bu, seed));
  return vec3(h) * (1.0f / 4294967295.0f);
}

// The cell's index modulo the period, in [0, period) also for negative cells (floor_div).
ivec3 wrap_cell(ivec3 cell, int period) { return cell - period * floor_div(cell, period); }

// Quintic fade (Perlin 2002).
vec3 fade(vec3 t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }

float perlin_corner(ivec3 cell, vec3 offset, int period, uint seed) {
  vec3 g = normalize(hash_cell(wrap_cell(cell, period), seed) * 2.0f - 1.0f + 1e-6f);
  return dot(g, offset);
}

// Perlin noise with lattice period `period` (p in lattice units); result roughly in [-1, 1].
float perlin_tiled(vec3 p, int period, uint seed) {
  vec3 pf = floor(p);
  ivec3 i0 = ivec3(pf);
  vec3 f = p - pf;
  vec3 u = fade(f);
  float n000 = perlin_corner(i0 + ivec3(0, 0, 0), f - vec3(0.0f, 0.0f, 0.0f), period, seed);
  float n100 = perlin_corner(i0 + ivec3(1, 0, 0), f - vec3(1.0f, 0.0f, 0.0f), period, seed);
  float n010 = perlin_corner(i0 + ivec3(0, 1, 0), f - vec3(0.0f, 1.0f, 0.0f), period, seed);
  float n110 = perlin_corner(i0 + ivec3(1, 1, 0), f - vec3(1.0f, 1.0f, 0.0f), period, seed);
  float n001 = perlin_corner(i0 + ivec3(0, 0, 1), f - vec3(0.0f, 0.0f, 1.0f), period, seed);
  float n101 = perlin_corner(i0 + ivec3(1, 0, 1), f - vec3(1.0f, 0.0f, 1.0f), period, seed);
  float n011 = perlin_corner(i0 + ivec3(0, 1, 1), f - vec3(0.0f, 1.0f, 1.0f), period, seed);
  float n111 = perlin_corner(i0 + ivec3(1, 1, 1), f - vec3(1.0f, 1.0f, 1.0f), period, seed);
  float nx00 = mix(n000, n100, u.x);
  float nx10 = mix(n010, n110, u.x);
  float nx01 = mix(n001, n101, u.x);
  float nx11 = mix(n011, n111, u.x);
  return mix(mix(nx00, nx10, u.y), mix(nx01, nx11, u.y), u.z);
}

// Worley noise (seed 000, 1.2.3): one jittered feature point per cell of a lattice with period
// `period`; returns 1 - (distance to the nearest point), clamped to [0, 1] (the inverted
// Voronoi distance the seed describes), with p in lattice units.
float worley_tiled(vec3 p, int period, uint seed) {
  vec3 pf = floor(p);
  ivec3 cell = ivec3(pf);
  vec3 f = p - pf;
  float nearest_sq = 3.0f;
  for (int z = -1; z <= 1; ++z)
    for (int y = -1; y <= 1; ++y)
      for (int x = -1; x <= 1; ++x) {
        ivec3 offset = ivec3(x, y, z);
        vec3 feature = vec3(offset) + hash_cell(wrap_cell(cell + offset, period), seed);
        vec3 d = feature - f;
        nearest_sq = min(nearest_sq, dot(d, d));
      }
  return saturate(1.0f - sqrt(nearest_sq));
}

// Three octaves of Worley with decreasing amplitudes (Schneider 2015): periods f, 2f, 4f.
float worley_fbm(vec3 uvw, int period, uint seed) {
  float fp = float(period);
  return worley_tiled(uvw * fp, period, seed) * 0.625f +
         worley_tiled(uvw * fp * 2.0f, period * 2, seed + 1u) * 0.25f +
         worley_tiled(uvw * fp * 4.0f, period * 4, seed + 2u) * 0.125f;
}

// Perlin fBm of `octaves` octaves, mapped to [0, 1]; uvw in tile units [0, 1).
float perlin_fbm01(vec3 uvw, int period, int octaves, uint seed) {
  float sum = 0.0f;
  float amplitude = 0.5f;
  float norm = 0.0f;
  int p = period;
  for (int i = 0; i < octaves; ++i) {
    sum += amplitude * perlin_tiled(uvw * float(p), p, seed + uint(i));
    norm += amplitude;
    amplitude *= 0.5f;
    p *= 2;
  }
  return saturate(0.5f + 0.5f * sum / norm * 1.4f);
}

// Perlin-Worley (Schneider 2015): Perlin fBm remapped so Worley cells give it billowy shapes.
float perlin_worley(vec3 uvw, int period, uint seed) {
  float perlin = perlin_fbm01(uvw, period, 4, seed);
  float worley = worley_fbm(uvw, period, seed + 17u);
  return saturate(remap(perlin, 0.0f, 1.0f, worley, 1.0f));
}

#endif
