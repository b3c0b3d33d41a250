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

  // Sizes the accumulation images for width x height pixels whose samples `slots` invocations
  // of each dispatch share (slot k's sums in rows [k height, (k + 1) height)) and binds them
  // (before the work that uses them starts recording); clear() records setting them to zero.
  void resize(int width, int height, int slots);
  int slots() const { return slots_; }
  void clear(VkCommandBuffer cmd) const;
  // Adds the samples set_samples gave to every pixel in every slot, with the paths set_paths gave:
  // of the lab (`planet` false), or of the planet's scene with the noise clouds' field of `mode`.
  // All four numbers travel as the dispatch's push constants.
  void record(VkCommandBuffer cmd, gpu::PassTimer& timer, bool planet, MarchMode mode) const;
  // The samples the next path_trace pass of the graph adds: `samples` a pixel in each slot
  // (slots x samples in all), the first numbered `first_sample`.
  void set_samples(int first_sample, int samples) {
    first_sample_ = first_sample;
    samples_ = samples;
  }
  // The random streams' seed and the paths' largest number of bounces.
  void set_paths(int seed, int max_bounces) {
    seed_ = seed;
    max_bounces_ = max_bounces;
  }
  // With FramePlan::Measure::kReference: the pass "path_trace" (record), after the passes it
  // needs (the planet's: the weather map).
  void add_passes(FrameGraph& graph, const FrameSetup& frame) override;

  // Uploads a majorant grid of width x height x depth bounds (x fastest) and binds it: the
  // noise clouds' (path_majorant.h's layout) or the lab's bricks' (lab_brick_majorants).
  void upload_majorant(const std::vector<float>& grid, glm::ivec3 size);

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
  int first_sample_ = 0, samples_ = 1, slots_ = 1;
  int seed_ = 0, max_bounces_ = 0;
};

}  // namespace nephele
