#include "render/modules/noise/noise.h"

#include <cstring>

#include "gpu/shader_interface.h"
#include "render/modules/noise/noise_cache.h"

namespace nephele {

namespace {
constexpr size_t kBaseNoiseBytes = size_t(kBaseNoiseSize) * kBaseNoiseSize * kBaseNoiseSize * 4;
}

NoiseModule::NoiseModule(gpu::Context& ctx, gpu::DescriptorSet& set)
    : ctx_(ctx),
      set_(set),
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

std::filesystem::path NoiseModule::cache_file(uint32_t seed) const {
  const std::filesystem::path dir = noise_cache_dir();
  if (dir.empty()) return {};
  return dir /
         noise_cache_name(gpu::embedded_spirv("noise_base.comp.spv"), ctx_.device_name(), seed);
}

std::optional<std::filesystem::path> NoiseModule::load_base(uint32_t seed) {
  const std::filesystem::path file = cache_file(seed);
  if (file.empty()) return std::nullopt;
  const std::optional<std::vector<uint8_t>> texels = read_noise_cache(file, kBaseNoiseBytes);
  if (!texels) return std::nullopt;
  gpu::Buffer staging(ctx_, kBaseNoiseBytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  std::memcpy(staging.data(), texels->data(), kBaseNoiseBytes);
  ctx_.submit_and_wait([&](VkCommandBuffer cmd) { base_.record_upload(cmd, staging); });
  return file;
}

void NoiseModule::store_base(uint32_t seed) {
  const std::filesystem::path file = cache_file(seed);
  if (file.empty()) return;
  gpu::Buffer staging(ctx_, kBaseNoiseBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  ctx_.submit_and_wait([&](VkCommandBuffer cmd) { base_.record_download(cmd, staging); });
  // A cache that cannot be written (a read-only home) only costs the next process the time.
  write_noise_cache(file, {static_cast<const uint8_t*>(staging.data()), kBaseNoiseBytes});
}

void NoiseModule::add_passes(FrameGraph& graph, const FrameSetup& /*frame*/) {
  graph.import("noise");  // made before the frame when stale (update_noise)
}

}  // namespace nephele
