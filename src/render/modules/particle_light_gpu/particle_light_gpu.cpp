#include "render/modules/particle_light_gpu/particle_light_gpu.h"

#include <algorithm>
#include <chrono>
#include <cstring>

#include "nephele/error.h"
#include "particles/particle_lighting.h"
#include "render/gpu_params.h"

namespace nephele {

namespace {

// Invocations a cloud. A splat covers 12 texels of a 32^2 buffer on average, 36 of a 64^2 one
// (at most 49 and 144; the benchmark's field): more invocations only wait at the barriers, two
// a particle. A GPU: one warp (32). lavapipe runs a group as rows of 8 SIMD lanes (256 bits)
// and switches between the rows at every barrier: one row, whose barriers cost nothing, was the
// fastest there (the benchmark's field, buffer 32: 8 invocations 2.4 times faster than 32, 4.3
// times than 64, 15 times than 256).
int invocations_for(const gpu::Context& ctx) {
  return ctx.is_cpu() ? 8 : 32;
}

double ms_since(std::chrono::steady_clock::time_point start) {
  const auto elapsed = std::chrono::steady_clock::now() - start;
  return std::chrono::duration<double, std::milli>(elapsed).count();
}

// Where the splats of each cloud start in the upload (and its particles' lights in the
// read-back), and the total.
std::vector<size_t> first_of_each(const particles::ParticleField& field, size_t& total) {
  std::vector<size_t> first;
  total = 0;
  for (const particles::ParticleCloud& c : field.clouds) {
    first.push_back(total);
    total += c.particles.size();
  }
  return first;
}

}  // namespace

ParticleLightGpuModule::ParticleLightGpuModule(gpu::Context& ctx, gpu::DescriptorSet& set)
    : ctx_(ctx), set_(set), invocations_(invocations_for(ctx)) {
  reserve(1, 1);
}

ParticleLightGpuModule::~ParticleLightGpuModule() = default;

const gpu::Kernel& ParticleLightGpuModule::kernel(int buffer) {
  std::unique_ptr<gpu::Kernel>& k = kernels_[buffer];
  if (!k)
    k = std::make_unique<gpu::Kernel>(ctx_, set_, "particle_light.comp.spv",
                                      std::vector<int32_t>{buffer, invocations_});
  return *k;
}

void ParticleLightGpuModule::reserve(size_t splats, size_t clouds) {
  splats = std::max<size_t>(splats, 1);
  clouds = std::max<size_t>(clouds, 1);
  if (splats_.size() >= splats * sizeof(gpu::ParticleSplatGpu) &&
      clouds_.size() >= clouds * sizeof(gpu::ParticleLightCloudGpu))
    return;
  ctx_.wait_queue_idle();  // a frame in flight may still hold the old buffers in its set
  constexpr VkBufferUsageFlags kUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  splats_ = gpu::Buffer(ctx_, splats * sizeof(gpu::ParticleSplatGpu), kUsage);
  lights_ = gpu::Buffer(ctx_, splats * sizeof(float), kUsage);
  clouds_ = gpu::Buffer(ctx_, clouds * sizeof(gpu::ParticleLightCloudGpu), kUsage);
  set_.bind_buffer(gpu::kParticleSplats, splats_, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  set_.bind_buffer(gpu::kParticleLightClouds, clouds_, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  set_.bind_buffer(gpu::kParticleLights, lights_, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
}

ParticleLightGpuResult ParticleLightGpuModule::light(GpuState& state,
                                                     const particles::ParticleField& field,
                                                     const glm::vec3& towards_light,
                                                     float forward_share, float opacity,
                                                     int buffer) {
  buffer = std::clamp(buffer, 1, 64);
  ParticleLightGpuResult result;
  result.invocations = invocations_;
  size_t total = 0;
  const std::vector<size_t> first = first_of_each(field, total);
  if (total == 0) return result;
  // The float index of ParticleSplatGpu, and the int range of ParticleLightCloudGpu.
  if (total >= (size_t(1) << 24))
    throw InputError("particle lighting on the device: " + std::to_string(total) +
                     " particles, at most 2^24 - 1");
  const gpu::Kernel& pass = kernel(buffer);
  reserve(total, field.clouds.size());

  auto start = std::chrono::steady_clock::now();
  std::vector<std::vector<particles::Splat>> sorted;
  sorted.reserve(field.clouds.size());
  for (const particles::ParticleCloud& c : field.clouds)
    sorted.push_back(particles::splats_from_light(c, towards_light, buffer));
  result.prepare_ms = ms_since(start);

  start = std::chrono::steady_clock::now();
  auto* splats = static_cast<gpu::ParticleSplatGpu*>(splats_.data());
  auto* clouds = static_cast<gpu::ParticleLightCloudGpu*>(clouds_.data());
  for (size_t c = 0; c < sorted.size(); ++c) {
    clouds[c].range = glm::ivec4(int(first[c]), int(sorted[c].size()), 0, 0);
    clouds[c].shading = glm::vec4(forward_share, opacity, 0.0f, 0.0f);
    for (size_t k = 0; k < sorted[c].size(); ++k) {
      const particles::Splat& s = sorted[c][k];
      splats[first[c] + k].splat = glm::vec4(s.x, s.y, s.radius, float(s.index));
    }
  }
  const uint32_t groups = uint32_t(field.clouds.size());
  const auto timings = state.run_once(gpu::FrameParams{}, [&](VkCommandBuffer cmd) {
    gpu::dispatch(cmd, pass, *state.timer, "particle_light", groups * uint32_t(invocations_), 1, 1,
                  uint32_t(invocations_), 1, 1);
  });
  result.lights.resize(total);
  std::memcpy(result.lights.data(), lights_.data(), total * sizeof(float));
  result.wall_ms = ms_since(start);
  for (const auto& [name, ms] : timings) result.gpu_ms += ms;
  return result;
}

}  // namespace nephele
