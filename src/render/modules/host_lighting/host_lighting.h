// The lighting and data a host lights its own scene with (nephele::HostLighting, frame.h): the
// sun and the moon at the camera after the air (on the CPU) and the clouds, the sky's light as
// spherical harmonics, the clouds' extinction and the visibility there (host_lighting.comp,
// read back when the frame's slot is reused), the cloud shadow map with its matrix
// (cloud_shadow_map.comp) and the environment cube map with the clouds (environment.comp).
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "gpu/kernel.h"
#include "nephele/frame.h"
#include "render/frame_params.h"
#include "render/gpu_params.h"
#include "render/render_module.h"

namespace nephele {

// The number of vec4s host_lighting.comp writes (bindings_inc.glsl, HostLightingBlock).
constexpr int kHostLightingVec4s = 10;

// The host's lighting from the CPU's part of a frame (`scene`, its lights) and the device's
// (host_lighting.comp's vec4s).
HostLighting host_lighting(const Scene& scene, const SkyLights& lights, const glm::vec4* device);

// The matrix that carries ENU points along the unit `light` (ENU, towards it) onto the plane
// `base_m` high and maps that plane's square (west, north edges, side extent_m) to [0, 1]^2,
// row 0 north (x, y); z the point's height above the plane.
glm::mat4 shadow_map_matrix(const glm::vec3& light, float base_m, const glm::vec2& west_north_m,
                            float extent_m);

// What is wrong with `options` (one line naming the field, its value and what is allowed), or
// empty.
std::string host_lighting_problem(const HostLightingOptions& options);

class HostLightingModule : public RenderModule {
 public:
  HostLightingModule(gpu::Context& ctx, gpu::DescriptorSet& set);
  void add_passes(FrameGraph& graph, const FrameSetup& frame) override;

  // When `options` (valid: host_lighting_problem) are enabled: sizes the shadow map and the
  // environment, binds the slot's buffer and fills params.host_shadow_*. False when not enabled.
  bool prepare(const HostLightingOptions& options, const Scene& scene, const SkyLights& lights,
               int slot, gpu::FrameParams& params);
  // The contract's (render_module.h): the above with the frame's values.
  void prepare(const FramePrepare& frame, FramePlan& plan) override;
  // The two passes; after the light volume, the sky view and the ground light.
  void record(VkCommandBuffer cmd, gpu::PassTimer& timer);
  // The lighting of the frame recorded in `slot`, once it completed; empty when that frame did
  // not ask for it.
  std::optional<HostLighting> collect(int slot);

  const gpu::Texture& shadow_map() const { return shadow_map_; }
  const gpu::Texture& environment() const { return environment_; }
  const glm::mat4& world_to_shadow_map() const { return world_to_map_; }

 private:
  gpu::Context& ctx_;
  gpu::DescriptorSet& set_;
  gpu::Buffer buffers_[gpu::kFramesInFlight];
  gpu::Texture shadow_map_, environment_;
  glm::mat4 world_to_map_{1.0f};
  uint32_t map_size_ = 0, environment_size_ = 0;
  struct Pending {
    Scene scene;
    SkyLights lights;
  };
  std::optional<Pending> pending_[gpu::kFramesInFlight];
  std::unique_ptr<gpu::Kernel> lighting_kernel_, map_kernel_,
      environment_kernel_;  // made when first recorded
};

}  // namespace nephele
