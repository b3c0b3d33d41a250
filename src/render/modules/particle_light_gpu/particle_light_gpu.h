// The particle clouds' lighting on the device (particle_light.comp): the CPU's splat
// (particles/particle_lighting.h) done by a compute pass, one workgroup a cloud, to measure the
// seed's claim that the CPU does it two orders of magnitude faster than the graphics card. The
// host projects and sorts each cloud's particles (particles::splats_from_light), uploads them,
// and reads the lights back; the frames never use it (the CPU lights them).
#pragma once

#include <glm/vec3.hpp>
#include <map>
#include <memory>
#include <vector>

#include "gpu/kernel.h"
#include "particles/particle_field.h"
#include "render/passes.h"

namespace nephele {

struct ParticleLightGpuResult {
  // I_k of every particle: the field's clouds in order, each cloud's particles in order.
  std::vector<float> lights;
  double prepare_ms = 0.0;  // host: the splats projected and sorted (as light_cloud does)
  double wall_ms = 0.0;     // host: the splats uploaded, the pass submitted and waited for, the
                            // lights read back (prepare_ms not included)
  double gpu_ms = 0.0;      // the pass's timestamps (0 where the queue has none)
  int invocations = 0;      // a cloud's workgroup
};

class ParticleLightGpuModule {
 public:
  // Binds placeholder buffers: every binding of the set must be written before any pass runs.
  ParticleLightGpuModule(gpu::Context& ctx, gpu::DescriptorSet& set);
  ~ParticleLightGpuModule();

  // Lights every cloud of `field` from the unit direction `towards_light` as light_cloud does
  // (`buffer` clamped to [1, 64] as there), in one submission of `state`'s one-off slot that
  // the host waits for. The field is not changed.
  ParticleLightGpuResult light(GpuState& state, const particles::ParticleField& field,
                               const glm::vec3& towards_light, float forward_share, float opacity,
                               int buffer);

 private:
  const gpu::Kernel& kernel(int buffer);  // made when first needed: one a buffer side
  // Buffers for `splats` splats (= particles) and `clouds` clouds, bound.
  void reserve(size_t splats, size_t clouds);

  gpu::Context& ctx_;
  gpu::DescriptorSet& set_;
  const int invocations_;  // a cloud's workgroup
  std::map<int, std::unique_ptr<gpu::Kernel>> kernels_;
  gpu::Buffer splats_, clouds_, lights_;
};

}  // namespace nephele
