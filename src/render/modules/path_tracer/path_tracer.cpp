#include "render/modules/path_tracer/path_tracer.h"

#include <algorithm>
#include <cstring>

#include "render/gpu_params.h"

namespace nephele {

PathTracerModule::PathTracerModule(gpu::Context& ctx, gpu::DescriptorSet& set)
    : ctx_(ctx),
      set_(set),
      // Depth 2: a texture of depth 1 is a 2D image, and the shader reads a 3D one.
      counts_(ctx, sizeof(Counts), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT),
      majorant_(ctx, 1, 1, 2, VK_FORMAT_R32_SFLOAT, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE) {
  set_.bind_sampled_image(gpu::kPathMajorant, majorant_);
  set_.bind_buffer(gpu::kPathCounts, counts_, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  undo_ = ctx.is_cpu();
}

void PathTracerModule::reset_running() {
  static_cast<Counts*>(counts_.data())->running = 0;
}

PathTracerModule::Counts PathTracerModule::counts() const {
  Counts c;
  std::memcpy(&c, counts_.data(), sizeof(c));
  return c;
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
  state_ = gpu::Texture(ctx_, uint32_t(width), uint32_t(height * slots * gpu::PATH_STATE_TEXELS), 1,
                        VK_FORMAT_R32G32B32A32_SFLOAT, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  set_.bind_storage_image(gpu::kPathSum, sum_);
  set_.bind_storage_image(gpu::kPathSquares, squares_);
  set_.bind_storage_image(gpu::kPathState, state_);
}

void PathTracerModule::clear(VkCommandBuffer cmd) const {
  sum_.record_clear(cmd);
  squares_.record_clear(cmd);
  state_.record_clear(cmd);
  std::memset(counts_.data(), 0, sizeof(Counts));
}

void PathTracerModule::record(VkCommandBuffer cmd, gpu::PassTimer& timer, bool planet,
                              MarchMode mode) const {
  const int baseline = mode == MarchMode::Baseline ? 1 : 0;
  const int variant = (planet ? 1 + baseline : 0) + (undo_ ? 3 : 0);
  if (!kernels_[variant])
    kernels_[variant] = std::make_unique<gpu::Kernel>(
        ctx_, set_, undo_ ? "path_trace.comp.spv" : "path_trace_gpu.comp.spv",
        std::vector<int32_t>{planet ? 1 : 0, baseline});
  gpu::dispatch(cmd, *kernels_[variant], timer, "path_trace", sum_.width(),
                sum_.height() / uint32_t(slots_), uint32_t(slots_), 8, 8, 1,
                gpu::DispatchConstants{glm::ivec4(target_, iterations_, seed_, max_bounces_)});
  // The counts, for the host once the pass has ended.
  VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  to_host.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1,
                       &to_host, 0, nullptr, 0, nullptr);
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
