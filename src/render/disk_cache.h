// nephele's disk cache: textures that take seconds to make on a CPU device (lavapipe) and a few
// ms to read back, kept between processes (the base noise, the clouds' lighting). A file is
// named by everything that makes its texels (the code that made them, the device, the inputs),
// so a new build or another device makes its own; a file that does not check out (its header,
// its length, its checksum) is ignored and made anew. docs/noise-clouds.md, docs/cloud-lighting.md.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace nephele {

// The most the clouds' lighting (files named lighting_*, texture_cache.h) may take of the cache:
// about 50 stills' (a light volume of 3.3 MB and a diffusion field of 16.8 MB each).
constexpr uint64_t kLightingCacheBytes = 1ull << 30;

// FNV-1a, 64 bits, continuing from `hash`.
uint64_t fnv1a64(std::span<const uint8_t> bytes, uint64_t hash = 0xcbf29ce484222325ull);
uint64_t fnv1a64(const std::string& text, uint64_t hash = 0xcbf29ce484222325ull);

// The cache's folder: $NEPHELE_CACHE_DIR, else $XDG_CACHE_HOME/nephele, else
// $HOME/.cache/nephele. Empty (no cache) when NEPHELE_CACHE_DIR is set to "" or none is known.
std::filesystem::path cache_dir();

// What identifies the code that makes a cached texture beyond its shader: the file this library
// was loaded from (the program, or libnephele.so), its size and its time of modification, so
// that a rebuild (other shaders, other constants in C++) makes its own files. Empty when that
// file cannot be found: then nothing is cached that depends on it.
const std::string& code_identity();

// What identifies an input file's contents: its path, size and time of modification ("missing"
// when it cannot be read), for the name of a texture made from it.
std::string file_identity(const std::string& path);

// The `bytes` texels stored in `file`, or nothing when it is missing, short, long or damaged.
std::optional<std::vector<uint8_t>> read_cache_file(const std::filesystem::path& file,
                                                    size_t bytes);

// Stores `texels` in `file` (its folder made when missing) through a temporary file renamed
// over it, so that a reader never sees half a file; false when it could not be written.
bool write_cache_file(const std::filesystem::path& file, std::span<const uint8_t> texels);

// Removes the least recently used files of `dir` whose names start with `prefix` until they
// take at most `max_bytes` together (a file read back counts as used: read_cache_file marks it).
void prune_cache(const std::filesystem::path& dir, const std::string& prefix, uint64_t max_bytes);

}  // namespace nephele
