#include "render/modules/noise/noise_cache.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <system_error>

namespace nephele {

namespace {
constexpr char kMagic[8] = {'N', 'E', 'P', 'H', 'N', 'O', 'I', '1'};
// The file: kMagic, the texels' length and their checksum (little-endian uint64 each), the
// texels.
constexpr size_t kHeader = sizeof(kMagic) + 2 * sizeof(uint64_t);

std::span<const uint8_t> bytes_of(const void* data, size_t size) {
  return {static_cast<const uint8_t*>(data), size};
}
}  // namespace

uint64_t fnv1a64(std::span<const uint8_t> bytes, uint64_t hash) {
  for (uint8_t b : bytes) {
    hash ^= b;
    hash *= 0x100000001b3ull;
  }
  return hash;
}

std::filesystem::path noise_cache_dir() {
  if (const char* dir = std::getenv("NEPHELE_CACHE_DIR")) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return std::filesystem::path(xdg) / "nephele";
  if (const char* home = std::getenv("HOME"); home && *home)
    return std::filesystem::path(home) / ".cache" / "nephele";
  return {};
}

std::string noise_cache_name(std::span<const uint32_t> spirv, const std::string& device,
                             uint32_t seed) {
  uint64_t h = fnv1a64(bytes_of(spirv.data(), spirv.size_bytes()));
  h = fnv1a64(bytes_of(device.data(), device.size()), h);
  h = fnv1a64(bytes_of(&seed, sizeof(seed)), h);
  char name[48];
  std::snprintf(name, sizeof(name), "base_noise_%016llx.bin", static_cast<unsigned long long>(h));
  return name;
}

std::optional<std::vector<uint8_t>> read_noise_cache(const std::filesystem::path& file,
                                                     size_t bytes) {
  std::error_code ec;
  if (std::filesystem::file_size(file, ec) != kHeader + bytes || ec) return std::nullopt;
  std::ifstream in(file, std::ios::binary);
  char magic[sizeof(kMagic)];
  uint64_t length = 0, checksum = 0;
  in.read(magic, sizeof(magic));
  in.read(reinterpret_cast<char*>(&length), sizeof(length));
  in.read(reinterpret_cast<char*>(&checksum), sizeof(checksum));
  if (!in || std::memcmp(magic, kMagic, sizeof(kMagic)) != 0 || length != bytes)
    return std::nullopt;
  std::vector<uint8_t> texels(bytes);
  in.read(reinterpret_cast<char*>(texels.data()), std::streamsize(bytes));
  if (!in || fnv1a64(texels) != checksum) return std::nullopt;
  return texels;
}

bool write_noise_cache(const std::filesystem::path& file, std::span<const uint8_t> texels) {
  std::error_code ec;
  std::filesystem::create_directories(file.parent_path(), ec);
  if (ec) return false;
  // Unique to this process: two that make the same texture at once each write their own.
  std::filesystem::path temporary = file;
  temporary += ".tmp" + std::to_string(::getpid());
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    const uint64_t length = texels.size(), checksum = fnv1a64(texels);
    out.write(kMagic, sizeof(kMagic));
    out.write(reinterpret_cast<const char*>(&length), sizeof(length));
    out.write(reinterpret_cast<const char*>(&checksum), sizeof(checksum));
    out.write(reinterpret_cast<const char*>(texels.data()), std::streamsize(texels.size()));
    if (!out.flush()) {
      std::filesystem::remove(temporary, ec);
      return false;
    }
  }
  std::filesystem::rename(temporary, file, ec);
  if (!ec) return true;
  std::filesystem::remove(temporary, ec);
  return false;
}

}  // namespace nephele
