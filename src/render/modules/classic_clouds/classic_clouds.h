// The classical cloud models of seed 004 (issue 23): drawn in place of nephele's march when
// clouds.model names one, by classic_clouds.comp into this frame's cloud buffer (as the
// temporal resolve writes it), so that compose.comp puts them in the sky unchanged. Their
// formulas are common/classic_inc.glsl's. Each model's pipeline is made when first drawn:
// scenes that never use one do not pay for its compilation (time, and on a CPU device memory).
#pragma once

#include <map>
#include <memory>

#include "gpu/kernel.h"
#include "nephele/scene.h"
#include "render/gpu_params.h"
#include "render/modules/metaball_clouds/metaball_clouds.h"
#include "render/render_module.h"

namespace nephele {

class ClassicCloudsModule : public RenderModule {
 public:
  ClassicCloudsModule(gpu::Context& ctx, gpu::DescriptorSet& set);
  void add_passes(FrameGraph& graph, const FrameSetup& frame) override;
  ~ClassicCloudsModule();

  // Fills params.classic_*: the scene's [classic] values in the shader's terms (and, when the
  // scene draws Nishita's metaballs, makes them).
  void prepare(const Scene& scene, gpu::FrameParams& params);
  // The contract's (render_module.h): the above with the frame's values.
  void prepare(const FramePrepare& frame, FramePlan& plan) override;
  // One thread per pixel of the width x height cloud buffer bound as clouds_a_out / _b_out.
  void record(VkCommandBuffer cmd, gpu::PassTimer& timer, CloudModel model, int width, int height);

 private:
  gpu::Context& ctx_;
  gpu::DescriptorSet& set_;
  std::map<CloudModel, std::unique_ptr<gpu::Kernel>> kernels_;
  MetaballCloudsModule metaballs_;
};

// Blinn's phase function's kind (classic_inc.glsl's BLINN_PHASE_*) for [classic] blinn_phase.
int blinn_phase_kind(const std::string& name);

}  // namespace nephele
