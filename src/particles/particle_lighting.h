// The particle clouds' lighting on the CPU (seed 003, 3.3.2, after Harris and Lastra 2001):
// a cloud's particles, nearest the light first, are splatted into a small one-byte-per-texel
// buffer seen from the light. Before a particle is drawn, the buffer's value at its centre is
// read as the light reaching it, I_k; then the particle is drawn with its opacity a_k(x) (its
// radial profile, common/particle_inc.glsl), which lets through T_k = 1 - a_k and scatters on
// the share f of what it intercepts that stays in the light's direction:
//   I_{k+1}(x) = g_k(x) + T_k(x) I(x),  g_k(x) = f a_k(x) I_k,  f = albedo p(0) gamma
// (Harris and Lastra's recurrence, I_0 = 1; p the phase function in 1/sr, gamma the solid angle
// about the forward direction). The splat is vectorised with the compiler's vector extensions;
// the buffer (64 x 72 bytes at most) stays in the first-level cache.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "nephele/scene.h"
#include "particles/particle_field.h"

namespace nephele::particles {

// f = albedo p(0) gamma, clamped to [0, 1]: the share of the light a particle intercepts that it
// scatters on in the light's direction.
float forward_share(const ParticleCloudParams& params);

// The cloud seen from the light: its particles nearest the light first (a stable sort on the
// distance along `towards_light`), each with its centre and radius in the texels of a
// `buffer` x `buffer` splat buffer framing the cloud. light_cloud splats them in this order;
// the GPU version (render/modules/particle_light_gpu/particle_light_gpu.h) uploads them.
struct Splat {
  float x, y, radius;
  uint32_t index;  // the particle's in cloud.particles
};
std::vector<Splat> splats_from_light(const ParticleCloud& cloud, const glm::vec3& towards_light,
                                     int buffer);

// Lights every particle of `cloud` from the unit direction `towards_light` (ENU, from the cloud
// to the light): sets each particle's `light` and the cloud's lit_towards. `buffer` is 32 or 64.
// The vectorised splat; light_cloud_scalar is the same arithmetic one texel at a time (tests).
void light_cloud(ParticleCloud& cloud, const glm::vec3& towards_light, float forward_share,
                 float opacity, int buffer);
void light_cloud_scalar(ParticleCloud& cloud, const glm::vec3& towards_light, float forward_share,
                        float opacity, int buffer);

// Relighting spread over frames: clouds never lit, lit from a direction more than
// `max_angle_deg` from today's, or lit with other parameters (forward_share, opacity,
// light_buffer), are relit, the ones never lit first, until `budget_particles`
// particles have been lit in this call (at least one cloud per call). Returns the clouds relit.
struct RelightReport {
  int clouds = 0;
  size_t particles = 0;
  int stale_left = 0;  // clouds still waiting
};
RelightReport relight(ParticleField& field, const glm::vec3& towards_light,
                      const ParticleCloudParams& params, size_t budget_particles,
                      float max_angle_deg = 0.5f);

}  // namespace nephele::particles
