// The reference path tracer module (issue 21): the accumulation images and the kernel of
// path_trace.comp. FrameRenderer::Impl::render_reference (src/render/reference.cpp) drives it.
#pragma once

#include "gpu/kernel.h"

namespace nephele {

class PathTracerModule {
 public:
  PathTracerModule(gpu::Context& ctx, gpu::DescriptorSet& set);

  // Sizes the accumulation images to width x height and binds them (before the work that
  // uses them starts recording), then clear() records setting them to zero.
  void resize(int width, int height);
  void clear(VkCommandBuffer cmd) const;
  // Adds FrameParams::path_info.y samples to every pixel.
  void record(VkCommandBuffer cmd, gpu::PassTimer& timer) const;

  const gpu::Texture& sum() const { return sum_; }
  const gpu::Texture& squares() const { return squares_; }

 private:
  gpu::Context& ctx_;
  gpu::DescriptorSet& set_;
  gpu::Kernel kernel_;
  gpu::Texture sum_, squares_;
};

}  // namespace nephele
