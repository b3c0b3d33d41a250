// The particle clouds' lighting on the device (particle_light.comp, render/modules/
// particle_light_gpu.h) against the CPU's (particles/particle_lighting.h): the same splat, so
// every particle's light must match within one step of the byte buffer (1/255), at both buffer
// sides; and the timing the benchmark reports.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "particles/particle_field.h"
#include "particles/particle_lighting.h"
#include "render/frame_renderer_impl.h"
#include "render/particle_light_timing.h"
#include "render_fixture.h"

namespace nephele {
namespace {

constexpr double kOneStep = 1.0 / 255.0;

ParticleCloudParams small_field() {
  ParticleCloudParams p;
  p.coverage = 0.4f;
  p.field_radius_m = 6000.0f;
  p.cell_m = 125.0f;
  return p;
}

// The largest |device - CPU| light and how many particles differ at all.
struct Difference {
  double largest = 0.0;
  size_t differing = 0, compared = 0;
};
Difference compare(const std::vector<float>& gpu, const particles::ParticleField& cpu) {
  Difference d;
  for (const particles::ParticleCloud& c : cpu.clouds)
    for (const particles::Particle& p : c.particles) {
      const double diff = std::abs(double(gpu.at(d.compared++)) - double(p.light));
      d.largest = std::max(d.largest, diff);
      d.differing += diff > 0.0;
    }
  return d;
}

TEST(ParticleLightGpu, EveryParticleGetsTheCpusLightWithinOneStep) {
  FrameRenderer::Impl impl(validated());  // every binding bound, as in a frame
  const ParticleCloudParams params = small_field();
  const particles::ParticleField field = particles::generate_field(params, 0.0f);
  ASSERT_GT(field.clouds.size(), 4u);
  const glm::vec3 sun = glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f));
  const float forward = particles::forward_share(params);

  // One cloud first, so the full field's buffers replace smaller ones.
  particles::ParticleField one;
  one.clouds = {field.clouds[0]};
  EXPECT_EQ(impl.particle_light.light(impl.state, one, sun, forward, params.opacity, 32)
                .lights.size(),
            one.particles());

  for (int buffer : {32, 64}) {
    particles::ParticleField cpu = field;
    for (particles::ParticleCloud& c : cpu.clouds)
      particles::light_cloud(c, sun, forward, params.opacity, buffer);
    const ParticleLightGpuResult gpu =
        impl.particle_light.light(impl.state, field, sun, forward, params.opacity, buffer);
    ASSERT_EQ(gpu.lights.size(), field.particles());
    const Difference d = compare(gpu.lights, cpu);
    std::printf("buffer %d: %zu particles in %zu clouds, largest difference %.6f (%.2f steps), "
                "%zu differ; device %.2f ms, wall %.2f ms\n",
                buffer, d.compared, field.clouds.size(), d.largest, d.largest / kOneStep,
                d.differing, gpu.gpu_ms, gpu.wall_ms);
    EXPECT_LE(d.largest, kOneStep + 1e-6) << "buffer " << buffer;
    // Not a trivial agreement: the clouds shade themselves.
    const auto [lo, hi] = std::minmax_element(gpu.lights.begin(), gpu.lights.end());
    EXPECT_LT(*lo, 0.5f * *hi) << "buffer " << buffer;
  }
  EXPECT_EQ(impl.ctx.validation_messages(), 0);
}

TEST(ParticleLightGpu, TheTimingMeasuresBothOnTheSameField) {
  FrameRenderer::Impl impl(validated());
  ParticleCloudParams params = small_field();
  params.light_buffer = 64;
  const particles::ParticleField field = particles::generate_field(params, 0.0f);
  const glm::vec3 sun = glm::normalize(glm::vec3(-0.2f, 0.4f, 0.9f));
  const ParticleLightTiming t = measure_particle_lighting(impl, field, params, sun, 3);
  EXPECT_EQ(t.buffer, 64);
  EXPECT_EQ(t.repeats, 3);
  EXPECT_EQ(t.particles, field.particles());
  EXPECT_EQ(t.clouds, field.clouds.size());
  EXPECT_GT(t.cpu_ms, 0.0);
  EXPECT_GT(t.gpu_wall_ms, 0.0);
  EXPECT_GT(t.gpu_prepare_ms, 0.0);
  if (impl.ctx.has_timestamps()) EXPECT_GT(t.gpu_ms, 0.0);
  EXPECT_LE(t.max_difference, kOneStep + 1e-6);
  EXPECT_EQ(impl.ctx.validation_messages(), 0);
  // The field itself stays unlit.
  for (const particles::ParticleCloud& c : field.clouds) EXPECT_EQ(c.lit_towards, glm::vec3(0.0f));
}

}  // namespace
}  // namespace nephele
