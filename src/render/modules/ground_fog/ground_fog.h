// The ground fog module (docs/ground-fog.md): a slab of fog above the ground, the "ground fog"
// layer of simulator image generators, drawn as a medium between the eye and every layer of
// compose.comp (ground_fog_medium.glsl). It owns its parameters (Scene::ground_fog), its
// uniform block (descriptor set 1, "GroundFogBlock") and no pass: compose reads the block.
#pragma once

#include "gpu/kernel.h"
#include "nephele/scene.h"
#include "render/render_module.h"

namespace nephele {

class GroundFogModule : public RenderModule {
 public:
  GroundFogModule(gpu::Context& ctx, gpu::DescriptorSet& set);
  // This frame's fog, from the scene and the frame's parameters (the sun, the sky's light),
  // into the uniform block of frame slot `slot`, bound for the frame; true when there is fog.
  bool prepare(const Scene& scene, const gpu::FrameParams& params, int slot);
  void add_passes(FrameGraph& graph, const FrameSetup& frame) override;

 private:
  gpu::DescriptorSet& set_;
  gpu::Buffer blocks_[gpu::kFramesInFlight + 1];  // one a slot: a frame in flight reads its own
};

}  // namespace nephele
