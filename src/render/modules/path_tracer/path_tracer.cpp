#include "render/modules/path_tracer/path_tracer.h"

#include <algorithm>
#include <cstring>

#include "render/gpu_params.h"

namespace nephele {

PathTracerModule::PathTracerModule(gpu::Context& ctx, gpu::DescriptorSet& set)
    : ctx_(ctx),
      set_(set),
      // Depth 2: a texture of depth 1 is a 2D image, and the shader reads a 3D one.
      majorant_(ctx, 1, 1, 2, VK_FORMAT_R32_SFLOAT, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE) {
  set_.bind_sampled_image(gpu::kPathMajorant, majorant_);
}

void PathTracerModule::upload_majorant(const std::vector<float>& grid, glm::ivec3 size) {
  // Depth 2 at least: a texture of depth 1 is a 2D image, and the shader reads a 3D one.
  const glm::uvec3 texels(size.x, size.y, std::max(size.z, 2));
  std::vector<float> texel_values = grid;
  texel_values.resize(size_t(texels.x) * texels.y * texels.z, 0.0f);
  if (majorant_.width() != texels.x || majorant_.height() != texels.y ||
      majorant_.depth() != texels.z) {
    ctx_.wait_queue_idle();
    majorant_ = gpu::Texture(ctx_, texels.x, texels.y, texels.z, VK_FORMAT_R32_SFLOAT,
                             VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
    set_.bind_sampled_image(gpu::kPathMajorant, majorant_);
  }
  gpu::Buffer staging(ctx_, VkDeviceSize(texel_values.size() * sizeof(float)),
                      VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  std::memcpy(staging.data(), texel_values.data(), texel_values.size() * sizeof(float));
  ctx_.submit_and_wait([&](VkCommandBuffer cmd) { majorant_.record_upload(cmd, staging); });
}

void PathTracerModule::resize(int width, int height, int slots) {
  slots_ = slots;
  if (int(sum_.width()) == width && int(sum_.height()) == height * slots) return;
  for (gpu::Texture* t : {&sum_, &squares_})
    *t = gpu::Texture(ctx_, uint32_t(width), uint32_t(height * slots), 1,
                      VK_FORMAT_R32G32B32A32_SFLOAT, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  set_.bind_storage_image(gpu::kPathSum, sum_);
  set_.bind_storage_image(gpu::kPathSquares, squares_);
}

void PathTracerModule::clear(VkCommandBuffer cmd) const {
  sum_.record_clear(cmd);
  squares_.record_clear(cmd);
}

void PathTracerModule::record(VkCommandBuffer cmd, gpu::PassTimer& timer, bool planet,
                              MarchMode mode) const {
  const int baseline = mode == MarchMode::Baseline ? 1 : 0;
  const int variant = planet ? 1 + baseline : 0;
  if (!kernels_[variant])
    kernels_[variant] = std::make_unique<gpu::Kernel>(
        ctx_, set_, "path_trace.comp.spv", std::vector<int32_t>{planet ? 1 : 0, baseline});
  gpu::dispatch(cmd, *kernels_[variant], timer, "path_trace", sum_.width(),
                sum_.height() / uint32_t(slots_), uint32_t(slots_), 8, 8, 1,
                gpu::DispatchConstants{glm::ivec4(first_sample_, samples_, seed_, max_bounces_)});
}

void PathTracerModule::add_passes(FrameGraph& graph, const FrameSetup& frame) {
  if (frame.plan.measure != FramePlan::Measure::kReference) return;
  const bool planet = frame.plan.planet_reference;
  const MarchMode mode = frame.scene.quality.mode;
  graph.output("path_sums");
  graph.add_pass("path_trace",
                 planet ? std::vector<std::string>{"weather_map", "noise", "voxel_clouds",
                                                   "atmosphere", FrameGraph::kView}
                        : std::vector<std::string>{"voxel_clouds", FrameGraph::kView},
                 {"path_sums"}, [timer = frame.timer, this, planet, mode](VkCommandBuffer cmd) {
                   record(cmd, timer(), planet, mode);
                 });
}

}  // namespace nephele
