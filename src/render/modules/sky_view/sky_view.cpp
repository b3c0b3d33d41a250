#include "render/modules/sky_view/sky_view.h"

#include "render/glsl.h"

namespace nephele {

SkyViewModule::SkyViewModule(gpu::Context& ctx, gpu::DescriptorSet& set)
    : set_(set),
      lut_kernel_(ctx, set, "sky_view.comp.spv"),
      volume_kernel_(ctx, set, "aerial_perspective.comp.spv") {
  for (int i = 0; i < 2; ++i) {
    // Half floats hold radiance to 0.05%. Both tables wrap in azimuth (u); v and w are kept
    // half a texel inside by the shaders (sky_view_inc.glsl), so repeating there reads nothing.
    luts_[i] = gpu::Texture(ctx, kSkyViewWidth, 2 * kSkyViewHeight, 1,
                            VK_FORMAT_R16G16B16A16_SFLOAT, VK_SAMPLER_ADDRESS_MODE_REPEAT);
    volumes_[i] = gpu::Texture(ctx, glsl::AP_SIZE_U, glsl::AP_SIZE_V, glsl::AP_SLICES,
                               VK_FORMAT_R32G32B32A32_SFLOAT, VK_SAMPLER_ADDRESS_MODE_REPEAT);
  }
  set_.bind_image(gpu::kSkyViewOut, gpu::kSkyViewLut, luts_[0]);
  set_.bind_image(gpu::kAerialPerspectiveOut, gpu::kAerialPerspective, volumes_[0]);
}

namespace {
constexpr int kLutSteps = kSkyViewBuildFrames / 2;
constexpr int kVolumeSteps = kSkyViewBuildFrames - kLutSteps;
// Band `step` of `steps` of `rows` rows: (first, count).
glm::ivec2 band(int step, int steps, int rows) {
  const int first = rows * step / steps;
  return {first, rows * (step + 1) / steps - first};
}
}  // namespace

void SkyViewModule::prepare(bool still, gpu::FrameParams& params) {
  const Built now{sky_view_key(params), params.sky_view_up, params.sky_view_forward};
  const bool stale = !read_ || !sky_view_reusable(read_->key, now.key);
  const int lut_rows = int(kSkyViewHeight), volume_rows = glsl::AP_SIZE_V;
  rows_ = glm::ivec4(0);
  bool complete = false;
  if (stale && (still || !read_)) {  // the whole pair now, read in this frame
    rows_ = glm::ivec4(0, lut_rows, 0, volume_rows);
    building_ = now;
    complete = true;
  } else {
    if (stale && !building_) {
      building_ = now;
      step_ = 0;
    }
    if (building_) {
      if (step_ < kLutSteps) {
        const glm::ivec2 b = band(step_, kLutSteps, lut_rows);
        rows_ = glm::ivec4(b, 0, 0);
      } else {
        const glm::ivec2 b = band(step_ - kLutSteps, kVolumeSteps, volume_rows);
        rows_ = glm::ivec4(0, 0, b);
      }
      complete = ++step_ == kSkyViewBuildFrames;
    }
  }
  const int build = 1 - read_index_;
  const Built target = building_ ? *building_ : *read_;
  if (complete) {  // read the pair in this frame, after its last band
    read_index_ = build;
    read_ = target;
    building_.reset();
  }
  set_.bind_storage_image(gpu::kSkyViewOut, luts_[build]);
  set_.bind_storage_image(gpu::kAerialPerspectiveOut, volumes_[build]);
  set_.bind_sampled_image(gpu::kSkyViewLut, luts_[read_index_]);
  set_.bind_sampled_image(gpu::kAerialPerspective, volumes_[read_index_]);
  params.sky_view_build_up = target.up;
  params.sky_view_build_forward = target.forward;
  params.sky_view_up = read_->up;
  params.sky_view_forward = read_->forward;
  params.sky_view_rows = rows_;
}

void SkyViewModule::record(VkCommandBuffer cmd, gpu::PassTimer& timer) {
  if (rows_.y > 0)
    gpu::dispatch(cmd, lut_kernel_, timer, "sky_view", kSkyViewWidth, uint32_t(rows_.y), 1, 8, 8,
                  1);
  if (rows_.w > 0)
    gpu::dispatch(cmd, volume_kernel_, timer, "aerial_persp", glsl::AP_SIZE_U, uint32_t(rows_.w), 1,
                  8, 8, 1);
}

void SkyViewModule::add_passes(FrameGraph& graph, const FrameSetup& frame) {
  graph.import("sky_view", true);  // built over several frames, reused while it holds
  graph.add_pass("sky_view", {"atmosphere"}, {"sky_view"},
                 [timer = frame.timer, this](VkCommandBuffer cmd) { record(cmd, timer()); });
}

void SkyViewModule::prepare(const FramePrepare& frame, FramePlan&) {
  prepare(frame.still, frame.params);
}

}  // namespace nephele
