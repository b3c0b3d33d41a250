// nephele — the image files a scene reads, checked from their headers (input_images.h).
//
// PNG and EXR headers are read here byte by byte rather than by stb_image or OpenEXR: both
// trust what a file declares (stb inflates a PNG's data into a buffer that grows without end,
// OpenEXR sizes its chunk table and attributes as the header says), so a small file could make
// them allocate gigabytes before they find it corrupt.
#include "image/input_images.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <stb/stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/packing.hpp>
#include <limits>
#include <memory>

#include "nephele/error.h"

namespace nephele {
namespace {

constexpr unsigned char kPngMagic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
constexpr unsigned char kExrMagic[4] = {0x76, 0x2f, 0x31, 0x01};
// Slack over the pixels' own bytes that a PNG's compressed data may take: deflate's worst
// case of fixed codes (9 bits a byte) and a margin for tiny images and block headers.
constexpr double kPngDataSlack = 1.125;
constexpr int64_t kPngDataMarginBytes = 64 * 1024;

uint32_t be32(const unsigned char* p) {
  return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | uint32_t(p[3]);
}

int32_t le32(const unsigned char* p) {
  return int32_t(uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 |
                 uint32_t(p[3]) << 24);
}

// A chunk's or attribute's name as a message may show it.
std::string shown_name(const std::string& name) {
  return "'" + shorten_for_message(name) + "'";
}

// A file read at offsets, each read checked against its size.
class ByteFile {
 public:
  explicit ByteFile(const std::string& path) : in_(path, std::ios::binary) {
    std::error_code error;
    size_ = int64_t(std::filesystem::file_size(path, error));
    if (error) size_ = 0;
  }
  bool good() const { return bool(in_); }
  int64_t size() const { return size_; }
  // `n` bytes at `offset`; false where the file ends before them.
  bool read(int64_t offset, void* out, int64_t n) {
    if (offset < 0 || n < 0 || offset + n > size_) return false;
    in_.clear();
    in_.seekg(offset);
    in_.read(static_cast<char*>(out), n);
    return in_.gcount() == n;
  }

 private:
  std::ifstream in_;
  int64_t size_ = 0;
};

// --- PNG ---------------------------------------------------------------------------------

int png_samples_per_pixel(int color_type) {
  switch (color_type) {
    case 0:
      return 1;
    case 2:
      return 3;
    case 3:
      return 1;
    case 4:
      return 2;
    case 6:
      return 4;
    default:
      return 0;
  }
}

bool png_depth_allowed(int color_type, int depth) {
  switch (color_type) {
    case 0:
      return depth == 1 || depth == 2 || depth == 4 || depth == 8 || depth == 16;
    case 3:
      return depth == 1 || depth == 2 || depth == 4 || depth == 8;
    case 2:
    case 4:
    case 6:
      return depth == 8 || depth == 16;
    default:
      return false;
  }
}

struct SizeLimit {
  int64_t max_side;
  std::string unit;
};

struct PngLayout {
  int64_t width = 0, height = 0;
  int depth = 0, color_type = 0, samples = 0;
  bool interlaced = false;
};

// The bytes a PNG's pixels inflate to: each row's filter byte and samples, per Adam7 pass when
// interlaced. As a double: a hostile header's product need not fit 64 bits.
double png_raw_bytes(const PngLayout& png) {
  const auto rows = [&](double w, double h) {
    if (w <= 0 || h <= 0) return 0.0;
    return (std::ceil(w * png.samples * png.depth / 8.0) + 1.0) * h;
  };
  if (!png.interlaced) return rows(double(png.width), double(png.height));
  static const int kPass[7][4] = {{0, 0, 8, 8}, {4, 0, 8, 8}, {0, 4, 4, 8}, {2, 0, 4, 4},
                                  {0, 2, 2, 4}, {1, 0, 2, 2}, {0, 1, 1, 2}};
  double total = 0.0;
  for (const auto& p : kPass)
    total += rows(std::floor(double(png.width - p[0] + p[2] - 1) / p[2]),
                  std::floor(double(png.height - p[1] + p[3] - 1) / p[3]));
  return total;
}

std::string ihdr_problem(const unsigned char* d, PngLayout& png) {
  png.width = be32(d);
  png.height = be32(d + 4);
  png.depth = d[8];
  png.color_type = d[9];
  png.samples = png_samples_per_pixel(png.color_type);
  png.interlaced = d[12] == 1;
  if (png.width == 0 || png.height == 0)
    return "declares " + std::to_string(png.width) + " x " + std::to_string(png.height) +
           " pixels: an image needs at least 1 x 1";
  if (png.samples == 0 || !png_depth_allowed(png.color_type, png.depth))
    return "declares colour type " + std::to_string(png.color_type) + " at " +
           std::to_string(png.depth) + " bits, which PNG does not define";
  if (d[10] != 0 || d[11] != 0 || d[12] > 1)
    return "declares an unknown compression, filter or interlace method";
  return "";
}

// Walks the chunks; `idat` (when given) receives each IDAT's offset and length.
std::string read_png_layout(ByteFile& file, PngLayout& png, bool& transparent,
                            const SizeLimit& limit,
                            std::vector<std::pair<int64_t, uint32_t>>* idat = nullptr) {
  int64_t at = 8, data_bytes = 0;
  bool first = true, seen_idat = false;
  transparent = false;
  while (true) {
    unsigned char head[8];
    if (!file.read(at, head, 8))
      return "is truncated: it ends at byte " + std::to_string(file.size()) + " with no IEND chunk";
    const uint32_t length = be32(head);
    const std::string type(reinterpret_cast<char*>(head + 4), 4);
    if (length > 0x7fffffffu || at + 12 + int64_t(length) > file.size())
      return "is truncated: its " + shown_name(type) + " chunk at byte " + std::to_string(at) +
             " declares " + std::to_string(length) + " bytes, past the file's end (" +
             std::to_string(file.size()) + " bytes)";
    if (first) {
      unsigned char d[13];
      if (type != "IHDR" || length != 13 || !file.read(at + 8, d, 13))
        return "is not a valid PNG: it does not start with a 13-byte IHDR chunk";
      if (std::string why = ihdr_problem(d, png); !why.empty()) return why;
      if (std::string why = image_size_problem(png.width, png.height, limit.max_side, limit.unit);
          !why.empty())
        return why;
      first = false;
    } else if (type == "IDAT") {
      seen_idat = true;
      data_bytes += length;
      if (idat) idat->emplace_back(at + 8, length);
    } else if (type == "tRNS" && !seen_idat) {
      transparent = true;
    } else if (type == "IEND") {
      break;
    }
    at += 12 + int64_t(length);
  }
  if (!seen_idat) return "has no IDAT chunk (no pixel data)";
  const double most = png_raw_bytes(png) * kPngDataSlack + double(kPngDataMarginBytes);
  if (double(data_bytes) > most)
    return "holds " + std::to_string(data_bytes) +
           " bytes of compressed pixel data, more than its " + std::to_string(png.width) + " x " +
           std::to_string(png.height) + " pixels can need; it is corrupt";
  return "";
}

std::string png_header(ByteFile& file, ImageHeader& header, const SizeLimit& limit) {
  PngLayout png;
  bool transparent = false;
  if (std::string why = read_png_layout(file, png, transparent, limit); !why.empty()) return why;
  header.exr = false;
  header.width = png.width;
  header.height = png.height;
  header.bits = png.depth;
  // As stb_image counts them: a palette is RGB, or RGBA with a transparency chunk.
  header.channels = png.color_type == 3 ? (transparent ? 4 : 3) : png.samples;
  return "";
}

// --- EXR ---------------------------------------------------------------------------------

// Scan lines in a chunk by compression (OpenEXR's numLinesInBuffer); 0 for an unknown one.
int exr_lines_per_chunk(int compression) {
  static const int kLines[] = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};
  return compression >= 0 && compression < 10 ? kLines[compression] : 0;
}

struct ExrLayout {
  bool has_window = false, tiled = false;
  int32_t window[4] = {};  // min x, min y, max x, max y
  uint32_t tile_x = 0, tile_y = 0;
  int compression = 0;
  bool deep = false;
  std::vector<std::string> channels;
};

// A NUL-terminated name of at most `longest` characters at `at`; false when there is none.
bool read_name(ByteFile& file, int64_t& at, size_t longest, std::string& name) {
  name.clear();
  char c = 0;
  while (file.read(at++, &c, 1)) {
    if (c == '\0') return true;
    if (name.size() == longest) return false;
    name += c;
  }
  return false;
}

void parse_channel_list(const std::vector<unsigned char>& v, std::vector<std::string>& names) {
  size_t at = 0;
  while (at < v.size() && v[at] != 0) {
    const auto end = std::find(v.begin() + ptrdiff_t(at), v.end(), 0);
    names.emplace_back(v.begin() + ptrdiff_t(at), end);
    at = size_t(end - v.begin()) + 1 + 16;  // pixel type, linear, reserved, sampling
  }
}

void take_attribute(const std::string& name, const std::string& type,
                    const std::vector<unsigned char>& v, ExrLayout& exr) {
  if (name == "dataWindow" && type == "box2i" && v.size() == 16) {
    for (int k = 0; k < 4; ++k) exr.window[k] = le32(v.data() + 4 * k);
    exr.has_window = true;
  } else if (name == "channels" && type == "chlist") {
    parse_channel_list(v, exr.channels);
  } else if (name == "tiles" && type == "tiledesc" && v.size() == 9) {
    exr.tile_x = uint32_t(le32(v.data()));
    exr.tile_y = uint32_t(le32(v.data() + 4));
  } else if (name == "compression" && v.size() == 1) {
    exr.compression = v[0];
  } else if (name == "type" && type == "string") {
    exr.deep = std::string(v.begin(), v.end()).rfind("deep", 0) == 0;
  }
}

std::string exr_chunk_problem(const ExrLayout& exr, int64_t w, int64_t h, int64_t table_at,
                              int64_t file_size) {
  double chunks = 0.0;
  if (exr.tiled) {
    if (exr.tile_x == 0 || exr.tile_y == 0 || exr.tile_x > uint32_t(std::max<int64_t>(w, 256)) ||
        exr.tile_y > uint32_t(std::max<int64_t>(h, 256)))
      return "declares tiles of " + std::to_string(exr.tile_x) + " x " +
             std::to_string(exr.tile_y) + " pixels for an image of " + std::to_string(w) + " x " +
             std::to_string(h);
    chunks = std::ceil(double(w) / exr.tile_x) * std::ceil(double(h) / exr.tile_y);
  } else {
    const int lines = exr_lines_per_chunk(exr.compression);
    if (lines == 0)
      return "declares an unknown compression (" + std::to_string(exr.compression) + ")";
    chunks = std::ceil(double(h) / lines);
  }
  // Each chunk has an 8-byte offset in the table after the header.
  if (chunks * 8.0 > double(file_size - table_at))
    return "is truncated or corrupt: its " + std::to_string(w) + " x " + std::to_string(h) +
           " pixels need a table of " + number_for_message(chunks) + " chunks, and the file (" +
           std::to_string(file_size) + " bytes) cannot hold it";
  return "";
}

std::string exr_header(ByteFile& file, ImageHeader& header, const SizeLimit& limit) {
  unsigned char version[4];
  if (!file.read(4, version, 4)) return "is truncated: it ends inside the EXR header";
  if (version[0] != 2) return "is an EXR of version " + std::to_string(version[0]) + " (2 is read)";
  ExrLayout exr;
  exr.tiled = version[1] & 0x02;
  const size_t longest = version[1] & 0x04 ? 255 : 31;
  if (version[1] & 0x08) return "is a deep EXR; only flat images are read";
  if (version[1] & 0x10) return "is a multi-part EXR; only single-part EXRs are read";
  int64_t at = 8;
  std::string name, type;
  while (true) {
    if (!read_name(file, at, longest, name))
      return "is truncated or corrupt: an attribute's name at byte " + std::to_string(at) +
             " does not end";
    if (name.empty()) break;
    unsigned char size_bytes[4];
    if (!read_name(file, at, longest, type) || !file.read(at, size_bytes, 4))
      return "is truncated or corrupt: its attribute " + shown_name(name) + " does not end";
    const int32_t size = le32(size_bytes);
    at += 4;
    if (size < 0 || at + size > file.size())
      return "is truncated or corrupt: its attribute " + shown_name(name) + " declares " +
             std::to_string(size) + " bytes, past the file's end (" + std::to_string(file.size()) +
             " bytes)";
    std::vector<unsigned char> value(size_t(std::max(size, 0)));
    file.read(at, value.data(), size);
    take_attribute(name, type, value, exr);
    at += size;
  }
  if (exr.deep) return "is a deep EXR; only flat images are read";
  if (!exr.has_window || exr.channels.empty())
    return "is not a valid EXR: it has no data window or no channels";
  const int64_t w = int64_t(exr.window[2]) - exr.window[0] + 1,
                h = int64_t(exr.window[3]) - exr.window[1] + 1;
  if (w < 1 || h < 1)
    return "declares an empty data window (" + std::to_string(w) + " x " + std::to_string(h) +
           " pixels)";
  if (std::string why = image_size_problem(w, h, limit.max_side, limit.unit); !why.empty())
    return why;
  if (std::string why = exr_chunk_problem(exr, w, h, at, file.size()); !why.empty()) return why;
  header.exr = true;
  header.width = w;
  header.height = h;
  header.channels = int(exr.channels.size());
  header.bits = 32;
  header.channel_names = exr.channels;
  return "";
}

// --- weather map -------------------------------------------------------------------------

[[noreturn]] void refuse_weather_map(const std::string& key, const std::string& path,
                                     const std::string& why) {
  throw InputError(key + " '" + shorten_path_for_message(path) + "': " + why + "; " +
                   weather_map_requirement());
}

Rgba8Image decode_png_rgba8(const std::string& path) {
  int w = 0, h = 0, channels = 0;
  std::unique_ptr<unsigned char, void (*)(void*)> data(
      stbi_load(path.c_str(), &w, &h, &channels, 4), stbi_image_free);
  if (!data) {
    const char* reason = stbi_failure_reason();
    throw std::runtime_error(std::string("cannot decode the PNG (") +
                             (reason ? reason : "unknown error") + ")");
  }
  Rgba8Image image{w, h, {}};
  image.texels.assign(data.get(), data.get() + size_t(w) * size_t(h) * 4);
  return image;
}

unsigned char unorm8(float v) {
  return static_cast<unsigned char>(std::clamp(std::isnan(v) ? 0.0f : v, 0.0f, 1.0f) * 255.0f +
                                    0.5f);
}

// The EXR's R, G, B, A (a missing alpha 1) as floats, 64 rows at a time: `strip(y0, rows,
// rgba)` gets rows y0 .. y0 + rows - 1 of the data window. Only a strip is held as floats.
template <class Strip>
void read_exr_strips(const std::string& path, int& width, int& height, const Strip& strip_fn) {
  constexpr int kRows = 64;
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    const int w = window.max.x - window.min.x + 1, h = window.max.y - window.min.y + 1;
    width = w;
    height = h;
    std::vector<float> strip(size_t(w) * kRows * 4);
    static const char* const kNames[4] = {"R", "G", "B", "A"};
    for (int y0 = 0; y0 < h; y0 += kRows) {
      const int rows = std::min(kRows, h - y0);
      // Slices are addressed by the data window's absolute coordinates.
      const ptrdiff_t first = ptrdiff_t(window.min.y + y0) * w + window.min.x;
      Imf::FrameBuffer frame;
      for (int c = 0; c < 4; ++c)
        frame.insert(
            kNames[c],
            Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(strip.data() - first * 4 + c),
                       4 * sizeof(float), 4 * sizeof(float) * size_t(w), 1, 1, c == 3 ? 1.0 : 0.0));
      file.setFrameBuffer(frame);
      file.readPixels(window.min.y + y0, window.min.y + y0 + rows - 1);
      strip_fn(y0, rows, strip.data());
    }
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("cannot decode the EXR (") +
                             one_line_for_message(e.what()) + ")");
  }
}

Rgba8Image decode_exr_rgba8(const std::string& path) {
  Rgba8Image image;
  read_exr_strips(path, image.width, image.height, [&](int y0, int rows, const float* rgba) {
    if (image.texels.empty()) image.texels.resize(size_t(image.width) * size_t(image.height) * 4);
    unsigned char* out = image.texels.data() + size_t(y0) * size_t(image.width) * 4;
    for (size_t i = 0; i < size_t(rows) * size_t(image.width) * 4; ++i) out[i] = unorm8(rgba[i]);
  });
  return image;
}

// --- albedo map --------------------------------------------------------------------------

std::string albedo_map_requirement() {
  return "an albedo map is a PNG or an EXR of at most " + std::to_string(kMaxAlbedoMapSide) +
         " x " + std::to_string(kMaxAlbedoMapSide) + " pixels";
}

float linear_from_srgb(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// RGB clamped to [0, 1] (NaN as 0) and alpha 1, as half floats.
void put_albedo_halfs(uint16_t* out, float r, float g, float b) {
  const auto clamped = [](float v) { return std::clamp(std::isnan(v) ? 0.0f : v, 0.0f, 1.0f); };
  out[0] = glm::packHalf1x16(clamped(r));
  out[1] = glm::packHalf1x16(clamped(g));
  out[2] = glm::packHalf1x16(clamped(b));
  out[3] = glm::packHalf1x16(1.0f);
}

// A PNG's sRGB codes decoded to linear through a table of the 256 codes.
HalfRgbaImage albedo_from_png(const std::string& path) {
  const Rgba8Image codes = decode_png_rgba8(path);
  float linear[256];
  for (int i = 0; i < 256; ++i) linear[i] = linear_from_srgb(float(i) / 255.0f);
  HalfRgbaImage image{codes.width, codes.height, std::vector<uint16_t>(codes.texels.size())};
  for (size_t i = 0; i < codes.texels.size(); i += 4)
    put_albedo_halfs(&image.halfs[i], linear[codes.texels[i]], linear[codes.texels[i + 1]],
                     linear[codes.texels[i + 2]]);
  return image;
}

HalfRgbaImage albedo_from_exr(const std::string& path) {
  HalfRgbaImage image;
  read_exr_strips(path, image.width, image.height, [&](int y0, int rows, const float* rgba) {
    if (image.halfs.empty()) image.halfs.resize(size_t(image.width) * size_t(image.height) * 4);
    uint16_t* out = image.halfs.data() + size_t(y0) * size_t(image.width) * 4;
    for (size_t i = 0; i < size_t(rows) * size_t(image.width) * 4; i += 4)
      put_albedo_halfs(out + i, rgba[i], rgba[i + 1], rgba[i + 2]);
  });
  return image;
}

}  // namespace

std::string read_image_header(const std::string& path, ImageHeader& header, int64_t max_side,
                              const std::string& unit) {
  const SizeLimit limit{max_side, unit};
  ByteFile file(path);
  if (!file.good()) return "cannot read the file";
  unsigned char magic[8] = {};
  file.read(0, magic, std::min<int64_t>(8, file.size()));
  if (file.size() == 0) return "is empty (0 bytes)";
  if (file.size() >= 8 && std::memcmp(magic, kPngMagic, 8) == 0)
    return png_header(file, header, limit);
  if (file.size() >= 4 && std::memcmp(magic, kExrMagic, 4) == 0)
    return exr_header(file, header, limit);
  return kNeitherPngNorExr;
}

std::string image_size_problem(int64_t width, int64_t height, int64_t max_side,
                               const std::string& unit) {
  if (width >= 1 && height >= 1 && width <= max_side && height <= max_side) return "";
  return std::to_string(width) + " x " + std::to_string(height) + " " + unit + ": at most " +
         std::to_string(max_side) + " a side are allowed";
}

std::string png_data_problem(const std::string& path, const ImageHeader& header) {
  ByteFile file(path);
  PngLayout png;
  bool transparent = false;
  std::vector<std::pair<int64_t, uint32_t>> chunks;
  const SizeLimit any{std::numeric_limits<int64_t>::max(), "pixels"};
  if (std::string why = read_png_layout(file, png, transparent, any, &chunks); !why.empty())
    return why;
  const double raw = png_raw_bytes(png);
  if (raw > double(std::numeric_limits<int>::max() - 1))
    return std::to_string(header.width) + " x " + std::to_string(header.height) +
           " pixels are too many to decode";
  std::vector<char> compressed;
  for (const auto& [offset, length] : chunks) {
    compressed.resize(compressed.size() + length);
    if (!file.read(offset, compressed.data() + compressed.size() - length, length))
      return "cannot read the file";
  }
  // One byte more than the pixels need: a stream that fills it inflates to more.
  std::vector<char> pixels(size_t(raw) + 1);
  // stb leaves its last reason in place where it finds a reserved block type: set a known one.
  int unused = 0;
  stbi_info_from_memory(reinterpret_cast<const stbi_uc*>(""), 0, &unused, &unused, &unused);
  const char* stale = stbi_failure_reason();
  const int n = stbi_zlib_decode_buffer(pixels.data(), int(pixels.size()), compressed.data(),
                                        int(compressed.size()));
  const char* reason =
      stbi_failure_reason() == stale ? "corrupt deflate data" : stbi_failure_reason();
  if ((n < 0 && std::strcmp(reason, "output buffer limit") == 0) || n > int(raw))
    return "its compressed pixel data inflates to more than its " + std::to_string(header.width) +
           " x " + std::to_string(header.height) + " pixels need; it is corrupt";
  if (n < 0) return std::string("cannot decode the PNG (") + reason + ")";
  if (n < int(raw))
    return "is truncated: its pixel data inflates to " + std::to_string(n) + " of the " +
           std::to_string(int64_t(raw)) + " bytes its " + std::to_string(header.width) + " x " +
           std::to_string(header.height) + " pixels need";
  return "";
}

std::string weather_map_requirement() {
  return "a weather map is an RGBA PNG (8 or 16 bits) or an EXR of at most " +
         std::to_string(kMaxWeatherMapSide) + " x " + std::to_string(kMaxWeatherMapSide) +
         " pixels";
}

Rgba8Image read_weather_map(const std::string& path, const std::string& key) {
  ImageHeader header;
  std::string why = read_image_header(path, header, kMaxWeatherMapSide);
  if (why.empty() && !header.exr) why = png_data_problem(path, header);
  if (!why.empty()) refuse_weather_map(key, path, why);
  try {
    return header.exr ? decode_exr_rgba8(path) : decode_png_rgba8(path);
  } catch (const std::exception& e) {
    refuse_weather_map(key, path, e.what());
  }
}

std::string albedo_map_problem(const std::string& path) {
  ImageHeader header;
  return read_image_header(path, header, kMaxAlbedoMapSide);
}

HalfRgbaImage read_albedo_map(const std::string& path, const std::string& key) {
  const auto refuse = [&](const std::string& why) {
    return InputError(key + " '" + shorten_path_for_message(path) + "': " + why + "; " +
                      albedo_map_requirement());
  };
  ImageHeader header;
  std::string why = read_image_header(path, header, kMaxAlbedoMapSide);
  if (why.empty() && !header.exr) why = png_data_problem(path, header);
  if (!why.empty()) throw refuse(why);
  try {
    return header.exr ? albedo_from_exr(path) : albedo_from_png(path);
  } catch (const std::exception& e) {
    throw refuse(e.what());
  }
}

}  // namespace nephele
