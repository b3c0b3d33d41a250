#include "render/image_layers.h"

#include <string>

#include "nephele/error.h"
#include "render/gpu_params.h"

namespace nephele {

ImageLayers::ImageLayers(gpu::Context& ctx, gpu::DescriptorSet& set) : ctx_(ctx), set_(set) {
  make(1, 1);
}

void ImageLayers::make(int width, int height) {
  texture_ = gpu::Texture(ctx_, uint32_t(width), uint32_t(height),
                          gpu::ArrayLayers{uint32_t(gpu::IMAGE_LAYERS)}, kFormat, true);
  ctx_.submit_and_wait([&](VkCommandBuffer cmd) { texture_.record_clear(cmd); });
  set_.bind_image(gpu::kLayersOut, gpu::kLayers, texture_);
}

void ImageLayers::require(int width, int height) {
  if (texture_.width() == uint32_t(width) && texture_.height() == uint32_t(height)) return;
  ctx_.wait_queue_idle();  // a frame in flight may still read the old ones
  make(width, height);
}

gpu::RenderTarget ImageLayers::target(int layer, int width, int height) const {
  if (uint32_t(width) > texture_.width() || uint32_t(height) > texture_.height())
    throw RuntimeError("ImageLayers::target: " + std::to_string(width) + " x " +
                       std::to_string(height) + " texels of layers of " +
                       std::to_string(texture_.width()) + " x " +
                       std::to_string(texture_.height()));
  gpu::RenderTarget t = texture_.render_target(uint32_t(layer));
  t.width = uint32_t(width);
  t.height = uint32_t(height);
  return t;
}

}  // namespace nephele
