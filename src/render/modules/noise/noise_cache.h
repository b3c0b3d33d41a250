// A disk cache of the base noise texture (128^3 RGBA8, 8 MiB): on lavapipe it takes 1.2-2.4 s
// to make, every process that draws noise clouds, where reading it back takes a few ms. Its
// file is named by everything that makes the texels (the shader's SPIR-V, the device, the
// seed), so a new build or another device makes its own; a file that does not check out
// (its header, its length, its checksum) is ignored and made anew. docs/noise-clouds.md.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace nephele {

// FNV-1a, 64 bits, continuing from `hash`.
uint64_t fnv1a64(std::span<const uint8_t> bytes, uint64_t hash = 0xcbf29ce484222325ull);

// The cache's folder: $NEPHELE_CACHE_DIR, else $XDG_CACHE_HOME/nephele, else
// $HOME/.cache/nephele. Empty (no cache) when NEPHELE_CACHE_DIR is set to "" or none is known.
std::filesystem::path noise_cache_dir();

// The file name of a texture made by `spirv` on `device` for `seed`.
std::string noise_cache_name(std::span<const uint32_t> spirv, const std::string& device,
                             uint32_t seed);

// The `bytes` texels stored in `file`, or nothing when it is missing, short, long or damaged.
std::optional<std::vector<uint8_t>> read_noise_cache(const std::filesystem::path& file,
                                                     size_t bytes);

// Stores `texels` in `file` (its folder made when missing) through a temporary file renamed
// over it, so that a reader never sees half a file; false when it could not be written.
bool write_noise_cache(const std::filesystem::path& file, std::span<const uint8_t> texels);

}  // namespace nephele
