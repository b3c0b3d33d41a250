// The particle clouds module (seed 003, 3.3.2-3.3.4; issue 22): keeps the scene's particle
// field (particles/particle_field.h), lights it on the CPU (particles/particle_lighting.h,
// spread over frames), sorts its particles back to front each frame and draws them as
// camera-facing quads in a raster pass (particles.vert, particles.frag) into a layer that
// compose.comp puts in depth order with the sky and the volumetric clouds; far clouds as
// impostors (impostors.h).
#pragma once

#include <glm/vec3.hpp>
#include <memory>
#include <optional>
#include <string>

#include "gpu/kernel.h"
#include "gpu/raster.h"
#include "nephele/renderer.h"
#include "nephele/scene.h"
#include "particles/particle_field.h"
#include "render/gpu_params.h"
#include "render/image_layers.h"
#include "render/modules/impostors/impostors.h"
#include "render/render_module.h"

namespace nephele {

// Particles a frame of an animation relights at most (a still relights every cloud at once).
constexpr size_t kParticleRelightBudget = 60000;

struct ParticleFrameStats {
  size_t particles = 0;  // drawn one by one (not in impostors)
  size_t field_particles = 0;
  int clouds = 0;
  int relit_clouds = 0;                                        // this frame
  double generate_ms = 0.0, lighting_ms = 0.0, sort_ms = 0.0;  // CPU
};

class ParticleCloudsModule : public RenderModule {
 public:
  ParticleCloudsModule(gpu::Context& ctx, gpu::DescriptorSet& set, ImageLayers& layers);
  void add_passes(FrameGraph& graph, const FrameSetup& frame) override;
  ~ParticleCloudsModule();

  // Before the frame's GpuState::begin: (re)generates the field when its parameters or, for an
  // evolving sky, the time step changed; relights the clouds whose light moved (all of them
  // for a still, else within kParticleRelightBudget); writes the particles back to front from
  // the camera into the buffer of frame slot `slot`; sizes the image layers to the image;
  // fills params.particle_shading and particle_light. Throws InputError when the scene has particle
  // clouds and the device's queue cannot draw.
  void prepare(const Scene& scene, int slot, int width, int height, bool still,
               gpu::FrameParams& params);
  // The contract's (render_module.h): the above with the frame's values.
  void prepare(const FramePrepare& frame, FramePlan& plan) override;
  // Draws the particles prepared (or only clears the layers: none, or no particle clouds).
  void record(VkCommandBuffer cmd, gpu::PassTimer& timer);
  // Whether this frame draws particles (prepare decided; else the layer is clear).
  bool active() const { return active_; }

  const ParticleFrameStats& stats() const { return stats_; }
  const particles::ParticleField& field() const { return field_; }
  const ImpostorFrameStats& impostor_stats() const { return impostors_.stats(); }
  // Both, as FrameStats reports them.
  ParticleCloudStats frame_stats() const;

 private:
  gpu::Context& ctx_;
  gpu::DescriptorSet& set_;
  std::unique_ptr<gpu::RasterPass> pass_;  // made when first needed
  gpu::Texture textures_;
  // The image layers they are drawn into (LAYER_PARTICLES, LAYER_PARTICLE_DEPTH), the
  // top-left layer_width_ x layer_height_ of them.
  ImageLayers& layers_;
  int layer_width_ = 1, layer_height_ = 1;
  gpu::Buffer buffers_[gpu::kFramesInFlight];
  particles::ParticleField field_;
  std::optional<particles::FieldShape> field_shape_;  // field_'s
  float field_time_s_ = 0.0f;                         // the time the field was generated for
  bool active_ = false;                               // this frame draws
  bool drawn_ = false;  // the layers hold particles (cleared when none are drawn)
  uint32_t near_first_ = 0, near_count_ = 0;  // the particles drawn one by one this frame
  gpu::DrawConstants camera_{};               // the frame's camera
  ImpostorCache impostors_;
  ParticleFrameStats stats_;
};

}  // namespace nephele
