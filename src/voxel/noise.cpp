// nephele — voxel clouds: Curly-Alligator noise (seed 002): alligator (cellular) noise as in
// Houdini, its domain displaced by curl noise so the billows curl like turbulent cloud edges.
#include <cmath>
#include <cstdint>

#include "voxel/voxel_grid.h"

namespace nephele::voxel {
namespace {

// pcg3d (Jarzynski & Olano 2020): three well-mixed 32-bit values from a lattice point.
glm::uvec3 pcg3d(glm::uvec3 v) {
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v ^= v >> 16u;
  v.x += v.y * v.z;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  return v;
}

glm::vec3 to_unit(glm::uvec3 h) {
  return glm::vec3(h >> 8u) * (1.0f / 16777216.0f);
}

glm::uvec3 lattice(glm::ivec3 c, uint32_t salt) {
  return glm::uvec3(static_cast<uint32_t>(c.x), static_cast<uint32_t>(c.y),
                    static_cast<uint32_t>(c.z) ^ (salt * 0x9E3779B9u));
}

// Alligator noise: each cell holds a feature point and an intensity; a point takes the
// largest intensity x falloff of distance (one cell) over the feature points near it, which
// makes round bumps that crowd into each other like cauliflower. In [0, 1].
float alligator(glm::vec3 q, uint32_t salt) {
  const glm::ivec3 cell = glm::ivec3(glm::floor(q));
  float value = 0.0f;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const glm::ivec3 c = cell + glm::ivec3(dx, dy, dz);
        const glm::uvec3 h = pcg3d(lattice(c, salt));
        const glm::vec3 feature = glm::vec3(c) + to_unit(h);
        const glm::vec3 d = q - feature;
        const float r2 = glm::dot(d, d);
        if (r2 >= 1.0f) continue;
        const float intensity = float(pcg3d(h).x >> 8u) * (1.0f / 16777216.0f);
        // (1 - r^2)^3: smooth at the feature point and where it reaches zero (r = 1).
        const float s = 1.0f - r2;
        value = std::max(value, intensity * s * s * s);
      }
  return value;
}

// Gradient noise with its analytic gradient (quintic fade): the curl of three such
// potentials is divergence-free, so the displaced domain neither bunches nor thins out.
float gradient_noise(glm::vec3 p, uint32_t salt, glm::vec3& gradient) {
  const glm::ivec3 c = glm::ivec3(glm::floor(p));
  const glm::vec3 f = p - glm::vec3(c);
  const glm::vec3 u = f * f * f * (f * (f * 6.0f - 15.0f) + 10.0f);
  const glm::vec3 du = 30.0f * f * f * (f * (f - 2.0f) + 1.0f);
  float g[8][3], v[8];
  for (int n = 0; n < 8; ++n) {
    const glm::ivec3 o((n & 1), (n >> 1) & 1, (n >> 2) & 1);
    const glm::vec3 dir = to_unit(pcg3d(lattice(c + o, salt))) * 2.0f - 1.0f;
    g[n][0] = dir.x, g[n][1] = dir.y, g[n][2] = dir.z;
    v[n] = glm::dot(dir, f - glm::vec3(o));
  }
  const auto lerp = [](float a, float b, float t) { return a + (b - a) * t; };
  // Trilinear blend of the corner values and, for the gradient, of their gradients plus the
  // fade's derivative times the value differences.
  const float x00 = lerp(v[0], v[1], u.x), x10 = lerp(v[2], v[3], u.x);
  const float x01 = lerp(v[4], v[5], u.x), x11 = lerp(v[6], v[7], u.x);
  const float y0 = lerp(x00, x10, u.y), y1 = lerp(x01, x11, u.y);
  const float value = lerp(y0, y1, u.z);
  glm::vec3 grad(0.0f);
  for (int n = 0; n < 8; ++n) {
    const glm::ivec3 o((n & 1), (n >> 1) & 1, (n >> 2) & 1);
    const float wx = o.x ? u.x : 1.0f - u.x, wy = o.y ? u.y : 1.0f - u.y,
                wz = o.z ? u.z : 1.0f - u.z;
    grad += wx * wy * wz * glm::vec3(g[n][0], g[n][1], g[n][2]);
    grad.x += (o.x ? du.x : -du.x) * wy * wz * v[n];
    grad.y += wx * (o.y ? du.y : -du.y) * wz * v[n];
    grad.z += wx * wy * (o.z ? du.z : -du.z) * v[n];
  }
  gradient = grad;
  return value;
}

glm::vec3 curl_noise(glm::vec3 p) {
  glm::vec3 a, b, c;
  gradient_noise(p, 11u, a);
  gradient_noise(p + glm::vec3(31.4f, 17.9f, 5.3f), 12u, b);
  gradient_noise(p + glm::vec3(-7.7f, 43.1f, 23.6f), 13u, c);
  // Potential (a, b, c) -> curl (dc/dy - db/dz, da/dz - dc/dx, db/dx - da/dy).
  return glm::vec3(c.y - b.z, a.z - c.x, b.x - a.y);
}

}  // namespace

float curly_alligator(glm::vec3 p_m, float frequency_per_m) {
  // Far beyond any cloud the lattice would overflow an int; such points get the noise of the
  // nearest point in range.
  const glm::vec3 raw = p_m * frequency_per_m;
  if (!std::isfinite(raw.x + raw.y + raw.z)) return 0.0f;
  const glm::vec3 q = glm::clamp(raw, glm::vec3(-1e6f), glm::vec3(1e6f));
  // Curl displacement of about a third of a cell, at half the frequency: the bumps' edges
  // swirl without tearing them apart.
  const glm::vec3 warped = q + 0.35f * curl_noise(0.5f * q);
  const float octave1 = alligator(warped, 1u);
  const float octave2 = alligator(2.03f * warped + glm::vec3(4.1f, 9.7f, 2.3f), 2u);
  const float value = 0.65f * octave1 + 0.35f * octave2;
  return std::isfinite(value) ? std::fmin(std::fmax(value, 0.0f), 1.0f) : 0.0f;
}

}  // namespace nephele::voxel
