#include "render/texture_cache.h"

#include <cstring>
#include <optional>
#include <vector>

#include "render/disk_cache.h"

namespace nephele {

bool load_cached_texture(gpu::Context& ctx, const gpu::Texture& texture,
                         const std::filesystem::path& file, size_t bytes) {
  if (file.empty()) return false;
  const std::optional<std::vector<uint8_t>> texels = read_cache_file(file, bytes);
  if (!texels) return false;
  gpu::Buffer staging(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  std::memcpy(staging.data(), texels->data(), bytes);
  ctx.submit_and_wait([&](VkCommandBuffer cmd) { texture.record_upload(cmd, staging); });
  return true;
}

bool store_cached_texture(gpu::Context& ctx, const gpu::Texture& texture,
                          const std::filesystem::path& file, size_t bytes) {
  if (file.empty()) return false;
  gpu::Buffer staging(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  ctx.submit_and_wait([&](VkCommandBuffer cmd) { texture.record_download(cmd, staging); });
  return write_cache_file(file, {static_cast<const uint8_t*>(staging.data()), bytes});
}

namespace {
constexpr const char* kLightingPrefix = "lighting_";
}

std::filesystem::path lighting_cache_file(const std::string& part, const std::string& key) {
  // The key holds code_identity(): without it nothing that code made can be told apart.
  const std::filesystem::path dir = cache_dir();
  if (dir.empty() || key.empty() || code_identity().empty()) return {};
  return dir / (kLightingPrefix + part + "_" + key + ".bin");
}

void store_lighting_texture(gpu::Context& ctx, const gpu::Texture& texture,
                            const std::filesystem::path& file, size_t bytes) {
  if (store_cached_texture(ctx, texture, file, bytes))
    prune_cache(file.parent_path(), kLightingPrefix, kLightingCacheBytes);
}

}  // namespace nephele
