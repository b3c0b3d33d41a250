#include "render/modules/noise/noise.h"

namespace nephele {

NoiseModule::NoiseModule(gpu::Context& ctx, gpu::DescriptorSet& set)
    : set_(set),
      base_kernel_(ctx, set, "noise_base.comp.spv"),
      detail_kernel_(ctx, set, "noise_detail.comp.spv"),
      curl_kernel_(ctx, set, "noise_curl.comp.spv"),
      base_(ctx, kBaseNoiseSize, kBaseNoiseSize, kBaseNoiseSize, VK_FORMAT_R8G8B8A8_UNORM),
      detail_(ctx, kDetailNoiseSize, kDetailNoiseSize, kDetailNoiseSize, VK_FORMAT_R8G8B8A8_UNORM,
              VK_SAMPLER_ADDRESS_MODE_REPEAT, kDetailNoiseLevels),
      curl_(ctx, kCurlNoiseSize, kCurlNoiseSize, 1, VK_FORMAT_R32G32B32A32_SFLOAT) {
  set_.bind_image(gpu::kBaseNoiseOut, gpu::kBaseNoise, base_);
  set_.bind_image(gpu::kDetailNoiseOut, gpu::kDetailNoise, detail_);
  set_.bind_image(gpu::kCurlNoiseOut, gpu::kCurlNoise, curl_);
}

void NoiseModule::record(VkCommandBuffer cmd, gpu::PassTimer& timer, int i) {
  switch (i) {
    case 0:
      gpu::dispatch(cmd, base_kernel_, timer, "noise_base", kBaseNoiseSize, kBaseNoiseSize,
                    kBaseNoiseSize, 4, 4, 4);
      break;
    case 1:
      gpu::dispatch(cmd, detail_kernel_, timer, "noise_detail", kDetailNoiseSize, kDetailNoiseSize,
                    kDetailNoiseSize, 4, 4, 4);
      detail_.record_mipmaps(cmd);
      break;
    default:
      gpu::dispatch(cmd, curl_kernel_, timer, "noise_curl", kCurlNoiseSize, kCurlNoiseSize, 1, 8, 8,
                    1);
  }
}

void NoiseModule::add_passes(FrameGraph& graph, const FrameSetup& /*frame*/) {
  graph.import("noise");  // made before the frame when stale (update_noise)
}

}  // namespace nephele
