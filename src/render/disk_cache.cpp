#include "render/disk_cache.h"

#include <dlfcn.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
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

uint64_t fnv1a64(const std::string& text, uint64_t hash) {
  return fnv1a64(bytes_of(text.data(), text.size()), hash);
}

std::filesystem::path cache_dir() {
  if (const char* dir = std::getenv("NEPHELE_CACHE_DIR")) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return std::filesystem::path(xdg) / "nephele";
  if (const char* home = std::getenv("HOME"); home && *home)
    return std::filesystem::path(home) / ".cache" / "nephele";
  return {};
}

std::string file_identity(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return path + "|missing";
  return path + "|" + std::to_string(st.st_size) + "|" + std::to_string(st.st_mtim.tv_sec) + "." +
         std::to_string(st.st_mtim.tv_nsec);
}

const std::string& code_identity() {
  static const std::string identity = [] {
    Dl_info info{};
    if (dladdr(reinterpret_cast<const void*>(&cache_dir), &info) == 0 || !info.dli_fname)
      return std::string();
    // The program itself is named as it was started (relative, or found on the PATH): its
    // file is /proc/self/exe.
    std::error_code ec;
    std::filesystem::path file = info.dli_fname;
    if (!file.is_absolute()) file = std::filesystem::read_symlink("/proc/self/exe", ec);
    struct stat st {};
    if (ec || file.empty() || ::stat(file.c_str(), &st) != 0) return std::string();
    return file_identity(file.string());
  }();
  return identity;
}

std::optional<std::vector<uint8_t>> read_cache_file(const std::filesystem::path& file,
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
  std::filesystem::last_write_time(file, std::filesystem::file_time_type::clock::now(), ec);
  return texels;
}

bool write_cache_file(const std::filesystem::path& file, std::span<const uint8_t> texels) {
  std::error_code ec;
  std::filesystem::create_directories(file.parent_path(), ec);
  if (ec) return false;
  // Unique to this process and call: two that make the same texture at once (two processes, or
  // two renderers of one) each write their own.
  static std::atomic<uint64_t> writes{0};
  std::filesystem::path temporary = file;
  temporary += ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(writes++);
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

void prune_cache(const std::filesystem::path& dir, const std::string& prefix, uint64_t max_bytes) {
  struct Entry {
    std::filesystem::file_time_type used;
    uint64_t bytes;
    std::filesystem::path file;
  };
  std::vector<Entry> entries;
  uint64_t total = 0;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(prefix, 0) != 0 || name.find(".tmp") != std::string::npos) continue;
    const uint64_t bytes = e.file_size(ec);
    if (ec) continue;
    entries.push_back({e.last_write_time(ec), bytes, e.path()});
    total += bytes;
  }
  std::sort(entries.begin(), entries.end(),
            [](const Entry& a, const Entry& b) { return a.used < b.used; });
  for (const Entry& e : entries) {
    if (total <= max_bytes) break;
    if (std::filesystem::remove(e.file, ec)) total -= e.bytes;
  }
}

}  // namespace nephele
