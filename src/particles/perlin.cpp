#include "particles/perlin.h"

#include <cmath>
#include <numeric>
#include <random>

namespace nephele::particles {

namespace {

// 6t^5 - 15t^4 + 10t^3: zero first and second derivatives at the lattice (Perlin 2002).
float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }
float lerp(float t, float a, float b) { return a + t * (b - a); }

// The 12 directions to the edges' midpoints of a cube (Perlin 2002), picked by the hash's low
// four bits (four of them twice).
float grad3(int hash, float x, float y, float z) {
  const int h = hash & 15;
  const float u = h < 8 ? x : y;
  const float v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
  return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}

// The 32 directions to the midpoints of a tesseract's 2-faces: one coordinate 0, the other
// three +-1.
float grad4(int hash, float x, float y, float z, float w) {
  const int h = hash & 31;
  const float a = h < 24 ? x : y, b = h < 16 ? y : z, c = h < 8 ? z : w;
  return ((h & 1) ? -a : a) + ((h & 2) ? -b : b) + ((h & 4) ? -c : c);
}

}  // namespace

PerlinNoise::PerlinNoise(uint32_t seed) {
  std::array<uint8_t, 256> p;
  std::iota(p.begin(), p.end(), uint8_t(0));
  std::mt19937 rng(seed);
  for (int i = 255; i > 0; --i) std::swap(p[i], p[std::uniform_int_distribution<int>(0, i)(rng)]);
  for (int i = 0; i < 512; ++i) perm_[i] = p[i & 255];
}

float PerlinNoise::noise3(float x, float y, float z) const {
  const float fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
  const int X = int(fx) & 255, Y = int(fy) & 255, Z = int(fz) & 255;
  x -= fx, y -= fy, z -= fz;
  const float u = fade(x), v = fade(y), w = fade(z);
  const int A = hash(X) + Y, AA = hash(A) + Z, AB = hash(A + 1) + Z;
  const int B = hash(X + 1) + Y, BA = hash(B) + Z, BB = hash(B + 1) + Z;
  return lerp(w,
              lerp(v, lerp(u, grad3(hash(AA), x, y, z), grad3(hash(BA), x - 1, y, z)),
                   lerp(u, grad3(hash(AB), x, y - 1, z), grad3(hash(BB), x - 1, y - 1, z))),
              lerp(v, lerp(u, grad3(hash(AA + 1), x, y, z - 1), grad3(hash(BA + 1), x - 1, y, z - 1)),
                   lerp(u, grad3(hash(AB + 1), x, y - 1, z - 1),
                        grad3(hash(BB + 1), x - 1, y - 1, z - 1))));
}

float PerlinNoise::noise4(float x, float y, float z, float w) const {
  const float f[4] = {std::floor(x), std::floor(y), std::floor(z), std::floor(w)};
  const int L[4] = {int(f[0]) & 255, int(f[1]) & 255, int(f[2]) & 255, int(f[3]) & 255};
  const float d[4] = {x - f[0], y - f[1], z - f[2], w - f[3]};
  const float s[4] = {fade(d[0]), fade(d[1]), fade(d[2]), fade(d[3])};
  // The 16 corners' contributions, blended along x, then y, z and w.
  float corner[16];
  for (int c = 0; c < 16; ++c) {
    const int o[4] = {c & 1, (c >> 1) & 1, (c >> 2) & 1, (c >> 3) & 1};
    const int h = hash(hash(hash(hash(L[0] + o[0]) + L[1] + o[1]) + L[2] + o[2]) + L[3] + o[3]);
    corner[c] = grad4(h, d[0] - o[0], d[1] - o[1], d[2] - o[2], d[3] - o[3]);
  }
  for (int axis = 0, n = 16; axis < 4; ++axis, n /= 2)
    for (int c = 0; c < n / 2; ++c) corner[c] = lerp(s[axis], corner[2 * c], corner[2 * c + 1]);
  return corner[0];
}

}  // namespace nephele::particles
