// The host's own geometry in the frame (nephele::HostScene, frame.h): its depth and colour
// copied into a buffer each frame, and host_scene.comp, which turns the depth into distances
// and merges the nearer of it and the terrain into the terrain's output, where every pass that
// knows the terrain (the clouds' march, compose's fog and occlusion, the stars, the shafts)
// treats it alike.
#pragma once

#include <memory>
#include <string>

#include "gpu/kernel.h"
#include "nephele/frame.h"
#include "render/gpu_params.h"
#include "render/render_module.h"

namespace nephele {

// What is wrong with `host` for `scene` (one line naming the field, its value and what is
// allowed), or empty when it is usable.
std::string host_scene_problem(const HostScene& host, const Scene& scene);

class HostSceneModule : public RenderModule {
 public:
  HostSceneModule(gpu::Context& ctx, gpu::DescriptorSet& set);
  void add_passes(FrameGraph& graph, const FrameSetup& frame) override;

  // Sizes the texel buffer for `host` (valid: host_scene_problem) and fills params.host_*;
  // false without a host scene (params.host_scene.x stays 0).
  bool prepare(const HostScene* host, gpu::FrameParams& params);
  // The contract's (render_module.h): the above with the frame's values.
  void prepare(const FramePrepare& frame, FramePlan& plan) override;
  // The copies of the host's images and host_scene.comp; after the terrain's pass.
  void record(VkCommandBuffer cmd, gpu::PassTimer& timer);

 private:
  gpu::Context& ctx_;
  gpu::DescriptorSet& set_;
  gpu::Buffer texels_;
  std::unique_ptr<gpu::Kernel> kernel_;  // made when first recorded
  HostScene host_{};
  VkDeviceSize color_offset_ = 0;
};

}  // namespace nephele
