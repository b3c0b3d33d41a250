// Post-processing of the frame's linear HDR image, after the stars and before the exposure
// meter and the display's tone map (only the image, not the film's layers), through one
// scratch image (post_temp):
// - seed 002's screen-space god rays and their radial blur (quality.light_shafts = "screen";
//   god_rays.comp), which add light;
// - bloom and glare (output.bloom_*; bloom.comp): the lens spreads a share of the image's
//   bright light over a Gaussian of an angular radius, keeping the image's total light.
#pragma once

#include <memory>

#include "gpu/kernel.h"
#include "nephele/scene.h"
#include "render/gpu_params.h"
#include "render/render_module.h"

namespace nephele {

// The most taps each side of bloom's Gaussian: sigma is capped at a third of it.
constexpr int kBloomMaxTaps = 256;

class PostModule : public RenderModule {
 public:
  PostModule(gpu::Context& ctx, gpu::DescriptorSet& set);
  void add_passes(FrameGraph& graph, const FrameSetup& frame) override;

  // Fills params.bloom for a width x height image and sizes the scratch image; false when the
  // scene has no post-processing (nothing to record).
  bool prepare(const Scene& scene, int width, int height, gpu::FrameParams& params);
  // The contract's (render_module.h): the above with the frame's values.
  void prepare(const FramePrepare& frame, FramePlan& plan) override;
  // God rays and bloom over the image prepare() sized for.
  void record(VkCommandBuffer cmd, gpu::PassTimer& timer);

 private:
  gpu::Context& ctx_;
  gpu::DescriptorSet& set_;
  gpu::Texture temp_;
  bool god_rays_ = false, bloom_ = false;  // this frame's
  int width_ = 0, height_ = 0;             // this frame's image
  // Made when first recorded: the rays and their blur, bloom along x and along y.
  std::unique_ptr<gpu::Kernel> rays_, rays_blur_, bloom_x_, bloom_y_;
};

// Bloom's Gaussian's sigma in pixels for a vertical field of view and image height, and its
// taps each side (3 sigma, at most kBloomMaxTaps and fewer than the image's smaller side).
glm::vec2 bloom_kernel(float radius_deg, float vertical_fov_deg, int width, int height);

}  // namespace nephele
