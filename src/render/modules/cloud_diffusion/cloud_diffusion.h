// The cloud diffusion module (docs/cloud-lighting.md): the clouds' multiple-scattered light
// solved on a regular grid in cloud space around the camera, as the diffusion (P1) equation
// with the sun's beam as its source, for `clouds.lighting = "diffusion"`. Three passes:
// the medium of each cell (diffusion_fill.comp), red-black sweeps of the solve
// (diffusion_solve.comp) and the field the march reads (diffusion_field.comp,
// cloud_diffusion_inc.glsl). Rebuilt with the light volume, whose optical depths towards the
// sun give the source: when a light volume is completed. As the light volume is, a still (or the
// first frame) builds it at once, an animation over frames into a second field while the clouds
// read the last one completed: the medium a band of rows a frame, then a few sweeps a frame. The
// frame knows it only through the registry (render_module.h).
#pragma once

#include <glm/vec4.hpp>
#include <memory>

#include "gpu/kernel.h"
#include "gpu/kernel_variants.h"
#include "nephele/scene.h"
#include "render/render_module.h"

namespace nephele {

// The solve's red-black sweeps for a build (converged to about 2% on the suite's decks from a
// zero start; an animation's build starts from the last one's fluence where the grid has not
// moved).
constexpr int kDiffusionSweeps = 128;
// An animation's build: the medium over kDiffusionFillFrames frames, then kDiffusionFrameSweeps
// sweeps a frame.
constexpr int kDiffusionFillFrames = 32;
constexpr int kDiffusionFrameSweeps = 2;

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
  gpu::Kernel solve_, gather_kernel_;
  gpu::Texture medium_, phi_;
  gpu::Texture fields_[2];  // the one read, fields_[read_], and the one built
  int read_ = 0;
  gpu::Buffer blocks_[gpu::kFramesInFlight + 1];  // one a slot: a frame in flight reads its own
  bool have_field_ = false;                       // fields_[read_] holds a solve
  glm::vec4 read_grid_{0.0f}, build_grid_{0.0f}, cell_{0.0f};
  // The build in progress: the medium's next row (kRows when filled), the sweeps left.
  bool building_ = false;
  int next_row_ = 0, sweeps_left_ = 0;
  bool zero_phi_ = true;
  // This frame's work.
  int fill_first_ = 0, fill_rows_ = 0, sweeps_ = 0;
  bool gather_ = false;
  bool with_voxels_ = false, with_flow_ = false;
};

std::unique_ptr<RenderModule> make_cloud_diffusion_module(const ModuleContext& context);

}  // namespace nephele
