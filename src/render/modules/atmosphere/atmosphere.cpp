#include "render/modules/atmosphere/atmosphere.h"

#include <cstring>

namespace nephele {

namespace {
// The texels of an RGBA32F texture.
std::vector<glm::vec4> read_texels(gpu::Context& ctx, const gpu::Texture& texture) {
  std::vector<glm::vec4> texels(size_t(texture.width()) * texture.height());
  gpu::Buffer staging(ctx, VkDeviceSize(texels.size() * sizeof(glm::vec4)),
                      VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  ctx.submit_and_wait([&](VkCommandBuffer cmd) { texture.record_download(cmd, staging); });
  std::memcpy(texels.data(), staging.data(), texels.size() * sizeof(glm::vec4));
  return texels;
}
}  // namespace

AtmosphereModule::AtmosphereModule(gpu::Context& ctx, gpu::DescriptorSet& set)
    : ctx_(ctx),
      set_(set),
      transmittance_kernel_(ctx, set, "transmittance_lut.comp.spv"),
      ms_kernel_(ctx, set, "multiscattering_lut.comp.spv"),
      field_kernels_([&] {
        std::vector<std::unique_ptr<gpu::Kernel>> kernels;
        for (int i = 0; i < glsl::MS_FIELD_ITERATIONS; ++i)
          kernels.push_back(std::make_unique<gpu::Kernel>(ctx, set, "ms_field.comp.spv",
                                                          std::vector<int32_t>{i}));
        return kernels;
      }()),
      transmittance_(ctx, glsl::TRANSMITTANCE_LUT_W, glsl::TRANSMITTANCE_LUT_H, 1,
                     VK_FORMAT_R32G32B32A32_SFLOAT, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE),
      ms_(ctx, glsl::MS_LUT_W, glsl::MS_LUT_H, 1, VK_FORMAT_R32G32B32A32_SFLOAT,
          VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE),
      field_(ctx, glsl::MS_FIELD_COEFFS * glsl::MS_FIELD_W, 2 * glsl::MS_FIELD_H, 1,
             VK_FORMAT_R32G32B32A32_SFLOAT, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE) {
  set_.bind_image(gpu::kTransmittanceLutOut, gpu::kTransmittanceLut, transmittance_);
  set_.bind_image(gpu::kMsLutOut, gpu::kMsLut, ms_);
  set_.bind_image(gpu::kMsFieldOut, gpu::kMsField, field_);
}

void AtmosphereModule::record(VkCommandBuffer cmd, gpu::PassTimer& timer) {
  gpu::dispatch(cmd, transmittance_kernel_, timer, "transmittance", glsl::TRANSMITTANCE_LUT_W,
                glsl::TRANSMITTANCE_LUT_H, 1, 8, 8, 1);
  gpu::dispatch(cmd, ms_kernel_, timer, "multiscatter", glsl::MS_LUT_W, glsl::MS_LUT_H, 1, 8, 8, 1);
  for (const auto& kernel : field_kernels_)
    gpu::dispatch(cmd, *kernel, timer, "ms field", glsl::MS_FIELD_W, glsl::MS_FIELD_H, 1, 8, 8, 1);
}

void AtmosphereModule::made(const AtmosphereParams& atmosphere) {
  tables_.transmittance = read_texels(ctx_, transmittance_);
  tables_.multiple_scattering = read_texels(ctx_, ms_);
  tables_.ms_field = read_texels(ctx_, field_);
  built_ = atmosphere;
}

void AtmosphereModule::add_passes(FrameGraph& graph, const FrameSetup& /*frame*/) {
  graph.import("atmosphere");  // the tables, made before the frame when stale
}

}  // namespace nephele
