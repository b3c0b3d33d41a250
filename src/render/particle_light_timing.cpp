#include "render/particle_light_timing.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "particles/particle_lighting.h"
#include "render/frame_renderer_impl.h"

namespace nephele {

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Lights every cloud of `field` with the vectorised CPU splat; returns the time (ms).
double light_on_cpu(particles::ParticleField& field, const ParticleCloudParams& params,
                    const glm::vec3& towards_light, float forward) {
  const auto start = std::chrono::steady_clock::now();
  for (particles::ParticleCloud& c : field.clouds)
    particles::light_cloud(c, towards_light, forward, params.opacity, params.light_buffer);
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

}  // namespace

ParticleLightTiming measure_particle_lighting(FrameRenderer::Impl& renderer,
                                              const particles::ParticleField& field,
                                              const ParticleCloudParams& params,
                                              const glm::vec3& towards_light, int repeats) {
  repeats = std::max(repeats, 1);
  const float forward = particles::forward_share(params);
  ParticleLightTiming out;
  out.buffer = std::clamp(params.light_buffer, 1, 64);
  out.repeats = repeats;
  out.clouds = field.clouds.size();
  out.particles = field.particles();

  particles::ParticleField cpu = field;
  std::vector<double> cpu_ms, gpu_ms, wall_ms, prepare_ms;
  ParticleLightGpuResult gpu;
  // Run 0 warms caches and makes the pipeline; it is not counted. CPU and device alternate so
  // that a slow spell of a shared machine falls on both.
  for (int r = 0; r <= repeats; ++r) {
    const double ms = light_on_cpu(cpu, params, towards_light, forward);
    gpu = renderer.particle_light.light(renderer.state, field, towards_light, forward,
                                        params.opacity, params.light_buffer);
    if (r == 0) continue;
    cpu_ms.push_back(ms);
    gpu_ms.push_back(gpu.gpu_ms);
    wall_ms.push_back(gpu.wall_ms);
    prepare_ms.push_back(gpu.prepare_ms);
  }
  out.cpu_ms = median(cpu_ms);
  out.invocations = gpu.invocations;
  out.gpu_ms = median(gpu_ms);
  out.gpu_wall_ms = median(wall_ms);
  out.gpu_prepare_ms = median(prepare_ms);

  size_t i = 0;
  for (const particles::ParticleCloud& c : cpu.clouds)
    for (const particles::Particle& p : c.particles) {
      const double d = std::abs(double(gpu.lights[i++]) - double(p.light));
      out.max_difference = std::max(out.max_difference, d);
      out.differing += d > 0.0;
    }
  return out;
}

ParticleLightTiming measure_particle_lighting(const RendererOptions& options,
                                              const particles::ParticleField& field,
                                              const ParticleCloudParams& params,
                                              const glm::vec3& towards_light, int repeats) {
  FrameRenderer::Impl renderer(options);
  return measure_particle_lighting(renderer, field, params, towards_light, repeats);
}

}  // namespace nephele
