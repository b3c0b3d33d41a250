// The voxel clouds module (seed 002, 体素云建模): loads or generates the scene's voxel clouds,
// stores them sparsely on the device (voxel/bricks.h: the bricks near their surfaces in one
// atlas, a page table per cloud) and places them in each frame's parameters. The clouds pass
// samples them with the noise clouds (shaders/voxel_field_inc.glsl).
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "gpu/kernel.h"
#include "nephele/renderer.h"
#include "nephele/scene.h"
#include "render/gpu_params.h"
#include "render/render_module.h"
#include "voxel/voxel_grid.h"

namespace nephele {

class VoxelCloudsModule : public RenderModule {
 public:
  VoxelCloudsModule(gpu::Context& ctx, gpu::DescriptorSet& set);
  void add_passes(FrameGraph& graph, const FrameSetup& frame) override;

  // Loads and uploads the scene's clouds when their sources change (a one-off wait for the
  // device; a grid once loaded is kept for later scenes), fills params.voxel_* with their
  // places at the scene's time and widens the cloud shell (params.radii_m.zw) to hold them.
  void prepare(const Scene& scene, gpu::FrameParams& params);
  // The contract's (render_module.h): the above with the frame's values.
  void prepare(const FramePrepare& frame, FramePlan& plan) override;

  const std::vector<VoxelCloudMemory>& memory() const { return memory_; }

  // A cloud's grid, loaded (or generated) once and kept.
  const voxel::VoxelGrid& grid(const VoxelCloudParams& cloud);
  size_t device_bytes() const { return device_bytes_; }

  // The source key of a scene's cloud: its file, or "preset:NAME:SEED", and the resolution.
  static std::string source_of(const VoxelCloudParams& cloud);

 private:
  void upload(const std::vector<const voxel::VoxelGrid*>& grids);

  gpu::Context& ctx_;
  gpu::DescriptorSet& set_;
  gpu::Texture atlas_;
  gpu::Texture pages_;
  std::map<std::string, std::unique_ptr<voxel::VoxelGrid>> grids_;  // by source_of
  std::vector<std::string> uploaded_;  // the sources in the atlas, in the scene's order
  std::vector<glm::ivec4> bricks_;     // per cloud: page table size, first layer
  std::vector<VoxelCloudMemory> memory_;
  size_t device_bytes_ = 0;
};

}  // namespace nephele
