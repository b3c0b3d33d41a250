// The cloud diffusion module (docs/cloud-lighting.md): the clouds' multiple-scattered light
// solved on a regular grid in cloud space around the camera, as the diffusion (P1) equation
// with the sun's beam as its source, for `clouds.lighting = "diffusion"`. Three passes:
// the medium of each cell (diffusion_fill.comp), red-black sweeps of the solve
// (diffusion_solve.comp) and the field the march reads (diffusion_field.comp,
// cloud_diffusion_inc.glsl). Rebuilt with the light volume, whose optical depths towards the
// sun give the source: when a light volume is completed. The frame knows it only through the
// registry (render_module.h).
#pragma once

#include <memory>

#include "gpu/kernel.h"
#include "gpu/kernel_variants.h"
#include "nephele/scene.h"
#include "render/render_module.h"

namespace nephele {

// The solve's red-black sweeps for a grid built from zero.
constexpr int kDiffusionSweeps = 64;

class CloudDiffusionModule : public RenderModule {
 public:
  explicit CloudDiffusionModule(const ModuleContext& context);
  // Whether this frame rebuilds the field (the clouds' lighting is "diffusion" and the light
  // volume was completed, or none has been built for it), and the block the march reads.
  void prepare(const FramePrepare& frame, FramePlan& plan) override;
  void add_passes(FrameGraph& graph, const FrameSetup& frame) override;

 private:
  void record(VkCommandBuffer cmd, gpu::PassTimer& timer);

  gpu::DescriptorSet& set_;
  gpu::KernelVariants fill_;  // with or without the voxel clouds, the flow map
  gpu::Kernel solve_, gather_;
  gpu::Texture medium_, phi_, field_;
  gpu::Buffer blocks_[gpu::kFramesInFlight + 1];  // one a slot: a frame in flight reads its own
  bool built_ = false;    // the field holds a solve for the clouds' current light volume
  bool rebuild_ = false;  // this frame's
  bool with_voxels_ = false, with_flow_ = false;
};

std::unique_ptr<RenderModule> make_cloud_diffusion_module(const ModuleContext& context);

}  // namespace nephele
