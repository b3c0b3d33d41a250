// Bloom and glare (output.bloom_*): the lens spreads a share of the image's bright light over a
// Gaussian of an angular radius, keeping the image's total light (bloom.comp, two separable
// passes through a scratch image). Recorded after the stars, before the exposure meter and the
// display's tone map; only the image, not the film's layers.
#pragma once

#include <memory>

#include "gpu/kernel.h"
#include "nephele/scene.h"
#include "render/gpu_params.h"

namespace nephele {

// The most taps each side of the Gaussian: sigma is capped at a third of it.
constexpr int kBloomMaxTaps = 256;

class BloomModule {
 public:
  BloomModule(gpu::Context& ctx, gpu::DescriptorSet& set);

  // Fills params.bloom for a width x height image and sizes the scratch image; false when the
  // scene has no bloom (nothing to record).
  bool prepare(const Scene& scene, int width, int height, gpu::FrameParams& params);
  void record(VkCommandBuffer cmd, gpu::PassTimer& timer, int width, int height);

 private:
  gpu::Context& ctx_;
  gpu::DescriptorSet& set_;
  gpu::Texture temp_;
  std::unique_ptr<gpu::Kernel> horizontal_, vertical_;  // made when first recorded
};

// The Gaussian's sigma in pixels for a vertical field of view and image height, and its taps
// each side (3 sigma, at most kBloomMaxTaps and fewer than the image's smaller side).
glm::vec2 bloom_kernel(float radius_deg, float vertical_fov_deg, int width, int height);

}  // namespace nephele
