#include "render/modules/noise/noise.h"

#include <cstdio>

#include "gpu/shader_interface.h"
#include "render/disk_cache.h"
#include "render/texture_cache.h"

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

std::string noise_cache_name(std::span<const uint32_t> spirv, const std::string& device,
                             uint32_t seed) {
  uint64_t h = fnv1a64({reinterpret_cast<const uint8_t*>(spirv.data()), spirv.size_bytes()});
  h = fnv1a64(device, h);
  h = fnv1a64({reinterpret_cast<const uint8_t*>(&seed), sizeof(seed)}, h);
  char name[48];
  std::snprintf(name, sizeof(name), "base_noise_%016llx.bin", static_cast<unsigned long long>(h));
  return name;
}

std::filesystem::path NoiseModule::cache_file(uint32_t seed) const {
  const std::filesystem::path dir = cache_dir();
  if (dir.empty()) return {};
  return dir /
         noise_cache_name(gpu::embedded_spirv("noise_base.comp.spv"), ctx_.device_name(), seed);
}

std::optional<std::filesystem::path> NoiseModule::load_base(uint32_t seed) {
  const std::filesystem::path file = cache_file(seed);
  if (!load_cached_texture(ctx_, base_, file, kBaseNoiseBytes)) return std::nullopt;
  return file;
}

void NoiseModule::store_base(uint32_t seed) {
  store_cached_texture(ctx_, base_, cache_file(seed), kBaseNoiseBytes);
}

void NoiseModule::add_passes(FrameGraph& graph, const FrameSetup& /*frame*/) {
  graph.import("noise");  // made before the frame when stale (update_noise)
}

}  // namespace nephele
