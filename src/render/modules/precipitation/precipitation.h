// The precipitation module (docs/precipitation.md): rain, drizzle, snow and sleet falling from
// the low cloud layer, seen as shafts under the precipitating clouds or an even curtain, a
// medium between the eye and every layer of compose.comp and of the stars
// (precipitation_medium.glsl) that lowers the visibility by the rate. It owns its parameters
// (Scene::precipitation), its uniform block (descriptor set 1, "PrecipitationBlock"), a pass
// (precipitation.comp) that marches it along the view's rays into froxels at an eighth of the
// image's resolution, which compose and the stars read ("media"), and a raster pass that draws
// the particles near the camera into an image layer (precipitation_particles.vert), which the
// medium puts in front. The frame knows it only through the registry (render_module.h).
#pragma once

#include <memory>
#include <string_view>

#include "gpu/kernel.h"
#include "gpu/raster.h"
#include "nephele/scene.h"
#include "render/render_module.h"

namespace nephele {

// PRECIPITATION_RAIN ... of common/precipitation_inc.glsl for precipitation.kind's name; -1
// for anything else.
int precipitation_kind(std::string_view name);
// The precipitation's extinction (1/m) under a shaft, and the visibility it leaves (m,
// Koschmieder: 3.912 / sigma_t; infinite without it).
float precipitation_sigma_t_per_m(const PrecipitationParams& p);
float precipitation_visibility_m(const PrecipitationParams& p);

// The froxels' texels per image pixel along each axis: one per 8 x 8 block.
constexpr int kPrecipitationDownsample = 8;

class PrecipitationModule : public RenderModule {
 public:
  explicit PrecipitationModule(const ModuleContext& context);
  // This frame's precipitation (its fall from the clouds' base, extinction and light) into the
  // uniform block of the frame's slot, bound for the frame, and the froxels sized for the
  // image; plan.media when it falls.
  void prepare(const FramePrepare& frame, FramePlan& plan) override;
  // The froxels' pass ("precipitation", writing "media") when it falls, and the particles'
  // raster pass ("precipitation_particles", into the image layers) when the camera is in it.
  void add_passes(FrameGraph& graph, const FrameSetup& frame) override;

 private:
  void bind_froxels();

  gpu::Context& ctx_;
  gpu::DescriptorSet& set_;
  ImageLayers& layers_;
  gpu::Buffer blocks_[gpu::kFramesInFlight + 1];  // one a slot: a frame in flight reads its own
  gpu::Texture froxels_, depth_;         // (light, transmittance) and summed depth by sample
  std::unique_ptr<gpu::Kernel> kernel_;  // made when first recorded
  std::unique_ptr<gpu::RasterPass> particles_;  // the particles near the camera
  gpu::DrawConstants camera_{};
  bool falls_ = false;
  bool near_ =
      false;  // the camera is in it: its particles are drawn (precipitation_particles.vert)
};

std::unique_ptr<RenderModule> make_precipitation_module(const ModuleContext& context);

}  // namespace nephele
