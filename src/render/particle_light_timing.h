// The particle clouds' lighting on the CPU (particles/particle_lighting.h) against the same
// splat on the device (render/modules/particle_light_gpu/particle_light_gpu.h), timed: the seed's
// claim that the CPU is two orders of magnitude faster than the graphics card, measured (`nephele
// bench
// --impostors`).
#pragma once

#include <cstddef>

#include <glm/vec3.hpp>

#include "nephele/frame.h"
#include "nephele/renderer.h"
#include "nephele/scene.h"
#include "particles/particle_field.h"

namespace nephele {

struct ParticleLightTiming {
  int buffer = 0;  // the splat buffer's side (texels): params.light_buffer, clamped to [1, 64]
  int repeats = 0;
  int invocations = 0;  // the device pass's workgroup, one a cloud
  size_t clouds = 0, particles = 0;
  // Medians over the repeats (ms).
  double cpu_ms = 0.0;          // light_cloud (vectorised) over every cloud, sort included
  double gpu_ms = 0.0;          // the device pass's timestamps (0 without timestamps)
  double gpu_wall_ms = 0.0;     // host: splats uploaded, pass submitted and waited for, lights
                                // read back
  double gpu_prepare_ms = 0.0;  // host: the projection and sort the device path needs first
  // The device's lights against the CPU's (one step of the byte buffer is 1/255).
  double max_difference = 0.0;
  size_t differing = 0;  // particles whose lights differ at all
};

// Lights every cloud of `field` from `towards_light` (unit, ENU, towards the light) with
// `params`' forward share, opacity and light_buffer, `repeats` times on the CPU and on the
// device of `renderer` (one submission a repeat, waited for), after one untimed run of each.
// `field` is not changed.
ParticleLightTiming measure_particle_lighting(FrameRenderer::Impl& renderer,
                                              const particles::ParticleField& field,
                                              const ParticleCloudParams& params,
                                              const glm::vec3& towards_light, int repeats);
// The same on a renderer of its own (options: the device, the validation layer).
ParticleLightTiming measure_particle_lighting(const RendererOptions& options,
                                              const particles::ParticleField& field,
                                              const ParticleCloudParams& params,
                                              const glm::vec3& towards_light, int repeats);

}  // namespace nephele
