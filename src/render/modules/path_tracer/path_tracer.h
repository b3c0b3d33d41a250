// The reference path tracer module (issue 21): the accumulation images and the kernel of
// path_trace.comp (a CPU device's) or path_trace_gpu.comp (a GPU's).
// FrameRenderer::Impl::render_reference (src/render/reference.cpp) drives it.
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

  // Sizes the accumulation images and the paths in progress for width x height pixels whose
  // samples `slots` invocations of each dispatch share (slot k's in rows [k height, (k + 1)
  // height)) and binds them (before the work that uses them starts recording); clear() records
  // setting them to zero, and zeroes the counts.
  void resize(int width, int height, int slots);
  int slots() const { return slots_; }
  void clear(VkCommandBuffer cmd) const;
  // Runs every invocation's paths on for set_samples' iterations, with the paths set_paths gave:
  // of the lab (`planet` false), or of the planet's scene with the noise clouds' field of `mode`.
  // All four numbers travel as the dispatch's push constants.
  void record(VkCommandBuffer cmd, gpu::PassTimer& timer, bool planet, MarchMode mode) const;
  // The next path_trace pass: each pixel's samples numbered under `target` (slot k of S takes k,
  // k + S, ...; 0: each slot finishes the sample it is on and a multiple of three), at most
  // `iterations` iterations an invocation (path_trace.comp).
  void set_samples(int target, int iterations) {
    target_ = target;
    iterations_ = iterations;
  }
  // What the passes so far have done (path_trace.comp's path_counts), once they have ended.
  struct Counts {
    uint32_t finished = 0;    // samples finished, over all pixels and slots
    uint32_t running = 0;     // invocations with samples still to take after the last pass
    uint32_t cut = 0;         // walks cut at PT_MAX_COLLISIONS: the image is biased if any
    uint32_t violations = 0;  // tentative collisions above their majorant
    uint32_t limited = 0;     // invocations whose pass the device's loop limit ended early
  };
  Counts counts() const;
  // Zeroes the count of running invocations, before a pass.
  void reset_running();
  // The random streams' seed and the paths' largest number of bounces.
  void set_paths(int seed, int max_bounces) {
    seed_ = seed;
    max_bounces_ = max_bounces;
  }
  // Whether a pass undoes the iteration a device's loop limit cut short (path_trace.comp, for
  // a CPU device) or has no such limit (path_trace_gpu.comp); by default the device's kind.
  void set_undo_cut_iteration(bool undo) { undo_ = undo; }
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
  // the planet with the default and with the baseline field; each without and with the undo.
  mutable std::unique_ptr<gpu::Kernel> kernels_[6];
  gpu::Texture sum_, squares_, state_;
  gpu::Buffer counts_;
  gpu::Texture majorant_;  // 1 x 1 x 2 texels until a grid is uploaded
  int target_ = 0, iterations_ = 1, slots_ = 1;
  int seed_ = 0, max_bounces_ = 0;
  bool undo_ = true;
};

}  // namespace nephele
