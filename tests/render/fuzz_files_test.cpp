// Seeded fuzz tests of the files a scene reads (issue 40): OpenVDB (a stream as `nephele
// make-cloud` writes it, and a file with grid offsets), NanoVDB, OBJ (meshes to voxelize,
// terrain meshes), PNG (weather map, 16-bit terrain heights, albedo map), EXR (terrain heights,
// weather map) and GeoTIFF (terrain heights). Each case mutates a small valid file (bytes
// flipped, the file cut short, a header field inflated; an OBJ's numbers, faces and tokens
// replaced) and feeds it to the loader the renderer uses. The contract, for every case:
//   - either it is refused: an InputError of one line (not empty, at most kMaxErrorLineChars)
//     naming the file; a `nephele` process exits with status 2, prints exactly one line on
//     stderr starting "nephele: error: " and writes nothing;
//   - or it is accepted, and what it gives is finite (voxel densities and distances, heights,
//     albedo, a render's pixels);
//   - never a crash, a hang, another exception type or another exit status;
//   - within bounded memory: the cases run in child processes whose resident memory a watchdog
//     here polls, killing a child above kChildRssLimitBytes (the case fails); under
//     AddressSanitizer the children also run with ASan's own hard_rss_limit_mb. A case that
//     raises its process's peak by more than kCaseGrowthBytes fails too.
//
// Every case comes from std::mt19937 seeded with kSeed, its format's stream and its index, so
// each case regenerates alone: NEPHELE_FUZZ_FILES_CASE=FORMAT:INDEX runs that one case only
// (failures print the command). The files mutated are written under
// NEPHELE_TEST_OUTPUT_DIR/fuzz_files/ (the valid ones in base/); a failing case's file is kept.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <glm/gtc/packing.hpp>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "image/input_images.h"
#include "nephele/error.h"
#include "nephele/image.h"
#include "nephele/scene_io.h"
#include "support/fuzz_support.h"
#include "support/terrain_files.h"
#include "support/vdb_files.h"
#include "terrain/heightfield.h"
#include "voxel/voxel_grid.h"

namespace fs = std::filesystem;

namespace nephele {
namespace {

using test::demangled_type;
using test::describe_death;
using test::Failure;
using test::kAsan;
using test::printable;
using test::reset_peak_memory;

// --- budget and contract ----------------------------------------------------------------------

constexpr uint32_t kSeed = 20260627;
constexpr uint32_t kProcessStream = 9000000;  // the process cases' seeds: kSeed + this + index
// Resident memory a child may reach (the watchdog kills it above), and ASan's own limit for
// it: ASan's shadow memory and its quarantine of freed blocks (256 MB) come on top of the
// program's own.
constexpr size_t kChildRssLimitBytes = size_t(kAsan ? 2048 : 1536) << 20;
constexpr int kAsanHardRssLimitMb = 2048;
// How much one in-process case may raise its child's peak resident memory.
constexpr size_t kCaseGrowthBytes = size_t(kAsan ? 768 : 384) << 20;
constexpr int kCaseTimeoutS = kAsan ? 120 : 20;        // one in-process case
constexpr int kProcessTimeoutS = kAsan ? 300 : 60;     // one `nephele` process
constexpr int kChildStartTimeoutS = kAsan ? 120 : 30;  // a child up to its first case
constexpr int kWatchdogPollMs = 20;
constexpr size_t kMaxErrorLineChars = 1000;  // as apps/cli/main.cpp caps a printed line
const std::string kErrorPrefix = "nephele: error: ";
const char* const kCaseVariable = "NEPHELE_FUZZ_FILES_CASE";
const char* const kChildVariable = "NEPHELE_FUZZ_FILES_CHILD";  // "FIRST_CASE FD"
const char* const kDirVariable = "NEPHELE_FUZZ_FILES_DIR";      // the parent's fuzz_dir()
// Set for the watchdog's own test: the child's memory grows until it is stopped.
const char* const kRunawayVariable = "NEPHELE_FUZZ_FILES_RUNAWAY";
const char* const kChildTest = "FuzzFiles.DISABLED_ChildRunsCases";

// What reads a format, and what its mutations know of its layout.
enum class Loader { kVoxelCloud, kMesh, kTerrain, kWeatherMap, kAlbedoMap };
enum class Syntax { kBinary, kPng, kExr, kTiff, kObj };

struct Format {
  const char* name;       // in messages and NEPHELE_FUZZ_FILES_CASE
  const char* extension;  // the loaders tell formats by it
  Loader loader;
  Syntax syntax;
  int cases;            // in-process cases
  uint32_t stream;      // the cases' seeds: kSeed + stream + index
  size_t header_bytes;  // where flips and cuts aim half the time: the header and first tables
};

// About 7 s on 2 cores in the Release build (about 2500 cases).
// clang-format off
const std::vector<Format> kFormats = {
    {"vdb-stream",   ".vdb",  Loader::kVoxelCloud, Syntax::kBinary, 330,       0, 1024},
    {"vdb-file",     ".vdb",  Loader::kVoxelCloud, Syntax::kBinary, 330,  100000, 1024},
    {"nvdb",         ".nvdb", Loader::kVoxelCloud, Syntax::kBinary,  150,  200000, 1024},
    {"obj-mesh",     ".obj",  Loader::kMesh,       Syntax::kObj,     240,  300000,    0},
    {"obj-terrain",  ".obj",  Loader::kTerrain,    Syntax::kObj,     180,  400000,    0},
    {"png-weather",  ".png",  Loader::kWeatherMap, Syntax::kPng,     210,  500000,  128},
    {"png-terrain",  ".png",  Loader::kTerrain,    Syntax::kPng,     210,  600000,  128},
    {"png-albedo",   ".png",  Loader::kAlbedoMap,  Syntax::kPng,     150,  700000,  128},
    {"exr-terrain",  ".exr",  Loader::kTerrain,    Syntax::kExr,     210,  800000,  512},
    {"exr-weather",  ".exr",  Loader::kWeatherMap, Syntax::kExr,     150,  900000,  512},
    {"tiff-terrain", ".tif",  Loader::kTerrain,    Syntax::kTiff,    210, 1000000,  512},
};
// clang-format on

const Format& format_named(const std::string& name) {
  for (const Format& f : kFormats)
    if (name == f.name) return f;
  throw std::invalid_argument("no fuzzed format '" + name + "'");
}

// --- small helpers ----------------------------------------------------------------------------

class Rng {
 public:
  explicit Rng(uint32_t seed) : engine_(seed) {}
  size_t below(size_t n) {
    return n == 0 ? 0 : std::uniform_int_distribution<size_t>(0, n - 1)(engine_);
  }
  bool chance(double p) { return std::uniform_real_distribution<double>(0.0, 1.0)(engine_) < p; }
  template <typename T>
  const T& pick(const std::vector<T>& items) {
    return items[below(items.size())];
  }
  uint32_t bits() { return engine_(); }

 private:
  std::mt19937 engine_;
};

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string hex(uint64_t value) {
  char text[24];
  std::snprintf(text, sizeof text, "0x%llx", static_cast<unsigned long long>(value));
  return text;
}

std::string tail(const std::string& text, size_t chars = 1500) {
  return printable(text.size() > chars ? "..." + text.substr(text.size() - chars) : text);
}

// A field of /proc/PID/status ("VmRSS:", "VmHWM:") in bytes; 0 when it cannot be read.
size_t status_bytes(const std::string& pid, const char* field) {
  std::ifstream status("/proc/" + pid + "/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind(field, 0) == 0)
      return size_t(std::stoull(line.substr(std::strlen(field)))) * 1024;
  return 0;
}

std::string mib(size_t bytes) {
  return std::to_string(bytes >> 20) + " MiB";
}

// The case NEPHELE_FUZZ_FILES_CASE names ("png-weather:17"), if any.
std::optional<std::pair<std::string, int>> only_case() {
  const char* value = std::getenv(kCaseVariable);
  if (!value || !*value) return std::nullopt;
  const std::string text = value;
  const size_t colon = text.find(':');
  if (colon == std::string::npos)
    throw std::invalid_argument(std::string(kCaseVariable) + "=FORMAT:INDEX");
  return std::pair{text.substr(0, colon), std::stoi(text.substr(colon + 1))};
}

std::string regenerate_hint(const std::string& format, int index, const std::string& test) {
  return std::string(kCaseVariable) + "=" + format + ":" + std::to_string(index) +
         " build/tests/nephele_tests --gtest_filter=FuzzFiles." + test;
}

// --- the valid files --------------------------------------------------------------------------

// A closed cube 600 m a side (z up), as a mesh to voxelize: 8 vertices, 12 triangles.
const char* const kCubeObj =
    "# cube\no cube\nv -300 -300 0\nv 300 -300 0\nv 300 300 0\nv -300 300 0\n"
    "v -300 -300 600\nv 300 -300 600\nv 300 300 600\nv -300 300 600\n"
    "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\n"
    "f 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";
// A pyramid 400 m high on a 2 km square (x east, y up, -z north), as a terrain mesh.
const char* const kPyramidObj =
    "v -1000 0 1000\nv 1000 0 1000\nv 1000 0 -1000\nv -1000 0 -1000\nv 200 400 -300\n"
    "vn 0 1 0\nvt 0.5 0.5\nf 1/1/1 2/1/1 5/1/1\nf 2 3 5\nf 3 4 5\nf 4 1 5\n";

// OpenVDB writes a random UUID into each file's header; a fixed one keeps the cases' bytes the
// same from run to run.
void fix_vdb_uuid(const std::string& path) {
  std::string bytes = read_file(path);
  const std::string uuid = "00000000-0000-4000-8000-000000000000";
  if (bytes.size() > 21 + uuid.size()) bytes.replace(21, uuid.size(), uuid);
  test::write_bytes(path, bytes);
}

// A w x h image of smooth values in [0, 1].
Image gradient(int w, int h) {
  Image image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      image.at(x, y) = glm::vec4(float(x) / float(w - 1), float(y) / float(h - 1),
                                 0.5f + 0.4f * std::sin(0.7f * float(x + y)), 1.0f);
  return image;
}

// Writes the valid file of every format into `dir` (named FORMAT + extension).
void write_base_files(const fs::path& dir) {
  fs::create_directories(dir);
  const auto path = [&](const char* format) {
    return (dir / (std::string(format) + format_named(format).extension)).string();
  };
  // As `nephele make-cloud --type cumulus --resolution 16 -o F` writes it: a stream.
  voxel::write_vdb(voxel::make_cloud(voxel::CloudPreset::Cumulus, 1, 16), path("vdb-stream"));
  fix_vdb_uuid(path("vdb-stream"));
  test::write_fog_balls_vdb(path("vdb-file"), {"temperature", "density"});
  fix_vdb_uuid(path("vdb-file"));
  test::write_fog_balls_nvdb(path("nvdb"), {"density"});
  test::write_bytes(path("obj-mesh"), kCubeObj);
  test::write_bytes(path("obj-terrain"), kPyramidObj);
  write_image(gradient(32, 32), path("png-weather"));
  std::vector<unsigned short> heights(32 * 32);
  for (size_t i = 0; i < heights.size(); ++i) heights[i] = (unsigned short)((i * 7919) % 65536);
  test::write_png16(path("png-terrain"), 32, 32, 1, heights);
  write_image(gradient(16, 16), path("png-albedo"));
  write_image(gradient(24, 24), path("exr-terrain"), 1.0f, ExrPixels::kFloat);
  write_image(gradient(32, 32), path("exr-weather"));
  std::vector<float> dem(24 * 24);
  for (size_t i = 0; i < dem.size(); ++i) dem[i] = 700.0f + float((i * 7919) % 1013);
  test::write_geotiff(path("tiff-terrain"), 24, 24, dem, 0.03, 0.0, 0.001, true, true);
}

// --- mutations --------------------------------------------------------------------------------

enum class Mutation { kAny, kFlip, kCut, kInflate };

// A field of a binary header: where it is, its width in bytes, its byte order and its name.
struct Field {
  size_t at;
  int bytes;  // 1, 2, 4 or 8
  bool big_endian;
  std::string name;
};

void put(std::string& bytes, const Field& f, uint64_t value) {
  for (int i = 0; i < f.bytes; ++i) {
    const int shift = 8 * (f.big_endian ? f.bytes - 1 - i : i);
    if (f.at + size_t(i) < bytes.size()) bytes[f.at + size_t(i)] = char((value >> shift) & 0xff);
  }
}

uint64_t get(const std::string& bytes, size_t at, int width, bool big_endian) {
  uint64_t value = 0;
  for (int i = 0; i < width && at + size_t(i) < bytes.size(); ++i) {
    const int shift = 8 * (big_endian ? width - 1 - i : i);
    value |= uint64_t(static_cast<unsigned char>(bytes[at + size_t(i)])) << shift;
  }
  return value;
}

// A value that a size, count or offset field should not hold, or only just may.
uint64_t inflated_value(Rng& rng, int width, uint64_t old) {
  static const std::vector<uint64_t> k8 = {0, 1, 3, 7, 8, 16, 32, 64, 128, 255};
  static const std::vector<uint64_t> k16 = {0, 1, 0x7fff, 0x8000, 0xffff, 8193, 16385};
  static const std::vector<uint64_t> k32 = {
      0,          1,          0xffffffff, 0x7fffffff, 0x80000000, 0x40000000, 0x10000000,
      0x01000000, 0x00100000, 0x10000,    0xffff,     8193,       16385,      4097};
  static const std::vector<uint64_t> k64 = {0,
                                            uint64_t(1) << 32,
                                            uint64_t(1) << 40,
                                            uint64_t(1) << 62,
                                            ~uint64_t(0),
                                            uint64_t(0x7fffffffffffffff),
                                            uint64_t(0x8000000000000000)};
  if (rng.chance(0.15)) return old + 1 + rng.below(64);  // just past what it was
  if (rng.chance(0.1)) return rng.bits();
  return width == 1   ? rng.pick(k8)
         : width == 2 ? rng.pick(k16)
         : width == 4 ? rng.pick(k32)
                      : rng.pick(k64);
}

uint32_t crc32_of(const std::string& bytes, size_t at, size_t n) {
  uint32_t crc = 0xffffffffu;
  for (size_t i = at; i < at + n && i < bytes.size(); ++i) {
    crc ^= static_cast<unsigned char>(bytes[i]);
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

// A PNG's fields: IHDR's size, depth, colour type and interlace, and every chunk's length.
// `crc_of` gets, for each field, where the chunk holding it starts (its length field).
std::vector<Field> png_fields(const std::string& bytes, std::vector<size_t>& chunk_of) {
  std::vector<Field> fields = {{16, 4, true, "IHDR width"},
                               {20, 4, true, "IHDR height"},
                               {24, 1, true, "IHDR depth"},
                               {25, 1, true, "IHDR colour type"},
                               {28, 1, true, "IHDR interlace"}};
  chunk_of.assign(fields.size(), 8);
  for (size_t at = 8; at + 8 <= bytes.size();) {
    const uint64_t length = get(bytes, at, 4, true);
    fields.push_back(
        {at, 4, true, "length of chunk " + bytes.substr(at + 4, 4) + " at " + std::to_string(at)});
    chunk_of.push_back(at);
    if (length > bytes.size()) break;
    at += 12 + length;
  }
  return fields;
}

// An EXR's fields: each header attribute's size, its box2i and int values, each channel's
// pixel type and sampling, and the first offsets of the chunk table after the header.
std::vector<Field> exr_fields(const std::string& bytes) {
  std::vector<Field> fields = {{4, 4, false, "version and flags"}};
  size_t at = 8;
  while (at < bytes.size() && bytes[at] != '\0') {
    const size_t name_end = bytes.find('\0', at);
    if (name_end == std::string::npos) return fields;
    const size_t type_end = bytes.find('\0', name_end + 1);
    if (type_end == std::string::npos || type_end + 5 > bytes.size()) return fields;
    const std::string name = bytes.substr(at, name_end - at);
    const std::string type = bytes.substr(name_end + 1, type_end - name_end - 1);
    const size_t size_at = type_end + 1, value_at = size_at + 4;
    const uint64_t size = get(bytes, size_at, 4, false);
    fields.push_back({size_at, 4, false, "size of attribute " + name});
    if (type == "box2i" || type == "int" || type == "tiledesc")
      for (size_t i = 0; i + 4 <= size; i += 4)
        fields.push_back({value_at + i, 4, false, name + " int " + std::to_string(i / 4)});
    if (type == "compression" || type == "lineOrder") fields.push_back({value_at, 1, false, name});
    if (type == "chlist")
      for (size_t c = value_at; c < value_at + size && bytes[c] != '\0';) {
        const size_t end = bytes.find('\0', c);
        if (end == std::string::npos) break;
        fields.push_back({end + 1, 4, false, "pixel type of channel " + bytes.substr(c, end - c)});
        fields.push_back({end + 9, 4, false, "x sampling of channel " + bytes.substr(c, end - c)});
        c = end + 17;
      }
    at = value_at + size;
  }
  for (int i = 0; i < 4; ++i)
    fields.push_back({at + 1 + 8 * size_t(i), 8, false, "chunk offset " + std::to_string(i)});
  return fields;
}

// A classic little-endian TIFF's fields: its first IFD's offset and entry count, and each
// entry's type, count and value (or offset).
std::vector<Field> tiff_fields(const std::string& bytes) {
  std::vector<Field> fields = {{4, 4, false, "first IFD offset"}};
  const size_t ifd = get(bytes, 4, 4, false);
  if (bytes.compare(0, 2, "II") != 0 || ifd + 2 > bytes.size()) return fields;
  fields.push_back({ifd, 2, false, "IFD entry count"});
  const size_t entries = get(bytes, ifd, 2, false);
  for (size_t i = 0; i < entries && ifd + 2 + 12 * (i + 1) <= bytes.size(); ++i) {
    const size_t at = ifd + 2 + 12 * i;
    const std::string tag = "tag " + std::to_string(get(bytes, at, 2, false));
    fields.push_back({at + 2, 2, false, tag + " type"});
    fields.push_back({at + 4, 4, false, tag + " count"});
    fields.push_back({at + 8, 4, false, tag + " value"});
  }
  return fields;
}

// A mutated file and what was done to it.
struct Mutant {
  std::string bytes, how;
};

// A position: half the time in the header (its first `header_bytes`), else anywhere.
size_t position(Rng& rng, size_t size, size_t header_bytes) {
  if (header_bytes > 0 && rng.chance(0.5)) return rng.below(std::min(size, header_bytes));
  return rng.below(size);
}

Mutant flip(const std::string& base, Rng& rng, size_t header_bytes) {
  Mutant m{base, "flipped"};
  const int flips = 1 + int(rng.below(3));
  for (int i = 0; i < flips; ++i) {
    const size_t at = position(rng, base.size(), header_bytes);
    const unsigned char mask = static_cast<unsigned char>(1 + rng.below(255));
    m.bytes[at] = char(m.bytes[at] ^ mask);
    m.how += std::string(i ? "," : "") + " byte " + std::to_string(at) + " ^ " + hex(mask);
  }
  return m;
}

Mutant cut(const std::string& base, Rng& rng, size_t header_bytes) {
  const size_t keep = position(rng, base.size(), header_bytes);
  return {base.substr(0, keep),
          "cut to " + std::to_string(keep) + " of " + std::to_string(base.size()) + " bytes"};
}

Mutant inflate(const Format& f, const std::string& base, Rng& rng) {
  Mutant m{base, ""};
  std::vector<Field> fields;
  std::vector<size_t> png_chunk;
  if (f.syntax == Syntax::kPng) fields = png_fields(base, png_chunk);
  if (f.syntax == Syntax::kExr) fields = exr_fields(base);
  if (f.syntax == Syntax::kTiff) fields = tiff_fields(base);
  size_t chosen = 0;
  const bool any_word = fields.empty() || rng.chance(0.2);
  if (any_word) {  // any word of the header
    const int width = rng.chance(0.6) ? 4 : 8;
    size_t at = rng.below(std::min(base.size(), std::max<size_t>(f.header_bytes, 64)));
    if (rng.chance(0.75)) at &= ~size_t(3);
    fields = {{at, width, f.syntax == Syntax::kPng,
               std::to_string(width) + "-byte word at " + std::to_string(at)}};
  } else {
    chosen = rng.below(fields.size());
  }
  const Field& field = fields[chosen];
  const uint64_t old = get(base, field.at, field.bytes, field.big_endian);
  const uint64_t mask = field.bytes == 8 ? ~uint64_t(0) : (uint64_t(1) << (8 * field.bytes)) - 1;
  uint64_t value = inflated_value(rng, field.bytes, old) & mask;
  while (value == old) value = inflated_value(rng, field.bytes, old) & mask;  // a change
  put(m.bytes, field, value);
  m.how = field.name + " " + hex(old) + " -> " + hex(value);
  // The chunk's CRC made right again most of the time, so that what follows it is read too.
  if (f.syntax == Syntax::kPng && !any_word && rng.chance(0.7)) {
    const size_t chunk = png_chunk[chosen];
    const uint64_t length = get(m.bytes, chunk, 4, true);
    if (chunk + 12 + length <= m.bytes.size()) {
      put(m.bytes, {chunk + 8 + length, 4, true, ""}, crc32_of(m.bytes, chunk + 4, 4 + length));
      m.how += " (CRC fixed)";
    }
  }
  return m;
}

// --- OBJ mutations ----------------------------------------------------------------------------

// clang-format off
const std::vector<std::string> kBadNumbers = {
    "nan", "-nan", "inf", "-inf", "1e39", "-1e39", "1e308", "1e309", "abc", "0x10", "1e-320",
    "", "+", "-", ".", "1.5.5", "1e", "3e38", "-3e38", "99999999999999999999", "1,5", "0"};
const std::vector<std::string> kBadIndices = {
    "0", "-1", "-9", "9", "99999", "-99999", "2147483647", "2147483648", "-2147483649",
    "4294967296", "1/2/3", "1//", "//1", "1/", "a", "nan", "1.5", "", "1/0/0", "1/-5"};
const std::vector<std::string> kKeywords = {
    "v", "vn", "vt", "f", "l", "p", "o", "g", "s", "usemtl", "mtllib", "#", "vp", "curv", "xyz", ""};
// clang-format on

std::vector<std::string> split(const std::string& text, char by) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, by)) parts.push_back(part);
  return parts;
}

std::string join(const std::vector<std::string>& parts, const std::string& by) {
  std::string text;
  for (size_t i = 0; i < parts.size(); ++i) text += (i ? by : "") + parts[i];
  return text;
}

// One edit of an OBJ text's lines; returns what it did.
std::string edit_obj(std::vector<std::string>& lines, Rng& rng) {
  if (lines.empty()) lines.push_back("");
  const size_t n = rng.below(lines.size());
  std::vector<std::string> words = split(lines[n], ' ');
  const std::string line = "line " + std::to_string(n + 1);
  std::string did;
  switch (rng.below(9)) {
    case 0:
    case 1: {  // a number or an index replaced
      if (words.size() < 2) break;
      const size_t w = 1 + rng.below(words.size() - 1);
      const std::string value = rng.pick(words[0] == "f" ? kBadIndices : kBadNumbers);
      did = line + " word " + std::to_string(w) + " '" + words[w] + "' -> '" + value + "'";
      words[w] = value;
      break;
    }
    case 2: {  // a word dropped
      if (words.empty()) break;
      const size_t w = rng.below(words.size());
      did = line + " word " + std::to_string(w) + " '" + words[w] + "' dropped";
      words.erase(words.begin() + ptrdiff_t(w));
      break;
    }
    case 3: {  // a word added
      const std::string value = rng.pick(rng.chance(0.5) ? kBadIndices : kBadNumbers);
      words.push_back(value);
      did = line + " gains '" + value + "'";
      break;
    }
    case 4: {  // another keyword
      const std::string keyword = rng.pick(kKeywords);
      did = line + " keyword '" + (words.empty() ? "" : words[0]) + "' -> '" + keyword + "'";
      if (words.empty())
        words.push_back(keyword);
      else
        words[0] = keyword;
      break;
    }
    case 5: {  // a line dropped or repeated
      if (rng.chance(0.5)) {
        lines.erase(lines.begin() + ptrdiff_t(n));
        return line + " dropped";
      }
      const size_t times = 1 + rng.below(rng.chance(0.2) ? 2000 : 3);
      lines.insert(lines.begin() + ptrdiff_t(n), times, lines[n]);
      return line + " repeated " + std::to_string(times) + " times";
    }
    case 6: {  // a face of many corners, or of none
      const size_t corners = rng.chance(0.5) ? rng.below(3) : 3 + rng.below(5000);
      std::string face = "f";
      for (size_t i = 0; i < corners; ++i) face += " " + std::to_string(1 + i % 5);
      lines.insert(lines.begin() + ptrdiff_t(n), face);
      return "a face of " + std::to_string(corners) + " corners before " + line;
    }
    case 7: {  // a long word
      const size_t length = 1 + rng.below(200000);
      const std::string digits(length, rng.chance(0.5) ? '9' : '0');
      words.push_back(rng.chance(0.5) ? digits : "1." + digits);
      did = line + " gains a number of " + std::to_string(length) + " digits";
      break;
    }
    default: {  // bytes that are not text
      std::string noise;
      const size_t length = 1 + rng.below(8);
      for (size_t i = 0; i < length; ++i)
        noise += char(rng.pick(std::vector<int>{0, 1, 9, 13, 0x7f, 0x80, 0xc3, 0xff, '\\'}));
      const size_t at = rng.below(lines[n].size() + 1);
      lines[n].insert(at, noise);
      return line + " gains bytes '" + printable(noise) + "' at " + std::to_string(at);
    }
  }
  lines[n] = join(words, " ");
  return did.empty() ? line + " unchanged" : did;
}

Mutant mutate_obj(const std::string& base, Rng& rng, Mutation kind) {
  if (kind == Mutation::kCut || (kind == Mutation::kAny && rng.chance(0.15)))
    return cut(base, rng, 0);
  if (kind == Mutation::kFlip || (kind == Mutation::kAny && rng.chance(0.1)))
    return flip(base, rng, 0);
  std::vector<std::string> lines = split(base, '\n');
  Mutant m{"", ""};
  const int edits = 1 + int(rng.below(3));
  for (int i = 0; i < edits; ++i) m.how += (i ? "; " : "") + edit_obj(lines, rng);
  m.bytes = join(lines, "\n") + (rng.chance(0.8) ? "\n" : "");
  return m;
}

Mutant mutate(const Format& f, const std::string& base, Rng& rng, Mutation kind = Mutation::kAny) {
  if (f.syntax == Syntax::kObj) return mutate_obj(base, rng, kind);
  if (kind == Mutation::kAny) {
    const size_t roll = rng.below(100);
    kind = roll < 40 ? Mutation::kFlip : roll < 65 ? Mutation::kCut : Mutation::kInflate;
  }
  if (kind == Mutation::kFlip) return flip(base, rng, f.header_bytes);
  if (kind == Mutation::kCut) return cut(base, rng, f.header_bytes);
  return inflate(f, base, rng);
}

// --- the loaders, in-process ------------------------------------------------------------------

struct Verdict {
  enum Kind { kAccepted, kRefused, kBroken } kind = kAccepted;
  std::string symptom, detail;
};

Verdict broken(const std::string& symptom, const std::string& detail = "") {
  return {Verdict::kBroken, symptom, detail};
}

bool all_finite(const std::vector<float>& values, size_t& first_bad) {
  for (size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i])) {
      first_bad = i;
      return false;
    }
  return true;
}

Verdict check_voxels(const voxel::VoxelGrid& g) {
  const glm::ivec3 d = g.dims;
  if (d.x < 1 || d.y < 1 || d.z < 1 || d.x > voxel::kMaxGridDim || d.y > voxel::kMaxGridDim ||
      d.z > voxel::kMaxGridDim)
    return broken("accepted a grid of impossible dimensions",
                  std::to_string(d.x) + " x " + std::to_string(d.y) + " x " + std::to_string(d.z));
  if (g.density.size() != size_t(d.x) * size_t(d.y) * size_t(d.z))
    return broken("accepted a grid whose density does not match its dimensions");
  if (!g.sdf_m.empty() && g.sdf_m.size() != g.density.size())
    return broken("accepted a grid whose distances do not match its dimensions");
  size_t bad = 0;
  if (!all_finite(g.density, bad))
    return broken("non-finite density", "voxel " + std::to_string(bad));
  if (!all_finite(g.sdf_m, bad))
    return broken("non-finite signed distance", "voxel " + std::to_string(bad));
  for (float v : g.density)
    if (v < 0.0f || v > 1.0f) return broken("density outside [0, 1]", std::to_string(v));
  if (!std::isfinite(g.voxel_m) || !(g.voxel_m > 0.0f))
    return broken("voxel size not finite and positive");
  return {};
}

// A scene that reads `path` as `loader` does, checked as the renderer checks it.
Scene scene_for(Loader loader, const std::string& path) {
  Scene s;  // at (0 N, 0 E): the GeoTIFF's north-west corner is at (0.03 N, 0 E)
  if (loader == Loader::kTerrain) {
    s.terrain.file = path;
    s.terrain.resolution = 64;  // an OBJ's raster
  }
  if (loader == Loader::kWeatherMap) s.clouds.weather_map = path;
  if (loader == Loader::kAlbedoMap) {
    s.terrain.preset = "mountains";
    s.terrain.albedo_map = path;
  }
  return s;
}

Verdict load(const Format& f, const std::string& path) {
  switch (f.loader) {
    case Loader::kVoxelCloud:
      return check_voxels(voxel::load_voxel_cloud(path, 16));
    case Loader::kMesh:
      return check_voxels(voxel::voxelize_mesh(path, 16));
    case Loader::kTerrain: {
      const Scene s = scene_for(f.loader, path);
      validate_scene(s);
      const terrain::Heightfield h = terrain::load_heightfield(s);
      if (h.width < 2 || h.height < 2 || h.height_m.size() != size_t(h.width) * size_t(h.height))
        return broken("accepted a heightfield of impossible size",
                      std::to_string(h.width) + " x " + std::to_string(h.height));
      size_t bad = 0;
      if (!all_finite(h.height_m, bad))
        return broken("non-finite height", "point " + std::to_string(bad));
      if (!std::isfinite(h.extent_m.x + h.extent_m.y + h.center_m.x + h.center_m.y))
        return broken("non-finite extent or centre");
      return {};
    }
    case Loader::kWeatherMap: {
      validate_scene(scene_for(f.loader, path));
      const Rgba8Image map = read_weather_map(path);
      if (map.width < 1 || map.height < 1 || map.width > kMaxWeatherMapSide ||
          map.height > kMaxWeatherMapSide ||
          map.texels.size() != size_t(map.width) * size_t(map.height) * 4)
        return broken("accepted a weather map of impossible size",
                      std::to_string(map.width) + " x " + std::to_string(map.height));
      return {};
    }
    case Loader::kAlbedoMap: {
      validate_scene(scene_for(f.loader, path));
      const HalfRgbaImage map = read_albedo_map(path);
      if (map.width < 1 || map.height < 1 || map.width > kMaxAlbedoMapSide ||
          map.height > kMaxAlbedoMapSide ||
          map.halfs.size() != size_t(map.width) * size_t(map.height) * 4)
        return broken("accepted an albedo map of impossible size",
                      std::to_string(map.width) + " x " + std::to_string(map.height));
      for (uint16_t half : map.halfs) {
        const float v = glm::unpackHalf1x16(half);
        if (!(v >= 0.0f && v <= 1.0f)) return broken("albedo outside [0, 1]", std::to_string(v));
      }
      return {};
    }
  }
  return broken("no loader");
}

// Why an InputError's message breaks the one-line rule ("" when it keeps it).
std::string message_problem(const std::string& message, const std::string& file_name) {
  if (message.empty()) return "error message is empty";
  if (message.find_first_of(std::string("\n\r\0", 3)) != std::string::npos)
    return "error message spans several lines";
  if (kErrorPrefix.size() + message.size() > kMaxErrorLineChars)
    return "error line is longer than " + std::to_string(kMaxErrorLineChars) + " characters";
  if (message.find(file_name) == std::string::npos) return "error message does not name the file";
  return "";
}

Verdict check_case(const Format& f, const std::string& path) {
  try {
    return load(f, path);
  } catch (const InputError& e) {
    const std::string why = message_problem(e.what(), fs::path(path).filename().string());
    if (!why.empty()) return broken("refused, but " + why, e.what());
    return {Verdict::kRefused, "", ""};
  } catch (const std::exception& e) {
    return broken("threw " + demangled_type(e), e.what());
  } catch (...) {
    return broken("threw something other than an exception");
  }
}

// --- cases and their children -----------------------------------------------------------------

struct CaseId {
  size_t format;
  int index;
};

std::vector<CaseId> in_process_cases() {
  std::vector<CaseId> cases;
  const auto only = only_case();
  for (size_t f = 0; f < kFormats.size(); ++f)
    for (int i = 0; i < kFormats[f].cases; ++i)
      if (!only || (only->first == kFormats[f].name && only->second == i)) cases.push_back({f, i});
  if (only && cases.empty()) {
    format_named(only->first);  // throws for an unknown format
    cases.push_back({size_t(&format_named(only->first) - kFormats.data()), only->second});
  }
  return cases;
}

// This test's folder: NEPHELE_TEST_OUTPUT_DIR/fuzz_files/TEST (ctest runs the tests at once),
// its child's from kDirVariable.
fs::path& fuzz_dir() {
  static fs::path dir;
  return dir;
}

std::string base_bytes(const Format& f) {
  return read_file(fuzz_dir() / "base" / (std::string(f.name) + f.extension));
}

std::string case_path(const Format& f, int index) {
  return (fuzz_dir() / "cases" / (std::string(f.name) + "-" + std::to_string(index) + f.extension))
      .string();
}

Mutant make_case(const Format& f, int index) {
  Rng rng(kSeed + f.stream + uint32_t(index));
  return mutate(f, base_bytes(f), rng);
}

void write_line(int fd, std::string line) {
  for (char& c : line)
    if (c == '\n' || c == '\r') c = '|';
  test::write_all(fd, line + '\n');
}

// Grows by 64 MiB, touched, every few milliseconds, up to 6 GiB (a watchdog that failed would
// still end it) and then waits: what a runaway case does.
[[noreturn]] void run_away(int fd, size_t first) {
  write_line(fd, "start " + std::to_string(first));
  std::vector<std::unique_ptr<char[]>> blocks;
  for (int i = 0; i < 96; ++i) {
    blocks.emplace_back(new char[size_t(64) << 20]);
    std::memset(blocks.back().get(), i + 1, size_t(64) << 20);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  std::this_thread::sleep_for(std::chrono::seconds(kCaseTimeoutS * 2));
  std::_Exit(0);
}

// The child's loop (FuzzFiles.DISABLED_ChildRunsCases): from case `first` on, writes
// "start I" before case I and "done I KIND\tSYMPTOM\tDETAIL" after it (KIND a, r or b).
void run_cases_as_child(size_t first, int fd) {
  if (!kAsan) {  // a single huge allocation fails at once rather than after the watchdog's poll
    const rlim_t limit = rlim_t(status_bytes("self", "VmSize:")) + (rlim_t(4) << 30);
    const rlimit as{limit, limit};
    setrlimit(RLIMIT_AS, &as);
  }
  if (std::getenv(kRunawayVariable)) run_away(fd, first);
  const std::vector<CaseId> cases = in_process_cases();
  // The loaders read each file by its name alone: a message must name it, and a long path
  // would be shortened in it.
  fs::current_path(fuzz_dir() / "cases");
  for (size_t i = first; i < cases.size(); ++i) {
    const Format& f = kFormats[cases[i].format];
    write_line(fd, "start " + std::to_string(i));
    const std::string path = case_path(f, cases[i].index);
    Verdict v;
    try {
      test::write_bytes(path, make_case(f, cases[i].index).bytes);
      reset_peak_memory();
      const size_t before = status_bytes("self", "VmRSS:");
      v = check_case(f, fs::path(path).filename().string());
      const size_t peak = status_bytes("self", "VmHWM:");
      if (v.kind != Verdict::kBroken && peak > before + kCaseGrowthBytes)
        v = broken("raised the peak resident memory by more than " + mib(kCaseGrowthBytes),
                   mib(peak - before) + " more at its peak");
    } catch (const std::exception& e) {
      v = broken("the case could not be made", e.what());
    }
    if (v.kind != Verdict::kBroken) fs::remove(path);
    const char kind = v.kind == Verdict::kAccepted ? 'a' : v.kind == Verdict::kRefused ? 'r' : 'b';
    write_line(fd, "done " + std::to_string(i) + " " + kind + "\t" + v.symptom + "\t" + v.detail);
  }
}

// Failures, grouped by symptom in the report.
std::string report(const std::vector<Failure>& failures) {
  return test::failure_report(failures, "case", 4);
}

// A child's stderr for a report: the first sanitizer report's line, then the end.
std::string sanitizer_report(const std::string& text) {
  std::string first;
  for (const std::string& line : split(text, '\n'))
    if (line.find("ERROR: ") != std::string::npos ||
        line.find("runtime error") != std::string::npos) {
      first = line + " ... ";
      break;
    }
  return printable(first) + tail(text, 1000);
}

// A process being watched: its resident memory polled, killed above a limit or past a time.
struct Watch {
  int status = 0;
  size_t peak_bytes = 0;  // the largest resident memory seen (VmRSS polls and ru_maxrss)
  bool over_memory = false, over_time = false;
};

// Waits for `pid`, polling its memory each kWatchdogPollMs; `on_poll` (may be null) runs each
// round and returns false to stop waiting early (the child is then killed).
Watch watch(pid_t pid, size_t rss_limit, const std::function<bool(Watch&)>& on_poll) {
  Watch w;
  const std::string id = std::to_string(pid);
  for (;;) {
    rusage usage{};
    const pid_t done = wait4(pid, &w.status, WNOHANG, &usage);
    if (done == pid) {
      w.peak_bytes = std::max(w.peak_bytes, size_t(usage.ru_maxrss) * 1024);
      w.over_memory = w.over_memory || w.peak_bytes > rss_limit;
      return w;
    }
    const size_t rss = status_bytes(id, "VmRSS:");
    w.peak_bytes = std::max(w.peak_bytes, rss);
    bool go_on = true;
    if (rss > rss_limit) {
      w.over_memory = true;
      go_on = false;
    } else if (on_poll) {
      go_on = on_poll(w);
    }
    if (!go_on) {
      kill(pid, SIGKILL);
      wait4(pid, &w.status, 0, &usage);
      return w;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(kWatchdogPollMs));
  }
}

// ASAN_OPTIONS with ASan's own limit on resident memory added (under ASan only).
void add_asan_rss_limit() {
  if (!kAsan) return;
  const char* options = std::getenv("ASAN_OPTIONS");
  std::string value = options ? options : "";
  if (value.find("hard_rss_limit_mb") != std::string::npos) return;
  value += std::string(value.empty() ? "" : ":") +
           "hard_rss_limit_mb=" + std::to_string(kAsanHardRssLimitMb);
  setenv("ASAN_OPTIONS", value.c_str(), 1);
}

// Lines from a pipe, read without blocking.
class LineReader {
 public:
  explicit LineReader(int fd) : fd_(fd) { fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK); }
  ~LineReader() { close(fd_); }
  // The complete lines read so far.
  std::vector<std::string> lines() {
    char chunk[4096];
    for (ssize_t n; (n = read(fd_, chunk, sizeof chunk)) > 0;) buffer_.append(chunk, size_t(n));
    std::vector<std::string> out;
    for (size_t newline; (newline = buffer_.find('\n')) != std::string::npos;) {
      out.push_back(buffer_.substr(0, newline));
      buffer_.erase(0, newline + 1);
    }
    return out;
  }

 private:
  int fd_;
  std::string buffer_;
};

// The in-process cases run in children (this test binary again, running
// FuzzFiles.DISABLED_ChildRunsCases from a given case): a child that crashes, hangs or grows
// past the limit costs its case, and a new child goes on from the next one.
class CaseRunner {
 public:
  explicit CaseRunner(std::vector<CaseId> cases) : cases_(std::move(cases)) {}

  void run() {
    for (size_t next = 0; next < cases_.size();) next = run_child(next);
  }
  const std::vector<Failure>& failures() const { return failures_; }
  std::map<std::string, std::map<char, int>> tally;  // per format: a, r, b

 private:
  std::string label(size_t i) const {
    const Format& f = kFormats[cases_[i].format];
    return std::string(f.name) + " #" + std::to_string(cases_[i].index) + " (seed " +
           std::to_string(kSeed + f.stream + uint32_t(cases_[i].index)) + ")";
  }
  std::string input(size_t i) const {
    const Format& f = kFormats[cases_[i].format];
    std::string how;
    try {
      how = make_case(f, cases_[i].index).how;
    } catch (const std::exception& e) {
      how = e.what();
    }
    return "the " + std::string(f.name) + " file " + how + ", kept as " +
           case_path(f, cases_[i].index) +
           "; regenerate: " + regenerate_hint(f.name, cases_[i].index, "LoadersInChildProcesses");
  }
  void fail(size_t i, const std::string& symptom, const std::string& detail) {
    failures_.push_back({symptom, label(i), detail, input(i)});
    ++tally[kFormats[cases_[i].format].name]['b'];
  }

  // Runs cases from `first` in one child; returns the first case it did not finish.
  size_t run_child(size_t first) {
    int fds[2];
    if (pipe(fds) != 0) throw std::runtime_error("cannot create a pipe");
    const std::string stderr_path = (fuzz_dir() / "child-stderr.txt").string();
    std::fflush(nullptr);
    const pid_t pid = fork();
    if (pid == 0) {
      close(fds[0]);
      const int out = open("/dev/null", O_WRONLY),
                err = open(stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      dup2(out, 1);
      dup2(err, 2);
      setenv(kChildVariable, (std::to_string(first) + " " + std::to_string(fds[1])).c_str(), 1);
      const std::string filter = std::string("--gtest_filter=") + kChildTest;
      execl("/proc/self/exe", "nephele_tests", filter.c_str(), "--gtest_also_run_disabled_tests",
            static_cast<char*>(nullptr));
      _exit(127);
    }
    close(fds[1]);
    LineReader reader(fds[0]);
    size_t current = first;  // the case the child is on (or starts with)
    bool started = false;
    auto since = std::chrono::steady_clock::now();
    const auto consume = [&] {
      for (const std::string& line : reader.lines()) {
        std::istringstream in(line);
        std::string word;
        size_t i = 0;
        in >> word >> i;
        if (word == "start") {
          current = i;
          started = true;
          since = std::chrono::steady_clock::now();
        } else if (word == "done") {
          record(i, line);
          current = i + 1;
          started = false;
        }
      }
    };
    std::string late;
    const Watch w = watch(pid, kChildRssLimitBytes, [&](Watch&) {
      consume();
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
      const int limit = started ? kCaseTimeoutS : kChildStartTimeoutS;
      if (seconds > limit) {
        late = "hung: no result within " + std::to_string(limit) + " s";
        return false;
      }
      return true;
    });
    consume();
    const std::string child_stderr = sanitizer_report(read_file(stderr_path));
    const bool clean_exit = WIFEXITED(w.status) && WEXITSTATUS(w.status) == 0;
    if (current >= cases_.size() && clean_exit && !w.over_memory) return current;
    const size_t failed = std::min(current, cases_.size() - 1);
    if (w.over_memory)
      fail(failed,
           "resident memory above " + mib(kChildRssLimitBytes) + " (killed by the watchdog)",
           mib(w.peak_bytes) + " seen; child's stderr: " + child_stderr);
    else if (!late.empty())
      fail(failed, late, "child's stderr: " + child_stderr);
    else if (current >= cases_.size())  // all done, but its exit (a leak report) is not clean
      fail(failed, "the child ended with " + describe_death(w.status) + " after its last case",
           "child's stderr: " + child_stderr);
    else
      fail(failed, describe_death(w.status) + (started ? "" : " (between cases)"),
           "child's stderr: " + child_stderr);
    return failed + 1;
  }

  void record(size_t i, const std::string& line) {
    if (i >= cases_.size()) return;
    const size_t space = line.find(' ', 5);
    if (space == std::string::npos || space + 1 >= line.size()) return;
    const char kind = line[space + 1];
    const std::vector<std::string> parts = split(line.substr(space + 1), '\t');
    if (kind == 'b') {
      fail(i, parts.size() > 1 ? parts[1] : "broken", parts.size() > 2 ? parts[2] : "");
      return;
    }
    ++tally[kFormats[cases_[i].format].name][kind];
  }

  std::vector<CaseId> cases_;
  std::vector<Failure> failures_;
};

// --- `nephele` processes ----------------------------------------------------------------------

struct ProcessCase {
  const char* format;
  Mutation mutation;
};

// Renders cost seconds each where a mutant is accepted, so their mutations are mostly cuts and
// inflated fields; voxelizing is cheap.
// clang-format off
const std::vector<ProcessCase> kProcessCases = {
    {"vdb-stream", Mutation::kCut},       {"vdb-file", Mutation::kInflate},
    {"png-weather", Mutation::kInflate},  {"exr-weather", Mutation::kCut},
    {"png-terrain", Mutation::kCut},      {"exr-terrain", Mutation::kInflate},
    {"tiff-terrain", Mutation::kCut},     {"obj-terrain", Mutation::kAny},
    {"png-albedo", Mutation::kCut},       {"obj-mesh", Mutation::kAny},
    {"obj-mesh", Mutation::kAny},         {"obj-mesh", Mutation::kAny},
};
// clang-format on

// The command line for a mutant at `file`, writing into `out`.
std::vector<std::string> process_args(const Format& f, const std::string& file,
                                      const fs::path& out) {
  if (f.loader == Loader::kMesh)
    return {"voxelize", file, "-o", (out / "x.vdb").string(), "--resolution", "16"};
  std::vector<std::string> args = {"render",
                                   "-q",
                                   "--width",
                                   "16",
                                   "--height",
                                   "16",
                                   "--light-volume-km",
                                   "0",
                                   "-o",
                                   (out / "x.exr").string()};
  if (f.loader == Loader::kVoxelCloud)
    args.insert(args.end(), {"--voxel-cloud", file + "@0,3000,1200"});
  if (f.loader == Loader::kWeatherMap) args.insert(args.end(), {"--weather-map", file});
  if (f.loader == Loader::kTerrain) args.insert(args.end(), {"--terrain", file});
  if (f.loader == Loader::kAlbedoMap) {
    const std::string scene = file + ".toml";
    test::write_bytes(scene, "[terrain]\npreset = \"mountains\"\nresolution = 16\nalbedo_map = \"" +
                                 file + "\"\n");
    args.insert(args.end(), {"--scene", scene});
  }
  return args;
}

std::string shell_words(const std::vector<std::string>& words) {
  std::string text;
  for (const std::string& w : words) text += (text.empty() ? "" : " ") + ("'" + w + "'");
  return text;
}

// Runs `nephele ARGS` under the watchdog, its output in `dir`; "" when the contract held, else
// the symptom, with `detail`.
std::string check_process(const Format& f, const std::vector<std::string>& args,
                          const fs::path& dir, const fs::path& out, std::string& detail) {
  std::vector<std::string> words = {NEPHELE_CLI_PATH};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  const std::string out_path = (dir / "stdout").string(), err_path = (dir / "stderr").string();
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    const int o = open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(o, 1);
    dup2(e, 2);
    execv(argv[0], argv.data());
    _exit(127);
  }
  const auto start = std::chrono::steady_clock::now();
  const Watch w = watch(pid, kChildRssLimitBytes, [&](Watch&) {
    return std::chrono::steady_clock::now() - start < std::chrono::seconds(kProcessTimeoutS);
  });
  const std::string err = read_file(err_path);
  std::vector<std::string> written;
  for (const auto& entry : fs::directory_iterator(out))
    written.push_back(entry.path().filename().string());
  detail = mib(w.peak_bytes) + " at its peak; stderr: " + tail(err);
  if (w.over_memory)
    return "resident memory above " + mib(kChildRssLimitBytes) + " (killed by the watchdog)";
  if (WIFSIGNALED(w.status) && WTERMSIG(w.status) == SIGKILL)
    return "hung: killed after " + std::to_string(kProcessTimeoutS) + " s";
  if (WIFSIGNALED(w.status)) return describe_death(w.status);
  const int code = WEXITSTATUS(w.status);
  if (code == 2) {
    const std::vector<std::string> lines = split(err, '\n');
    if (lines.size() != 1 || err.back() != '\n')
      return "refused (exit 2), but stderr is not one line";
    if (lines[0].rfind(kErrorPrefix, 0) != 0)
      return "refused (exit 2), but stderr does not start with '" + kErrorPrefix + "'";
    if (lines[0].size() > kMaxErrorLineChars) return "refused (exit 2), but its line is too long";
    if (!written.empty()) return "refused (exit 2), but wrote " + written[0];
    return "";
  }
  if (code != 0) return describe_death(w.status);
  try {
    if (f.loader == Loader::kMesh)
      return check_voxels(voxel::load_voxel_cloud((out / "x.vdb").string(), 16)).symptom;
    const Image image = read_image((out / "x.exr").string());
    for (const glm::vec4& p : image.pixels)
      if (!std::isfinite(p.r + p.g + p.b + p.a)) return "non-finite pixels in the rendered image";
  } catch (const std::exception& e) {
    return std::string("accepted, but its output cannot be read: ") + e.what();
  }
  return "";
}

// --- tests ------------------------------------------------------------------------------------

class FuzzFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    if (std::getenv(kChildVariable)) {  // the parent wrote the files
      fuzz_dir() = std::getenv(kDirVariable);
      return;
    }
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    fuzz_dir() = fs::path(NEPHELE_TEST_OUTPUT_DIR) / "fuzz_files" / test->name();
    fs::remove_all(fuzz_dir());
    write_base_files(fuzz_dir() / "base");
    fs::create_directories(fuzz_dir() / "cases");
    setenv(kDirVariable, fuzz_dir().c_str(), 1);
    add_asan_rss_limit();
  }
};

// Every in-process case, in children under the watchdog.
TEST_F(FuzzFiles, LoadersInChildProcesses) {
  const auto start = std::chrono::steady_clock::now();
  CaseRunner runner(in_process_cases());
  runner.run();
  std::string counts;
  for (const auto& [format, tally] : runner.tally)
    counts += " " + format + " " + std::to_string(tally.count('a') ? tally.at('a') : 0) + "/" +
              std::to_string(tally.count('r') ? tally.at('r') : 0);
  std::printf("[ fuzz     ] accepted/refused:%s; %zu failing; %.1f s\n", counts.c_str(),
              runner.failures().size(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  EXPECT_TRUE(runner.failures().empty()) << report(runner.failures());
}

// The watchdog itself: a child whose memory grows without end is stopped at the limit (by the
// watchdog, or under ASan by its hard_rss_limit_mb), and its case fails.
TEST_F(FuzzFiles, TheWatchdogStopsARunawayChild) {
  setenv(kRunawayVariable, "1", 1);
  CaseRunner runner({{0, 0}});
  runner.run();
  unsetenv(kRunawayVariable);
  ASSERT_EQ(runner.failures().size(), 1u) << report(runner.failures());
  const Failure& failure = runner.failures()[0];
  const bool by_watchdog = failure.symptom.rfind("resident memory above", 0) == 0;
  const bool by_asan =
      kAsan && failure.detail.find("hard rss limit exhausted") != std::string::npos;
  EXPECT_TRUE(by_watchdog || by_asan) << report(runner.failures());
  std::printf("[ fuzz     ] the runaway child: %s (%s)\n", failure.symptom.c_str(),
              failure.detail.substr(0, 200).c_str());
}

// Mutants through `nephele render` and `nephele voxelize` processes under the watchdog.
TEST_F(FuzzFiles, NepheleProcesses) {
  const auto start = std::chrono::steady_clock::now();
  const auto only = only_case();
  std::vector<Failure> failures;
  int refused = 0, accepted = 0;
  for (size_t i = 0; i < kProcessCases.size(); ++i) {
    const Format& f = format_named(kProcessCases[i].format);
    if (only && !(only->first == f.name && only->second == int(i))) continue;
    Rng rng(kSeed + kProcessStream + uint32_t(i));
    const Mutant m = mutate(f, base_bytes(f), rng, kProcessCases[i].mutation);
    const fs::path dir = fuzz_dir() / ("process-" + std::to_string(i));
    fs::remove_all(dir);
    fs::create_directories(dir / "out");
    const std::string file = (dir / (std::string(f.name) + f.extension)).string();
    test::write_bytes(file, m.bytes);
    const std::vector<std::string> args = process_args(f, file, dir / "out");
    std::string detail;
    const auto process_start = std::chrono::steady_clock::now();
    const std::string symptom = check_process(f, args, dir, dir / "out", detail);
    const bool was_refused = fs::is_empty(dir / "out");
    std::printf(
        "[ fuzz     ] process %zu (%s, %s): %s in %.1f s\n", i, f.name, m.how.c_str(),
        !symptom.empty() ? "failed"
        : was_refused    ? "refused"
                         : "accepted",
        std::chrono::duration<double>(std::chrono::steady_clock::now() - process_start).count());
    if (symptom.empty()) {
      (was_refused ? refused : accepted) += 1;
      continue;
    }
    failures.push_back(
        {symptom,
         "process " + std::to_string(i) + " (" + f.name + ", seed " +
             std::to_string(kSeed + kProcessStream + uint32_t(i)) + ")",
         detail,
         "the " + std::string(f.name) + " file " + m.how + ": nephele " + shell_words(args) +
             "; regenerate: " + regenerate_hint(f.name, int(i), "NepheleProcesses")});
  }
  std::printf("[ fuzz     ] %d processes refused, %d accepted, %zu failing; %.1f s\n", refused,
              accepted, failures.size(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  EXPECT_TRUE(failures.empty()) << report(failures);
}

// The child of LoadersInChildProcesses (disabled: it runs only as that child).
TEST_F(FuzzFiles, DISABLED_ChildRunsCases) {
  const char* child = std::getenv(kChildVariable);
  if (!child) GTEST_SKIP() << "runs only as the child of FuzzFiles.LoadersInChildProcesses";
  size_t first = 0;
  int fd = -1;
  std::istringstream(child) >> first >> fd;
  run_cases_as_child(first, fd);
  close(fd);
}

}  // namespace
}  // namespace nephele
