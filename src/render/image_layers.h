// nephele — the image layers compose blends over the clouds: one 2D array image at the frame's
// size, a layer (LAYER_*, shaders/common/params_inc.glsl) each for the surfaces (the terrain,
// the host's geometry) and the particle clouds, so that compose and the passes that read a
// layer see one binding however many layers there are (shaders/layers_inc.glsl). The modules
// that draw a layer write theirs: compute passes through layers_out, raster passes into a
// layer's render target.
#pragma once

#include "gpu/kernel.h"
#include "gpu/resources.h"

namespace nephele {

class ImageLayers {
 public:
  static constexpr VkFormat kFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
  // 1 x 1 layers, zero, until a frame draws one.
  ImageLayers(gpu::Context& ctx, gpu::DescriptorSet& set);

  // Sizes the layers for a width x height frame (waits for the frames in flight when it
  // remakes them: they may read the old ones); made anew, every layer is zero.
  void require(int width, int height);
  const gpu::Texture& texture() const { return texture_; }
  // The top-left width x height texels of `layer`, a raster pass's target.
  gpu::RenderTarget target(int layer, int width, int height) const;

 private:
  void make(int width, int height);
  gpu::Context& ctx_;
  gpu::DescriptorSet& set_;
  gpu::Texture texture_;
};

}  // namespace nephele
