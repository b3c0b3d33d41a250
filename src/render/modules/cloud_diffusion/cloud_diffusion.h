// The cloud diffusion module (docs/cloud-lighting.md): the clouds' multiple-scattered light
// solved on regular grids in cloud space around the camera (two cascades: 70 m cells to 4.5 km,
// 280 m cells to 18 km), as the diffusion equation with similarity scaling and the sun's
// reduced beam as its source, for `clouds.lighting = "diffusion"`. Its passes:
// the medium of each cell (diffusion_fill.comp), a deck's open base (diffusion_column.comp) and
// the cells of clear air next to cloud (diffusion_boundary.comp), red-black sweeps of the solve
// (diffusion_solve.comp), between them the light clear air carries from cloud to cloud
// (diffusion_exchange.comp, diffusion_inflow.comp), and the field the march reads
// (diffusion_field.comp, cloud_diffusion_inc.glsl). Rebuilt with the light volume, whose optical
// depths towards the sun give the source: when a light volume is completed. As the light volume is,
// a still (or the first frame) builds it at once, an animation over frames into a second field
// while the clouds read the last one completed: the medium a band of rows a frame, then a sweep and
// a band of the gather a frame. The frame knows it only through the registry (render_module.h).
#pragma once

#include <filesystem>
#include <glm/vec4.hpp>
#include <memory>

#include "gpu/kernel.h"
#include "gpu/kernel_variants.h"
#include "nephele/scene.h"
#include "render/render_module.h"
// DIFFUSION_CASCADES, CloudDiffusionGpu
#include "render/gpu_params.h"
#include "render/modules/cloud_diffusion/cloud_diffusion_gpu_inc.glsl"

namespace nephele {

// The solve's red-black sweeps for a build built at once (a still, an animation's first
// field), from a zero start, and the gather of the light clear air carries between clouds
// (diffusion_exchange.comp) every kDiffusionExchangeSweeps of them and once before the field.
// The gathers, not the sweeps, limit the convergence: the lab's split deck
// (ReferenceTest.TheDiffusionLightCrossesAGapInADeck) takes its light across the gap once a
// gather (stop 59: 96 and 64 sweeps gathered every 16 left it at 0.90 and 0.79 of the tracer,
// against 0.95 at 128). Stop 63, at 40 x 25: 64 sweeps gathered every 8 (eight gathers, as 128
// every 16) give the suite's views within 0.6% of 128 (sum 100.4 points against 101) for 1.2 s
// less a still on lavapipe; 32 every 4 leave the overcast deck unconverged (7 points darker).
constexpr int kDiffusionSweeps = 64;
constexpr int kDiffusionExchangeSweeps = 8;
// An animation's build, a part a frame from the last build's fluence: the medium over
// kDiffusionFillFrames frames, then kDiffusionFrameSweeps sweeps a frame of
// kDiffusionAnimationSweeps, with a band of the gather each (one completed every
// kDiffusionAnimationExchangeSweeps sweeps: a frame's share of a gather is what a sweep costs;
// on lavapipe 9 and 8 ms a frame; a build takes 192 frames, the light volume's 256).
constexpr int kDiffusionFillFrames = 64;
constexpr int kDiffusionFrameSweeps = 1;
constexpr int kDiffusionAnimationSweeps = 128;
constexpr int kDiffusionAnimationExchangeSweeps = 16;
// After an edit of the clouds (the light volume rebuilt over kLightVolumeEditFrames), the
// medium over this many frames and the sweeps over as many, so that the lighting follows the
// edit within 48 frames rather than 208 (on lavapipe about 50 and 230 ms a frame).
constexpr int kDiffusionEditFrames = 16;

class CloudDiffusionModule : public RenderModule {
 public:
  explicit CloudDiffusionModule(const ModuleContext& context);
  // Whether this frame rebuilds the field (the clouds' lighting is "diffusion" and the light
  // volume was completed, or none has been built for it), and the block the march reads.
  void prepare(const FramePrepare& frame, FramePlan& plan) override;
  void add_passes(FrameGraph& graph, const FrameSetup& frame) override;
  // A still's field built in `slot` is written to the disk cache (FramePlan::lighting_cache_key).
  void finished(int slot) override;

 private:
  void record(VkCommandBuffer cmd, gpu::PassTimer& timer);

  gpu::Context& ctx_;
  gpu::DescriptorSet& set_;
  gpu::KernelVariants fill_;  // with or without the voxel clouds, the flow map
  // Reading the gather's set 0 or set 1 (EXCHANGE_READ_SET).
  gpu::KernelVariants exchange_kernel_, inflow_kernel_, gather_kernel_;
  gpu::Kernel solve_, column_kernel_, boundary_kernel_;
  gpu::Texture medium_, phi_;
  gpu::Texture inflow_;  // per cell of cloud, the light clear air brings in (diffusion_inflow.comp)
  // Per row, its cells the gather casts rays from (diffusion_boundary.comp).
  gpu::Texture boundary_;
  // The clear air's gathered light (diffusion_exchange_inc.glsl): two sets, one read and one
  // written.
  gpu::Texture exchange_[2];
  int exchange_read_ = 0, sweeps_since_exchange_ = 0, exchange_row_ = 0;
  bool at_once_ = true;     // this frame builds the whole field
  gpu::Texture fields_[2];  // the one read, fields_[read_], and the one built
  int read_ = 0;
  gpu::Buffer blocks_[gpu::kFramesInFlight + 1];  // one a slot: a frame in flight reads its own
  bool have_field_ = false;                       // fields_[read_] holds a solve
  // Per cascade: the grids read and built, the built one's cells (CloudDiffusionGpu).
  glm::vec4 read_grid_[gpu::DIFFUSION_CASCADES]{}, build_grid_[gpu::DIFFUSION_CASCADES]{};
  glm::vec4 cell_[gpu::DIFFUSION_CASCADES]{};
  // The build in progress: the medium's next row (kRows when filled), the sweeps left.
  bool building_ = false;
  bool edit_ = false;  // the build follows an edit (kDiffusionEditFrames)
  int next_row_ = 0, sweeps_left_ = 0;
  bool zero_phi_ = true;
  bool phi_kept_ = true;  // phi_ holds the fluence of the field read (not one from the disk cache)
  // A still's field to keep in the disk cache once the frame in store_slot_ has finished.
  std::filesystem::path store_file_;
  int store_slot_ = -1, store_field_ = 0;
  // This frame's work.
  int fill_first_ = 0, fill_rows_ = 0, sweeps_ = 0;
  bool gather_ = false;
  bool with_voxels_ = false, with_flow_ = false;
};

std::unique_ptr<RenderModule> make_cloud_diffusion_module(const ModuleContext& context);

}  // namespace nephele
