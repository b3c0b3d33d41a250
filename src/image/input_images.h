// nephele — the image files a scene reads (the weather map, the terrain's albedo map and its
// heights), checked from their headers before anything is decoded: a hostile file is refused
// in one line whatever size it declares, and what is decoded stays within stated limits.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace nephele {

// The largest images the scene reads, pixels a side (docs/reliability.md: limits on inputs).
// At 1920 x 1080 a render with every input at its limit peaks under 3 GiB of the process's
// memory on lavapipe.
constexpr int kMaxWeatherMapSide = 8192;  // clouds.weather_map: 256 MiB as 8-bit RGBA
constexpr int kMaxAlbedoMapSide = 4096;   // terrain.albedo_map: 256 MiB as float RGBA

// What an image file's header declares, read without decoding its pixels.
struct ImageHeader {
  bool exr = false;  // else a PNG
  int64_t width = 0, height = 0;
  int channels = 0;  // PNG: 1 grey, 2 grey and alpha, 3 RGB (or a palette), 4 RGBA; EXR: its count
  int bits = 8;      // PNG: bits a channel
  std::vector<std::string> channel_names;  // EXR
};

// read_image_header's answer for a file that is neither (it says what is allowed).
inline constexpr const char* kNeitherPngNorExr = "is neither a PNG nor an EXR file";

// Reads the header of a PNG or an EXR (told by its content) and checks its structure as far as
// it can be checked without decoding: for a PNG every chunk whole within the file, one IHDR
// first, IDAT data no larger than its pixels need and an IEND; for an EXR its attributes within
// the file, a scan-line or tiled image (not deep) and a chunk table that fits in the file.
// Its size is checked against `max_side` (image_size_problem) as soon as it is read, before the
// rest. Returns "" and fills `header`, or why the file cannot be read (one line, no path).
std::string read_image_header(const std::string& path, ImageHeader& header, int64_t max_side,
                              const std::string& unit = "pixels");

// "12000 x 12000 pixels: at most 8192 a side are allowed", or "" within [1, max_side].
std::string image_size_problem(int64_t width, int64_t height, int64_t max_side,
                               const std::string& unit = "pixels");

// Why a PNG's compressed pixel data does not inflate to exactly what its header declares (at
// most that many bytes are allocated), "" when it does. `path` holds a PNG whose header
// read_image_header accepted.
std::string png_data_problem(const std::string& path, const ImageHeader& header);

// An 8-bit RGBA image, row 0 at the top.
struct Rgba8Image {
  int width = 0, height = 0;
  std::vector<unsigned char> texels;  // 4 bytes a pixel
};

// What a weather map must be, for messages.
std::string weather_map_requirement();

// The weather map as 8-bit RGBA (a 16-bit PNG cut to 8 bits, an EXR clamped to [0, 1], a
// missing alpha 1), with no full-resolution float copy. Throws InputError naming `key` and
// the path, and saying what a weather map must be, for any file it cannot read.
Rgba8Image read_weather_map(const std::string& path, const std::string& key = "clouds.weather_map");

// Why `path` cannot be the terrain's albedo map, told from its header ("" when it may be one).
std::string albedo_map_problem(const std::string& path);

// An image of half floats, 4 a pixel (R, G, B, A), row 0 at the top.
struct HalfRgbaImage {
  int width = 0, height = 0;
  std::vector<uint16_t> halfs;
};

// The terrain's albedo map as linear RGB half floats in [0, 1], alpha 1: a PNG's sRGB codes
// decoded, an EXR's values clamped (NaN as 0). Decoded without a full-resolution float copy
// (an EXR 64 rows at a time). Throws InputError naming `key` and the path once, saying what an
// albedo map must be, for any file it cannot read.
HalfRgbaImage read_albedo_map(const std::string& path,
                              const std::string& key = "terrain.albedo_map");

}  // namespace nephele
