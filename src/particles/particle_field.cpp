#include "particles/particle_field.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include <glm/geometric.hpp>

#include "particles/perlin.h"

namespace nephele::particles {

namespace {

// A 32-bit integer hash (Wellons' lowbias32): per-cell random numbers without storing any.
uint32_t mix32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

float cell_random(uint32_t seed, int i, int j, int k, uint32_t which) {
  uint32_t h = mix32(seed ^ 0x9e3779b9u);
  h = mix32(h ^ uint32_t(i));
  h = mix32(h ^ uint32_t(j) * 0x85ebca6bu);
  h = mix32(h ^ uint32_t(k) * 0xc2b2ae35u);
  h = mix32(h ^ which);
  return float(h >> 8) * (1.0f / 16777216.0f);  // [0, 1)
}

// The noise object for a seed, shared by every call with it.
const PerlinNoise& noise_for(uint32_t seed) {
  thread_local uint32_t cached_seed = ~0u;
  thread_local PerlinNoise noise(0);
  if (cached_seed != seed) noise = PerlinNoise(seed), cached_seed = seed;
  return noise;
}

// The nearest square's centre (east, north) to `p`: squares of `spacing` centred on multiples
// of it.
glm::vec2 square_center(const glm::vec2& p, float spacing) {
  return glm::vec2(std::round(p.x / spacing), std::round(p.y / spacing)) * spacing;
}

// The grid's layers of cells [x, y): those whose centres ((k + 0.5) cell) lie in the layer.
glm::ivec2 cell_layers(const ParticleCloudParams& params) {
  const int k0 = int(std::ceil(params.bottom_altitude_m / params.cell_m - 0.5f));
  const int k1 = int(std::ceil(params.top_altitude_m / params.cell_m - 0.5f));
  return {k0, std::max(k1, k0 + 1)};
}

}  // namespace

size_t ParticleField::particles() const {
  size_t n = 0;
  for (const ParticleCloud& c : clouds) n += c.particles.size();
  return n;
}

float spawn_value(const ParticleCloudParams& params, const glm::vec3& p_m, float time_s) {
  const PerlinNoise& noise = noise_for(params.seed);
  const glm::vec3 q = p_m / params.noise_period_m;
  // Two octaves; the second shifted so its lattice does not line up with the first's.
  float n;
  if (params.evolution_s > 0.0f) {
    const float w = time_s / params.evolution_s;
    n = noise.noise4(q.x, q.y, q.z, w) +
        0.5f * noise.noise4(2.0f * q.x + 17.3f, 2.0f * q.y + 5.1f, 2.0f * q.z + 11.7f, 2.0f * w);
  } else {
    n = noise.noise3(q.x, q.y, q.z) +
        0.5f * noise.noise3(2.0f * q.x + 17.3f, 2.0f * q.y + 5.1f, 2.0f * q.z + 11.7f);
  }
  const float value = std::clamp(0.5f + 0.6f * n, 0.0f, 1.0f);
  // The envelope: the noise decides where clouds are; the envelope thins them towards the tops
  // (to 40% at the top) and draws each towards the middle of its own square (to 55% at the
  // corners), so a cloud's particles are mostly its square's, whom they are lit and drawn with.
  const glm::vec2 c = square_center(glm::vec2(p_m), params.cloud_spacing_m);
  const float r = glm::length(glm::vec2(p_m) - c) / (0.5f * params.cloud_spacing_m);
  const float h = std::clamp((p_m.z - params.bottom_altitude_m) /
                                 (params.top_altitude_m - params.bottom_altitude_m),
                             0.0f, 1.0f);
  const float envelope = (1.0f - 0.6f * h * h) * (0.55f + 0.45f * std::exp(-2.0f * r * r));
  return value * envelope;
}

float coverage_threshold(const ParticleCloudParams& params) {
  if (params.coverage >= 1.0f) return -1.0f;  // every cell
  // Values where cells of squares far apart put their particles (the grid's layers of cells,
  // whose centres lie in the layer, and a random offset in each) and, for an evolving sky, at
  // times over many evolution periods.
  constexpr int kSamples = 32768;
  std::mt19937 rng(params.seed * 2654435761u + 7u);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<float> values(kSamples);
  const float spacing = params.cloud_spacing_m;
  const glm::ivec2 layers = cell_layers(params);
  for (int i = 0; i < kSamples; ++i) {
    const glm::vec2 square = glm::vec2(float(i % 64), float(i / 64 % 64)) * spacing * 7.0f;
    const int k = layers.x + std::min(int(unit(rng) * float(layers.y - layers.x)), layers.y - layers.x - 1);
    const glm::vec3 p(square.x + (unit(rng) - 0.5f) * spacing,
                      square.y + (unit(rng) - 0.5f) * spacing, (float(k) + unit(rng)) * params.cell_m);
    const float t = params.evolution_s > 0.0f ? unit(rng) * 200.0f * params.evolution_s : 0.0f;
    values[i] = spawn_value(params, p, t);
  }
  const size_t rank = std::min(size_t(kSamples - 1), size_t((1.0f - params.coverage) * kSamples));
  std::nth_element(values.begin(), values.begin() + rank, values.end());
  return values[rank];
}

FieldShape field_shape(const ParticleCloudParams& p, float time_s) {
  return {p.coverage, p.bottom_altitude_m, p.top_altitude_m, p.field_radius_m, p.cloud_spacing_m,
          p.cell_m, p.particle_radius_m, p.noise_period_m, p.evolution_s, p.seed, time_s};
}

ParticleField generate_field(const ParticleCloudParams& params, float time_s) {
  ParticleField field;
  if (params.coverage <= 0.0f) return field;
  field.threshold = coverage_threshold(params);
  const float spacing = params.cloud_spacing_m, cell = params.cell_m;
  const glm::vec3 drift(params.wind_mps * time_s, 0.0f);
  // The squares whose centres lie within the field's radius.
  std::vector<glm::ivec2> squares;
  const int n = int(std::floor(params.field_radius_m / spacing));
  for (int j = -n; j <= n; ++j)
    for (int i = -n; i <= n; ++i)
      if (glm::length(glm::vec2(i, j)) * spacing <= params.field_radius_m) squares.push_back({i, j});
  const glm::ivec2 layers = cell_layers(params);
  const int k0 = layers.x, k1 = layers.y;
  std::vector<ParticleCloud> clouds(squares.size());
  std::vector<size_t> cells(squares.size());
  const float threshold = field.threshold;
  tbb::parallel_for(size_t(0), squares.size(), [&](size_t s) {
    const glm::vec2 c = glm::vec2(squares[s]) * spacing;
    // Cells whose centres ((i + 0.5) cell) lie in the square [c - spacing/2, c + spacing/2).
    const int i0 = int(std::ceil((c.x - 0.5f * spacing) / cell - 0.5f));
    const int i1 = int(std::ceil((c.x + 0.5f * spacing) / cell - 0.5f));
    const int j0 = int(std::ceil((c.y - 0.5f * spacing) / cell - 0.5f));
    const int j1 = int(std::ceil((c.y + 0.5f * spacing) / cell - 0.5f));
    ParticleCloud& cloud = clouds[s];
    cloud.center_m = glm::vec3(c, 0.5f * (params.bottom_altitude_m + params.top_altitude_m)) + drift;
    cells[s] = size_t(std::max(i1 - i0, 0)) * size_t(std::max(j1 - j0, 0)) * size_t(std::max(k1 - k0, 0));
    for (int k = k0; k < k1; ++k)
      for (int j = j0; j < j1; ++j)
        for (int i = i0; i < i1; ++i) {
          // A random offset within the cell (seed 003: "within one pixel").
          const glm::vec3 offset(cell_random(params.seed, i, j, k, 0),
                                 cell_random(params.seed, i, j, k, 1),
                                 cell_random(params.seed, i, j, k, 2));
          const glm::vec3 p = (glm::vec3(i, j, k) + offset) * cell;
          const float v = spawn_value(params, p, time_s);
          if (!(v > threshold) && params.coverage < 1.0f) continue;
          // How far above the threshold, in [0, 1]: the particle's size and its texture.
          const float u = std::clamp((v - threshold) / std::max(1.0f - threshold, 1e-6f), 0.0f, 1.0f);
          Particle particle;
          particle.position_m = p + drift;
          particle.radius_m = params.particle_radius_m * (0.45f + 0.55f * u);
          particle.texture = std::min(int(u * kTextureCount), kTextureCount - 1);
          cloud.particles.push_back(particle);
          cloud.bound_radius_m =
              std::max(cloud.bound_radius_m,
                       glm::length(particle.position_m - cloud.center_m) + particle.radius_m);
        }
  });
  for (size_t s = 0; s < clouds.size(); ++s) {
    field.cells += cells[s];
    if (!clouds[s].particles.empty()) field.clouds.push_back(std::move(clouds[s]));
  }
  return field;
}

}  // namespace nephele::particles
