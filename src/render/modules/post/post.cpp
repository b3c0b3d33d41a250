#include "render/modules/post/post.h"

#include <algorithm>
#include <cmath>

namespace nephele {

glm::vec2 bloom_kernel(float radius_deg, float vertical_fov_deg, int width, int height) {
  // Pixels per degree at the image's centre: the focal length in pixels times tan(1 deg).
  const float focal_px = 0.5f * float(height) / std::tan(glm::radians(0.5f * vertical_fov_deg));
  const float sigma = std::max(focal_px * std::tan(glm::radians(radius_deg)), 0.3f);
  const int taps = std::max(
      std::min({int(std::ceil(3.0f * sigma)), kBloomMaxTaps, std::min(width, height) - 1}), 0);
  // Fewer taps than 3 sigma: the Gaussian narrowed to fit them.
  return glm::vec2(std::min(sigma, std::max(float(taps), 1.0f) / 3.0f), float(taps));
}

PostModule::PostModule(gpu::Context& ctx, gpu::DescriptorSet& set)
    : ctx_(ctx),
      set_(set),
      temp_(ctx, 1, 1, 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE) {
  set_.bind_storage_image(gpu::kPostTemp, temp_);
}

bool PostModule::prepare(const Scene& scene, int width, int height, gpu::FrameParams& params) {
  const OutputParams& o = scene.output;
  width_ = width;
  height_ = height;
  const glm::vec2 kernel =
      bloom_kernel(o.bloom_radius_deg, vertical_fov_deg(scene.camera, float(width) / float(height)),
                   width, height);
  params.bloom = glm::vec4(o.bloom_strength, o.bloom_threshold_cd_m2, kernel.x, kernel.y);
  bloom_ = o.bloom_strength > 0.0f && kernel.y >= 1.0f;
  god_rays_ = light_shafts_method(scene.quality.light_shafts) == gpu::LIGHT_SHAFTS_SCREEN;
  if (!bloom_ && !god_rays_) return false;
  if (temp_.width() != uint32_t(width) || temp_.height() != uint32_t(height)) {
    ctx_.wait_queue_idle();  // a frame in flight may still use the old one
    temp_ = gpu::Texture(ctx_, uint32_t(width), uint32_t(height), 1, VK_FORMAT_R32G32B32A32_SFLOAT,
                         VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
    set_.bind_storage_image(gpu::kPostTemp, temp_);
  }
  return true;
}

void PostModule::record(VkCommandBuffer cmd, gpu::PassTimer& timer) {
  const int width = width_, height = height_;
  const auto pass = [&](std::unique_ptr<gpu::Kernel>& kernel, const char* spv, int constant,
                        const char* name) {
    if (!kernel)
      kernel = std::make_unique<gpu::Kernel>(ctx_, set_, spv, std::vector<int32_t>{constant});
    gpu::dispatch(cmd, *kernel, timer, name, uint32_t(width), uint32_t(height), 1, 8, 8, 1);
  };
  if (god_rays_) {
    pass(rays_, "god_rays.comp.spv", 0, "god_rays");
    pass(rays_blur_, "god_rays.comp.spv", 1, "god_rays_blur");
  }
  if (bloom_) {
    pass(bloom_x_, "bloom.comp.spv", 0, "bloom_x");
    pass(bloom_y_, "bloom.comp.spv", 1, "bloom_y");
  }
}

void PostModule::add_passes(FrameGraph& graph, const FrameSetup& frame) {
  if (!frame.plan.post) return;
  graph.add_pass("post", {"color", "cloud_layer", "terrain", "shafts", FrameGraph::kView},
                 {"color"},
                 [timer = frame.timer, this](VkCommandBuffer cmd) { record(cmd, timer()); });
}

void PostModule::prepare(const FramePrepare& frame, FramePlan& plan) {
  plan.post = prepare(frame.scene, frame.width, frame.height, frame.params);
}

}  // namespace nephele
