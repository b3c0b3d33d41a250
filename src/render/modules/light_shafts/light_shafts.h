// Volumetric light shafts (quality.light_shafts = "volumetric"): the air's single scattering
// lost to the clouds' shadows, marched at an eighth of the image's resolution per axis
// (light_shafts.comp, light_shafts_inc.glsl) after the clouds and read by compose.
#pragma once

#include <memory>

#include "gpu/kernel.h"
#include "nephele/scene.h"
#include "render/gpu_params.h"
#include "render/render_module.h"

namespace nephele {

constexpr int kLightShaftsDownsample = 8;

class LightShaftsModule : public RenderModule {
 public:
  LightShaftsModule(gpu::Context& ctx, gpu::DescriptorSet& set);
  void add_passes(FrameGraph& graph, const FrameSetup& frame) override;

  // Sizes the shafts' image for a width x height frame; false when the scene has none.
  bool prepare(const Scene& scene, int width, int height);
  // The contract's (render_module.h): the above with the frame's values.
  void prepare(const FramePrepare& frame, FramePlan& plan) override;
  void record(VkCommandBuffer cmd, gpu::PassTimer& timer);

 private:
  gpu::Context& ctx_;
  gpu::DescriptorSet& set_;
  gpu::Texture shafts_;
  std::unique_ptr<gpu::Kernel> kernel_;  // made when first recorded
};

}  // namespace nephele
