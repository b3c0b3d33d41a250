// nephele — image tone mapping, writers (PNG, EXR) and readers.
//
// Both writers encode into memory first and then go through write_file_atomically (a
// temporary file beside the target, renamed over it). That keeps every I/O error in one
// place, where it is checked (OpenEXR's file destructor swallows errors, and stbi_write_png
// ignores fwrite failures), and means that a failure never leaves a partial image or a
// temporary file behind.
#include "nephele/image.h"

#include "nephele/exposure.h"
#include "nephele/scene.h"

#include <ImfChannelList.h>
#include <ImfFloatAttribute.h>
#include <ImfMatrixAttribute.h>
#include <ImfStringAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfIO.h>
#include <ImfOutputFile.h>
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

#include "nephele/error.h"
#include "nephele/output_file.h"
#include "render/glsl.h"

namespace nephele {
namespace {

namespace fs = std::filesystem;

constexpr const char* kAllowedFormats = "(allowed: .png, .exr)";

enum class ImageFormat { kPng, kExr, kUnsupported };

// The format named by the path's extension, compared case-insensitively.
ImageFormat format_of(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".png") return ImageFormat::kPng;
  if (ext == ".exr") return ImageFormat::kExr;
  return ImageFormat::kUnsupported;
}

std::string quoted(const std::string& s) {
  return "'" + s + "'";
}

static_assert(int(ToneMap::Aces) == glsl::TONEMAP_ACES && int(ToneMap::Agx) == glsl::TONEMAP_AGX &&
              int(ToneMap::Uncharted2) == glsl::TONEMAP_UNCHARTED2 &&
              int(ToneMap::Reinhard) == glsl::TONEMAP_REINHARD && int(ToneMap::None) == glsl::TONEMAP_NONE);

// One sRGB value in [0, 1] to its 8-bit code.
unsigned char code_of(float v) {
  return static_cast<unsigned char>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

void check_writable_image(const Image& image, const std::string& path) {
  const size_t expected = size_t(std::max(image.width, 0)) * size_t(std::max(image.height, 0));
  if (image.width <= 0 || image.height <= 0 || image.pixels.size() != expected) {
    throw InputError("image " + quoted(path) + ": cannot write a " + std::to_string(image.width) +
                     "x" + std::to_string(image.height) + " image with " +
                     std::to_string(image.pixels.size()) + " pixels");
  }
}

// --- encoders ----------------------------------------------------------------------------

std::vector<unsigned char> encode_png(const Image& image, float exposure, ToneMap op) {
  const std::vector<unsigned char> rgba = tonemap_srgb8(image, exposure, op);
  std::vector<unsigned char> out;
  auto append = [](void* context, void* data, int size) {
    auto* sink = static_cast<std::vector<unsigned char>*>(context);
    auto* bytes = static_cast<unsigned char*>(data);
    sink->insert(sink->end(), bytes, bytes + size);
  };
  if (!stbi_write_png_to_func(append, &out, image.width, image.height, 4, rgba.data(),
                              image.width * 4)) {
    out.clear();
  }
  return out;
}

// An OpenEXR output stream that collects the file in memory.
class MemoryOStream : public Imf::OStream {
 public:
  MemoryOStream() : Imf::OStream("<memory>") {}
  void write(const char c[], int n) override {
    if (pos_ + size_t(n) > bytes_.size()) bytes_.resize(pos_ + size_t(n));
    std::memcpy(bytes_.data() + pos_, c, size_t(n));
    pos_ += size_t(n);
  }
  uint64_t tellp() override { return pos_; }
  void seekp(uint64_t pos) override { pos_ = size_t(pos); }
  std::vector<unsigned char> take() { return std::move(bytes_); }

 private:
  std::vector<unsigned char> bytes_;
  size_t pos_ = 0;
};

// A value an EXR may hold: NaN as 0, and no further from 0 than `largest` (inf included).
float storable(float v, float largest) {
  return std::isnan(v) ? 0.0f : std::clamp(v, -largest, largest);
}

// Linear layers, ZIP-compressed (the Header default), half or float. Exposure is not applied:
// an EXR keeps the radiance as rendered (half clamped to its largest value, 65504).
std::vector<unsigned char> encode_exr(const std::vector<ExrLayer>& layers, ExrPixels pixels,
                                      const ExrAttributes& attributes = {}) {
  const bool as_half = pixels == ExrPixels::kHalf;
  const float largest = as_half ? float(HALF_MAX) : std::numeric_limits<float>::max();
  const int width = layers.front().image->width, height = layers.front().image->height;
  const size_t count = layers.front().image->pixels.size();
  Imf::Header header(width, height);
  for (const auto& [name, value] : attributes.strings)
    header.insert(name, Imf::StringAttribute(value));
  for (const auto& [name, value] : attributes.floats) header.insert(name, Imf::FloatAttribute(value));
  for (const auto& [name, m] : attributes.matrices)
    header.insert(name, Imf::M44fAttribute(Imath::M44f(m[0], m[1], m[2], m[3], m[4], m[5], m[6],
                                                       m[7], m[8], m[9], m[10], m[11], m[12],
                                                       m[13], m[14], m[15])));
  const Imf::PixelType type = as_half ? Imf::HALF : Imf::FLOAT;
  static const char* const kNames[4] = {"R", "G", "B", "A"};
  // Every channel's values and name, kept alive until the pixels are written.
  std::vector<std::vector<float>> floats;
  std::vector<std::vector<Imath::half>> halves;
  std::vector<std::string> names;
  for (const ExrLayer& layer : layers)
    for (int c = 0; c < layer.channels; ++c) {
      std::vector<float> values(count);
      for (size_t i = 0; i < count; ++i) values[i] = storable(layer.image->pixels[i][c], largest);
      floats.push_back(std::move(values));
      const std::string name = layer.names.empty() ? kNames[c] : layer.names[size_t(c)];
      names.push_back(layer.prefix.empty() ? name : layer.prefix + "." + name);
    }
  Imf::FrameBuffer frame;
  for (size_t k = 0; k < names.size(); ++k) {
    header.channels().insert(names[k], Imf::Channel(type));
    if (as_half) {
      halves.emplace_back(floats[k].begin(), floats[k].end());
      frame.insert(names[k], Imf::Slice(Imf::HALF, reinterpret_cast<char*>(halves.back().data()),
                                        sizeof(Imath::half), sizeof(Imath::half) * size_t(width)));
    } else {
      frame.insert(names[k], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(floats[k].data()),
                                        sizeof(float), sizeof(float) * size_t(width)));
    }
  }
  MemoryOStream stream;
  {
    // The line offset table is written when the file object is destroyed.
    Imf::OutputFile file(stream, header);
    file.setFrameBuffer(frame);
    file.writePixels(height);
  }
  return stream.take();
}

// --- decoders ----------------------------------------------------------------------------

[[noreturn]] void throw_read_error(const std::string& path, const std::string& what) {
  throw InputError("image " + quoted(path) + ": " + what);
}

Image decode_png(const std::string& path) {
  int w = 0, h = 0, channels = 0;
  std::unique_ptr<unsigned char, void (*)(void*)> data(
      stbi_load(path.c_str(), &w, &h, &channels, 4), stbi_image_free);
  if (!data) {
    const char* reason = stbi_failure_reason();
    throw_read_error(path,
                     std::string("cannot decode PNG: ") + (reason ? reason : "unknown error"));
  }
  Image image(w, h);
  const unsigned char* p = data.get();
  for (glm::vec4& px : image.pixels) {
    px = glm::vec4(p[0], p[1], p[2], p[3]) / 255.0f;
    p += 4;
  }
  return image;
}

// Read as 32-bit floats whatever the file stores (half or float), so float32 values beyond
// the half range come back as written; a missing alpha reads as 1.
Image decode_exr(const std::string& path, const std::string& layer = "") {
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    const int w = window.max.x - window.min.x + 1;
    const int h = window.max.y - window.min.y + 1;
    Image image(w, h);
    // The frame buffer is addressed by absolute pixel coordinates of the data window.
    char* origin = reinterpret_cast<char*>(image.pixels.data() - window.min.x -
                                           ptrdiff_t(window.min.y) * w);
    Imf::FrameBuffer frame;
    const char* const names[4] = {"R", "G", "B", "A"};
    const std::string prefix = layer.empty() ? "" : layer + ".";
    if (!layer.empty() && !file.header().channels().findChannel(prefix + "R"))
      throw std::runtime_error("no layer \"" + layer + "\" (no channel " + prefix + "R)");
    for (int c = 0; c < 4; ++c)
      frame.insert(prefix + names[c], Imf::Slice(Imf::FLOAT, origin + c * sizeof(float), sizeof(glm::vec4),
                                        sizeof(glm::vec4) * size_t(w), 1, 1, c == 3 ? 1.0 : 0.0));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    return image;
  } catch (const std::exception& e) {
    throw_read_error(path, std::string("cannot decode EXR: ") + e.what());
  }
}

// Identifies the file by its signature rather than its name.
ImageFormat sniff_format(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw_read_error(path, "file does not exist");
  if (fs::is_directory(path, ec)) throw_read_error(path, "is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw_read_error(path, std::string("cannot open: ") + std::strerror(errno));
  unsigned char magic[8] = {};
  in.read(reinterpret_cast<char*>(magic), sizeof magic);
  static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  static const unsigned char kExr[4] = {0x76, 0x2f, 0x31, 0x01};
  if (in.gcount() == 8 && std::memcmp(magic, kPng, 8) == 0) return ImageFormat::kPng;
  if (in.gcount() >= 4 && std::memcmp(magic, kExr, 4) == 0) return ImageFormat::kExr;
  return ImageFormat::kUnsupported;
}

}  // namespace

float luminance(const glm::vec4& rgb) {
  return 0.2126f * rgb.r + 0.7152f * rgb.g + 0.0722f * rgb.b;
}

std::vector<unsigned char> tonemap_srgb8(const Image& image, float exposure, ToneMap op) {
  std::vector<unsigned char> out(image.pixels.size() * 4);
  unsigned char* o = out.data();
  for (const glm::vec4& p : image.pixels) {
    // NaN and negatives give black (display_rgb), as in the display pass.
    const glm::vec3 c = glsl::display_rgb(int(op), glm::vec3(p) * exposure);
    o[0] = code_of(c.r);
    o[1] = code_of(c.g);
    o[2] = code_of(c.b);
    o[3] = 255;
    o += 4;
  }
  return out;
}

void write_image(const Image& image, const std::string& path, std::optional<float> exposure,
                 ExrPixels exr, ToneMap op) {
  const ImageFormat format = format_of(path);
  if (format == ImageFormat::kUnsupported) {
    throw InputError("image path " + quoted(path) + ": unsupported image format " +
                     kAllowedFormats);
  }
  check_writable_image(image, path);
  std::vector<unsigned char> bytes;
  try {
    bytes = format == ImageFormat::kPng
                ? encode_png(image, exposure ? *exposure : still_exposure(OutputParams{}, image), op)
                                        : encode_exr({ExrLayer{"", &image, 4}}, exr);
  } catch (const std::exception& e) {
    throw RuntimeError("cannot encode image " + quoted(path) + ": " + e.what());
  }
  if (bytes.empty()) throw RuntimeError("cannot encode image " + quoted(path));
  write_file_atomically(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

void write_exr_layers(const std::vector<ExrLayer>& layers, const std::string& path,
                      ExrPixels exr, const ExrAttributes& attributes) {
  if (format_of(path) != ImageFormat::kExr)
    throw InputError("image path " + quoted(path) + ": layers need an .exr file");
  if (layers.empty()) throw InputError("image " + quoted(path) + ": no layers to write");
  for (const ExrLayer& layer : layers) {
    if (!layer.image || layer.channels < 1 || layer.channels > 4 ||
        (!layer.names.empty() && layer.names.size() != size_t(layer.channels)))
      throw InputError("image " + quoted(path) + ": layer \"" + layer.prefix + "\" is malformed");
    if (layer.image->width != layers.front().image->width ||
        layer.image->height != layers.front().image->height)
      throw InputError("image " + quoted(path) + ": its layers differ in size");
    check_writable_image(*layer.image, path);
  }
  static const char* const kReserved[] = {"channels", "compression", "dataWindow",
                                          "displayWindow", "lineOrder", "pixelAspectRatio",
                                          "screenWindowCenter", "screenWindowWidth", "type",
                                          "tiles", "version", "chunkCount", "name"};
  const auto check_name = [&](const std::string& name) {
    for (const char* reserved : kReserved)
      if (name == reserved || name.empty())
        throw InputError("image " + quoted(path) + ": header attribute \"" + name +
                         "\" is reserved by OpenEXR");
  };
  for (const auto& a : attributes.strings) check_name(a.first);
  for (const auto& a : attributes.floats) check_name(a.first);
  for (const auto& a : attributes.matrices) check_name(a.first);
  std::vector<unsigned char> bytes;
  try {
    bytes = encode_exr(layers, exr, attributes);
  } catch (const std::exception& e) {
    throw RuntimeError("cannot encode image " + quoted(path) + ": " + e.what());
  }
  write_file_atomically(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

void check_output_path(const std::string& path, const std::string& parameter) {
  if (format_of(path) == ImageFormat::kUnsupported)
    throw InputError(parameter + " " + quoted(path) + ": unsupported image format " +
                     kAllowedFormats);
  check_output_file(path, parameter);
}

Image read_image(const std::string& path) {
  switch (sniff_format(path)) {
    case ImageFormat::kPng:
      return decode_png(path);
    case ImageFormat::kExr:
      return decode_exr(path);
    case ImageFormat::kUnsupported:
      break;
  }
  throw_read_error(path, std::string("not a PNG or EXR file ") + kAllowedFormats);
}

Image read_exr_layer(const std::string& path, const std::string& layer) {
  if (sniff_format(path) != ImageFormat::kExr) throw_read_error(path, "not an EXR file");
  return decode_exr(path, layer);
}

}  // namespace nephele
