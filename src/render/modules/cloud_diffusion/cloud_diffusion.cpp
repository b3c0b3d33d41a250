#include "render/modules/cloud_diffusion/cloud_diffusion.h"

#include <cstring>

#include "render/gpu_params.h"
// The block's one definition, as the shaders have it.
#include "render/modules/cloud_diffusion/cloud_diffusion_gpu_inc.glsl"

namespace nephele {

namespace {
constexpr const char* kBlockName = "CloudDiffusionBlock";
// The grid's horizontal half extent: 125 m cells at 128 a side.
constexpr float kHalfExtentM = 4500.0f;
// Successive over-relaxation: the red-black sweeps converge about 20 times faster than
// Gauss-Seidel's on the grid's clouds (tens of cells across).
constexpr float kOverRelaxation = 1.8f;

uint32_t rows() {
  return uint32_t(gpu::DIFFUSION_XY * gpu::DIFFUSION_Z);
}
}  // namespace

CloudDiffusionModule::CloudDiffusionModule(const ModuleContext& context)
    : set_(context.set),
      fill_(context.ctx, context.set, "diffusion_fill.comp.spv", 0, {1, 1}),
      solve_(context.ctx, context.set, "diffusion_solve.comp.spv"),
      gather_(context.ctx, context.set, "diffusion_field.comp.spv") {
  const auto volume = [&](VkFormat format) {
    return gpu::Texture(context.ctx, gpu::DIFFUSION_XY, gpu::DIFFUSION_XY, gpu::DIFFUSION_Z, format,
                        VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  };
  medium_ = volume(VK_FORMAT_R32G32B32A32_SFLOAT);
  phi_ = volume(VK_FORMAT_R32_SFLOAT);
  field_ = volume(VK_FORMAT_R32G32B32A32_SFLOAT);
  for (gpu::Buffer& b : blocks_) {
    b = gpu::Buffer(context.ctx, sizeof(gpu::CloudDiffusionGpu),
                    VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    std::memset(b.data(), 0, sizeof(gpu::CloudDiffusionGpu));  // not in use
  }
  // The march declares the block and the field whatever its lighting: always bound.
  set_.bind_module_buffer(kBlockName, blocks_[0], VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
  set_.bind_module_sampled_image("cloud_diffusion_field", field_);
  set_.bind_module_storage_image("cloud_diffusion_field_out", field_);
  set_.bind_module_storage_image("cloud_diffusion_medium_out", medium_);
  set_.bind_module_storage_image("cloud_diffusion_medium", medium_);
  set_.bind_module_storage_image("cloud_diffusion_phi_out", phi_);
  set_.bind_module_storage_image("cloud_diffusion_phi", phi_);
}

void CloudDiffusionModule::prepare(const FramePrepare& frame, FramePlan& plan) {
  const gpu::FrameParams& params = frame.params;
  const bool on =
      frame.scene.clouds.lighting == "diffusion" && plan.volumetric && params.light_volume.w > 0.0f;
  rebuild_ = on && (!built_ || plan.light_volume_built);
  built_ = on && (built_ || rebuild_);
  with_voxels_ = params.voxel_info.x > 0;
  with_flow_ = params.cloud_flow.x > 0.0f;
  gpu::CloudDiffusionGpu block{};
  if (on) {
    // Centred where the light volume is (the camera, when it was built), in cloud space.
    block.grid = glm::vec4(params.light_volume.x, params.light_volume.y, kHalfExtentM, 1.0f);
    const float thickness_m = params.radii_m.w - params.radii_m.z;
    block.cell = glm::vec4(2.0f * kHalfExtentM / float(gpu::DIFFUSION_XY),
                           thickness_m / float(gpu::DIFFUSION_Z), kOverRelaxation, 0.0f);
  }
  std::memcpy(blocks_[frame.slot].data(), &block, sizeof(block));
  set_.bind_module_buffer(kBlockName, blocks_[frame.slot], VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
}

void CloudDiffusionModule::record(VkCommandBuffer cmd, gpu::PassTimer& timer) {
  gpu::dispatch(cmd, fill_.get({with_voxels_ ? 1 : 0, with_flow_ ? 1 : 0}), timer, "diffusion_fill",
                gpu::DIFFUSION_XY, rows(), 1, 8, 8, 1);
  // Each sweep the red cells, then the black.
  gpu::dispatch_repeated(cmd, solve_, timer, "diffusion_solve", 2 * kDiffusionSweeps,
                         glm::uvec3(gpu::DIFFUSION_XY / 2, rows(), 1), glm::uvec3(8, 8, 1),
                         [](int k) { return gpu::DispatchConstants{glm::ivec4(k & 1, 0, 0, 0)}; });
  gpu::dispatch(cmd, gather_, timer, "diffusion_field", gpu::DIFFUSION_XY, rows(), 1, 8, 8, 1);
}

void CloudDiffusionModule::add_passes(FrameGraph& graph, const FrameSetup& frame) {
  graph.import("cloud_diffusion", true);  // kept until the light volume is rebuilt
  if (!rebuild_) return;
  graph.add_pass("cloud_diffusion", {"weather_map", "noise", "voxel_clouds", "light_volume"},
                 {"cloud_diffusion"},
                 [timer = frame.timer, this](VkCommandBuffer cmd) { record(cmd, timer()); });
}

std::unique_ptr<RenderModule> make_cloud_diffusion_module(const ModuleContext& context) {
  return std::make_unique<CloudDiffusionModule>(context);
}

}  // namespace nephele
