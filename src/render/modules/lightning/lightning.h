// The lightning module (docs/lightning.md): flashes in the low layer's cumulonimbus cells at
// Scene::lightning's rate, in-cloud flashes and strokes to the ground with their bolts, the same
// for the same seed and time. It owns its parameters, its uniform block (set 1
// "LightningBlock"), the flashes' buffer (set 1 "LightningFlashes", one a frame slot) and one
// pass (lightning.comp) that finds the frame's flashes; compose draws their light as one of its
// translucent layers (lightning_layer.glsl), and the rain near the camera is lit by them. The
// frame knows it only through the registry (render_module.h).
#pragma once

#include <memory>

#include "gpu/kernel.h"
#include "nephele/scene.h"
#include "render/modules/lightning/lightning_gpu_inc.glsl"
#include "render/render_module.h"

namespace nephele {

// A tile of the ground whose candidate places flash (m), and a storm cell's core that they may
// fall in (m^2: a disc of 3 km).
constexpr float kLightningTileM = 20000.0f;
constexpr float kLightningCoreM2 = 3.14159265f * 3000.0f * 3000.0f;

// The frame's block: the slot and the time in it (in double: the scene's time may be 1e6 s),
// the tile under the camera, the chance a candidate flashes and the cloud layer's base and top.
// when.w = 0 when nothing flashes (no rate, or no cumulonimbus: clouds.precipitation 0).
gpu::LightningGpu lightning_block(const Scene& scene);

class LightningModule : public RenderModule {
 public:
  explicit LightningModule(const ModuleContext& context);
  // The block of the frame's slot and its flashes' buffer, bound; plan.layers when it flashes.
  void prepare(const FramePrepare& frame, FramePlan& plan) override;
  // The flashes' pass ("lightning", before compose's layers) when it flashes.
  void add_passes(FrameGraph& graph, const FrameSetup& frame) override;

 private:
  gpu::Context& ctx_;
  gpu::DescriptorSet& set_;
  gpu::Buffer blocks_[gpu::kFramesInFlight + 1];  // one a slot: a frame in flight reads its own
  gpu::Buffer flashes_[gpu::kFramesInFlight + 1];
  std::unique_ptr<gpu::Kernel> kernel_;  // made when first recorded
  bool on_ = false;
};

std::unique_ptr<RenderModule> make_lightning_module(const ModuleContext& context);

}  // namespace nephele
