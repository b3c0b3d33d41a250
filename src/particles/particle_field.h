// The particle clouds' shapes (seed 003, 3.3.3): a grid of cells over the field, one particle
// in each cell where 3D Perlin noise (4D, with time, for a changing sky) under the cloud's
// envelope exceeds a threshold; the noise's value sets the particle's size and picks its texture;
// a random offset within its cell hides the grid. The threshold comes from the noise's
// distribution, so `coverage` holds at every moment whatever the animation does.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "nephele/scene.h"

namespace nephele::particles {

// The procedural particle textures (particle_textures.h) a particle picks from.
constexpr int kTextureCount = 4;

struct Particle {
  glm::vec3 position_m{0.0f};  // ENU (m) at the field's time
  float radius_m = 0.0f;
  float light = 1.0f;  // I_k: the share of the sunlight that reaches it (particle_lighting.h)
  int texture = 0;     // [0, kTextureCount)
};

// One cloud: the particles of one square of the field, lit and drawn (or turned into an
// impostor) as a unit.
struct ParticleCloud {
  glm::vec3 center_m{0.0f};   // ENU: the middle of its square at the layer's mid height
  float bound_radius_m = 0.0f;  // a sphere about center_m holding every particle whole
  std::vector<Particle> particles;
  // Its last lighting (particle_lighting.h): the direction towards the light (0 = never lit),
  // the parameters it used, and how many lightings it has had (a drawing of it is stale when
  // the count moved on).
  glm::vec3 lit_towards{0.0f};
  float lit_forward = -1.0f, lit_opacity = -1.0f;
  int lit_buffer = 0;
  uint32_t lightings = 0;
};

struct ParticleField {
  std::vector<ParticleCloud> clouds;  // only squares holding at least one particle
  float threshold = 0.0f;             // the spawn threshold of the envelope-weighted noise
  size_t cells = 0;                   // cells of the grid over the field
  size_t particles() const;
};

// The value that decides whether a cell spawns: fractal Perlin noise in [0, 1] times an
// envelope in [0.22, 1] (thinner towards the tops and towards the corners of the cloud's
// square), at ENU `p_m` relative to the drifting field and `time_s`.
float spawn_value(const ParticleCloudParams& params, const glm::vec3& p_m, float time_s);

// The threshold that `coverage` of the cells exceed, from the values' distribution over a
// square's volume (and over time when the sky evolves): deterministic for the parameters.
float coverage_threshold(const ParticleCloudParams& params);

// The field at `time_s` (empty when coverage is 0). Deterministic for the parameters and time.
ParticleField generate_field(const ParticleCloudParams& params, float time_s);

// What generate_field's result depends on: two fields are the same when their shapes are.
struct FieldShape {
  float coverage, bottom_altitude_m, top_altitude_m, field_radius_m, cloud_spacing_m, cell_m,
      particle_radius_m, noise_period_m, evolution_s;
  uint32_t seed;
  float time_s;
  bool operator==(const FieldShape&) const = default;
};
FieldShape field_shape(const ParticleCloudParams& params, float time_s);

}  // namespace nephele::particles
