// nephele — linear HDR images and their writers.
#pragma once

#include <glm/vec4.hpp>
#include <array>
#include <utility>
#include <optional>
#include <string>
#include <vector>

#include "nephele/tonemap.h"

namespace nephele {

// Linear HDR RGBA, row-major, row 0 at the top.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<glm::vec4> pixels;

  Image() = default;
  Image(int w, int h) : width(w), height(h), pixels(size_t(w) * size_t(h), glm::vec4(0.0f)) {}
  glm::vec4& at(int x, int y) { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
  const glm::vec4& at(int x, int y) const { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
};

// Relative luminance of linear Rec.709 RGB.
float luminance(const glm::vec4& rgb);

// Tone map (exposure, then `op`) and encode as 8-bit sRGB RGBA, alpha 255; 4 bytes a pixel.
// NaN and negative values give 0, large ones 255.
std::vector<unsigned char> tonemap_srgb8(const Image& image, float exposure,
                                         ToneMap op = ToneMap::Aces);

// What an EXR stores: half floats (the default; values beyond the largest half, 65504, are
// clamped to it, so the sun's disk does not become inf) or 32-bit floats (the true values).
enum class ExrPixels { kHalf, kFloat };

// Writes by extension, case-insensitive: .png (tone-mapped 8-bit sRGB, alpha 255) or .exr
// (linear RGBA, ZIP, as `exr` says; `exposure` applies to PNG only, an EXR keeps the values
// as they are). `exposure` multiplies the values before the tone map (exposure_from_ev100 of
// exposure.h); without one the image is metered as a camera's auto exposure would meter it
// (still_exposure with the default OutputParams), so a frame's cd/m^2 give a well-exposed
// PNG: write_image(frame.color, "sky.png"). Pass 1.0f for values already exposed. Never
// writes NaN or inf: NaN is stored as 0, infinities as the largest value. Writes atomically
// (write_file_atomically), so a failed write leaves nothing behind. Throws InputError for an
// unsupported extension or an empty image, RuntimeError naming the path on I/O failure.
void write_image(const Image& image, const std::string& path,
                 std::optional<float> exposure = std::nullopt, ExrPixels exr = ExrPixels::kHalf,
                 ToneMap op = ToneMap::Aces);

// One layer of a multi-layer EXR: `image`'s first `channels` channels (1 to 4: R, G, B, A),
// named "R", "G", ... or, with a prefix, "prefix.R", ... (OpenEXR's layer convention); with
// `names`, those names instead (one a channel: "depth_m" gives "prefix.depth_m").
struct ExrLayer {
  std::string prefix;
  const Image* image = nullptr;
  int channels = 4;
  std::vector<std::string> names;
};

// Attributes for an EXR's header (OpenEXR's standard ones where they exist, else named
// nephele.* by convention): text, numbers, and a 4x4 matrix (row-major as OpenEXR's M44f,
// which transforms row vectors: p' = p M).
struct ExrAttributes {
  std::vector<std::pair<std::string, std::string>> strings;
  std::vector<std::pair<std::string, float>> floats;
  std::vector<std::pair<std::string, std::array<float, 16>>> matrices;
};

// Writes the layers (all of one size) into one EXR file, atomically, as write_image does, with
// `attributes` in its header. Throws InputError for a path that is not .exr, no layers, layers
// of different sizes, a `names` list whose size is not `channels`, or an attribute name that
// OpenEXR reserves (channels, compression, ...).
void write_exr_layers(const std::vector<ExrLayer>& layers, const std::string& path,
                      ExrPixels exr = ExrPixels::kHalf, const ExrAttributes& attributes = {});

// The attributes of an EXR file's header as text ("name" -> "value"; numbers as written by
// the shortest round trip, matrices as 16 numbers), for tests and tools. Throws InputError
// naming the path if it cannot be read.
std::vector<std::pair<std::string, std::string>> read_exr_attributes(const std::string& path);

// The named channels of an EXR file ("R", "clouds.A", ...), each as an image whose r, g, b
// hold it (a = 1). Throws InputError naming the path and the channel if one is missing.
Image read_exr_channel(const std::string& path, const std::string& channel);

// Throws InputError naming `parameter` if `path` cannot be written as an image (unknown
// extension, or any reason of check_output_file in output_file.h). Writes nothing.
// The message reads e.g. "--output 'x.jpg': unsupported image format (allowed: .png, .exr)".
void check_output_path(const std::string& path, const std::string& parameter);

// Reads a PNG (8-bit values as stored, scaled to [0, 1], no sRGB decode; always RGBA) or an
// EXR (linear, half or float; missing alpha reads as 1), recognised by content, not by name.
// Throws InputError naming the path if it cannot be read.
Image read_image(const std::string& path);

// Reads the layer `layer` of an EXR (channels layer.R, .G, .B, and .A, which reads as 1 when
// missing; "" the unnamed R, G, B, A). Throws InputError naming the path if it cannot be read
// or has no such layer.
Image read_exr_layer(const std::string& path, const std::string& layer);

}  // namespace nephele
