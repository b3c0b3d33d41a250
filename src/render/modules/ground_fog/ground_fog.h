// The ground fog module (docs/ground-fog.md): a slab of fog above the ground, the "ground fog"
// layer of simulator image generators, drawn as a medium between the eye and every layer of
// compose.comp and of the stars (ground_fog_medium.glsl). It also draws the time-of-day
// keyframes' fog (seed 003: a colour mixed in linearly from a near to a far distance), the
// same medium on the same surfaces. It owns its parameters (Scene::ground_fog), its uniform
// block (descriptor set 1, "GroundFogBlock") and no pass: compose and the stars read the block.
// The frame knows it only through the registry (render_module.h).
#pragma once

#include <memory>

#include "gpu/kernel.h"
#include "nephele/scene.h"
#include "render/render_module.h"

namespace nephele {

class GroundFogModule : public RenderModule {
 public:
  explicit GroundFogModule(const ModuleContext& context);
  // This frame's fog, from the scene and the frame's parameters (the sun, the sky's light, the
  // keyframes' fog), into the uniform block of the frame's slot, bound for the frame;
  // plan.media when there is fog of either kind.
  void prepare(const FramePrepare& frame, FramePlan& plan) override;
  void add_passes(FrameGraph& graph, const FrameSetup& frame) override;

 private:
  gpu::DescriptorSet& set_;
  gpu::Buffer blocks_[gpu::kFramesInFlight + 1];  // one a slot: a frame in flight reads its own
};

std::unique_ptr<RenderModule> make_ground_fog_module(const ModuleContext& context);

}  // namespace nephele
