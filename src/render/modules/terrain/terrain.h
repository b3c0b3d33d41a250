// The terrain under the clouds (issue 24): the scene's heightfield (terrain/heightfield.h) on
// the device with its pyramid of maxima, and terrain.comp, which casts every view ray against it
// before the clouds are marched (they stop at it) and lights what it hits; compose puts the
// air in front of it and hides the sky behind it.
//
// Ray casting in compute by default; terrain.method = "raster" draws the heightfield as a mesh
// with depth instead (terrain.vert/.frag: seed 002's way) and lights the distances it leaves
// (docs/terrain.md: the two measured).
#pragma once

#include <memory>
#include <string>

#include "gpu/kernel.h"
#include "gpu/raster.h"
#include "nephele/scene.h"
#include "render/gpu_params.h"
#include "render/image_layers.h"
#include "render/render_module.h"

namespace nephele {

class TerrainModule : public RenderModule {
 public:
  TerrainModule(gpu::Context& ctx, gpu::DescriptorSet& set, ImageLayers& layers);
  void add_passes(FrameGraph& graph, const FrameSetup& frame) override;

  // Loads the scene's terrain when it changed (InputError for bad input), sizes the image
  // layers for a width x height frame (also without terrain when `host_scene`: the host's
  // geometry goes into the same layer, LAYER_SURFACES) and fills params.terrain_*; false when the
  // scene has none (then params.terrain_shape.z stays 0).
  bool prepare(const Scene& scene, int width, int height, bool host_scene,
               gpu::FrameParams& params);
  // The contract's (render_module.h): the above with the frame's values.
  void prepare(const FramePrepare& frame, FramePlan& plan) override;
  void record(VkCommandBuffer cmd, gpu::PassTimer& timer);

 private:
  gpu::Context& ctx_;
  gpu::DescriptorSet& set_;
  gpu::Texture heights_;     // and below them terrain::MaxPyramid's levels
  gpu::Texture albedo_;      // terrain.albedo_map, linear
  std::string albedo_path_;  // the map albedo_ holds
  ImageLayers& layers_;      // terrain.comp's result goes into LAYER_SURFACES
  int width_ = 0, height_ = 0;  // the frame's
  // The raster method's: the mesh pass (its distances into LAYER_SURFACES) and depth,
  // terrain.comp reading them.
  std::unique_ptr<gpu::RasterPass> raster_;
  gpu::DepthTarget depth_;
  std::unique_ptr<gpu::Kernel> raster_kernel_;
  bool raster_frame_ = false;            // this frame draws the mesh
  std::unique_ptr<gpu::Kernel> kernel_;  // made when first recorded
  std::string key_;                      // what the heights were made from
  glm::vec4 rect_{0.0f}, shape_{0.0f};
  glm::ivec4 grid_{0};
};

}  // namespace nephele
