// The reference path tracer module (issue 21): the accumulation images and the kernel of
// path_trace.comp. FrameRenderer::Impl::render_reference (src/render/reference.cpp) drives it.
#pragma once

#include <memory>
#include <vector>

#include "gpu/kernel.h"
#include "nephele/scene.h"
#include "render/render_module.h"

namespace nephele {

class PathTracerModule : public RenderModule {
 public:
  PathTracerModule(gpu::Context& ctx, gpu::DescriptorSet& set);

  // Sizes the accumulation images to width x height and binds them (before the work that
  // uses them starts recording), then clear() records setting them to zero.
  void resize(int width, int height);
  void clear(VkCommandBuffer cmd) const;
  // Adds FrameParams::path_info.y samples to every pixel: of the lab (`planet` false), or of
  // the planet's scene with the noise clouds' field of `mode`.
  // Adds `samples` samples to every pixel, the first numbered `first_sample`: of the lab
  // (`planet` false), or of the planet's scene with the noise clouds' field of `mode`.
  void record(VkCommandBuffer cmd, gpu::PassTimer& timer, bool planet, MarchMode mode,
              int first_sample, int samples) const;
  // The samples the next path_trace pass of the graph adds (record's).
  void set_samples(int first_sample, int samples) {
    first_sample_ = first_sample;
    samples_ = samples;
  }
  // With FramePlan::Measure::kReference: the pass "path_trace" (record), after the passes it
  // needs (the planet's: the weather map).
  void add_passes(FrameGraph& graph, const FrameSetup& frame) override;

  // Uploads the noise clouds' majorant grid (path_majorant.h's layout) and binds it.
  void upload_majorant(const std::vector<float>& grid);

  const gpu::Texture& sum() const { return sum_; }
  const gpu::Texture& squares() const { return squares_; }

 private:
  gpu::Context& ctx_;
  gpu::DescriptorSet& set_;
  // Built on first use (a pipeline costs a CPU device its compilation at creation): the lab,
  // the planet with the default and with the baseline field.
  mutable std::unique_ptr<gpu::Kernel> kernels_[3];
  gpu::Texture sum_, squares_;
  gpu::Texture majorant_;  // 1 x 1 x 2 texels until a grid is uploaded
  int first_sample_ = 0, samples_ = 1;
};

}  // namespace nephele
