// A device texture kept in nephele's disk cache (disk_cache.h): read into the texture, or
// written from it, whole, through a staging buffer and a wait on the device.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

#include "gpu/context.h"
#include "gpu/resources.h"

namespace nephele {

// Fills `texture` (level 0, `bytes` of tightly packed texels) from `file`: false, the texture
// untouched, when the file is missing or does not check out.
bool load_cached_texture(gpu::Context& ctx, const gpu::Texture& texture,
                         const std::filesystem::path& file, size_t bytes);

// Writes level 0 of `texture` (`bytes`) to `file`. A cache that cannot be written (a read-only
// home) only costs the next process the time: false, and nothing else.
bool store_cached_texture(gpu::Context& ctx, const gpu::Texture& texture,
                          const std::filesystem::path& file, size_t bytes);

// A still's lighting in the cache: `part` ("volume", "diffusion") of the lighting named `key`
// (FramePlan::lighting_cache_key), in cache_dir(); empty when there is no cache, no key or no
// code_identity().
std::filesystem::path lighting_cache_file(const std::string& part, const std::string& key);

// Writes `texture` to `file` as store_cached_texture does, then keeps the lighting's files
// within kLightingCacheBytes (prune_cache, least recently used first).
void store_lighting_texture(gpu::Context& ctx, const gpu::Texture& texture,
                            const std::filesystem::path& file, size_t bytes);

}  // namespace nephele
