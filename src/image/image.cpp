// nephele — image tone mapping, writers (PNG, EXR) and readers.
//
// Both writers encode into memory first and then go through one routine that writes the
// bytes to a temporary file beside the target and renames it over the target. That keeps
// every I/O error in one place, where it is checked (OpenEXR's file destructor swallows
// errors, and stbi_write_png ignores fwrite failures), and means that a failure never
// leaves a partial image or a temporary file behind.
#include "nephele/image.h"

#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfRgba.h>
#include <ImfRgbaFile.h>
#include <fcntl.h>
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

#include "nephele/error.h"

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

// The directory a file would be created in ("." for a bare file name).
fs::path directory_of(const std::string& path) {
  fs::path dir = fs::path(path).parent_path();
  return dir.empty() ? fs::path(".") : dir;
}

// Narkowicz 2015 fit of the ACES filmic curve; input must be finite and >= 0.
float aces_fit(float x) {
  const float y = (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
  return std::clamp(y, 0.0f, 1.0f);
}

// Exact sRGB opto-electronic transfer function (IEC 61966-2-1) for v in [0, 1].
float srgb_oetf(float v) {
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

// One linear channel (already exposed) to an 8-bit sRGB code value.
unsigned char encode_channel(float v) {
  // NaN and negatives give black; the curve saturates at ~7.2, so clamping far above that
  // only keeps the products inside the fit finite (inf would give inf/inf = NaN).
  if (!(v > 0.0f)) v = 0.0f;
  v = std::min(v, 1.0e4f);
  return static_cast<unsigned char>(std::lround(srgb_oetf(aces_fit(v)) * 255.0f));
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

std::vector<unsigned char> encode_png(const Image& image, float exposure) {
  const std::vector<unsigned char> rgba = tonemap_srgb8(image, exposure);
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

// Linear half-float RGBA, ZIP-compressed (the Header default). Exposure is not applied:
// an EXR keeps the radiance as rendered.
std::vector<unsigned char> encode_exr(const Image& image) {
  std::vector<Imf::Rgba> halves(image.pixels.size());
  for (size_t i = 0; i < halves.size(); ++i) {
    const glm::vec4& p = image.pixels[i];
    halves[i] = Imf::Rgba(p.r, p.g, p.b, p.a);
  }
  MemoryOStream stream;
  {
    // The line offset table is written when the file object is destroyed.
    Imf::RgbaOutputFile file(stream, Imf::Header(image.width, image.height), Imf::WRITE_RGBA);
    file.setFrameBuffer(halves.data(), 1, size_t(image.width));
    file.writePixels(image.height);
  }
  return stream.take();
}

// --- atomic file replacement -------------------------------------------------------------

// Removes the temporary file unless released (after a successful rename).
class TempFile {
 public:
  explicit TempFile(std::string path) : path_(std::move(path)) {}
  ~TempFile() {
    if (!path_.empty()) ::unlink(path_.c_str());
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  const std::string& path() const { return path_; }
  void release() { path_.clear(); }

 private:
  std::string path_;
};

[[noreturn]] void throw_io_error(const std::string& path, const std::string& what, int err) {
  throw RuntimeError("cannot write image " + quoted(path) + ": " + what + ": " +
                     std::strerror(err));
}

// Creates a new, uniquely named file beside `path` (".<name>.tmp-<pid>-<n>"), open for
// writing. Mode 0666 before the umask, as for any file the program creates.
int create_temp_beside(const std::string& path, std::string& temp_path) {
  static std::atomic<unsigned> counter{0};
  const fs::path dir = directory_of(path);
  const std::string name = fs::path(path).filename().string();
  for (int attempt = 0; attempt < 100; ++attempt) {
    temp_path = (dir / ("." + name + ".tmp-" + std::to_string(::getpid()) + "-" +
                        std::to_string(counter++)))
                    .string();
    const int fd = ::open(temp_path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0 || errno != EEXIST) return fd;
  }
  errno = EEXIST;
  return -1;
}

void write_all(int fd, const std::vector<unsigned char>& bytes, const std::string& path) {
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw_io_error(path, "write failed", errno);
    if (n == 0) throw_io_error(path, "write failed", ENOSPC);
    done += size_t(n);
  }
}

void replace_file(const std::string& path, const std::vector<unsigned char>& bytes) {
  std::string temp_path;
  const int fd = create_temp_beside(path, temp_path);
  if (fd < 0) {
    const int err = errno;  // before building the message can touch it
    throw_io_error(path, "cannot create a file in " + quoted(directory_of(path).string()), err);
  }
  TempFile temp(temp_path);
  try {
    write_all(fd, bytes, path);
  } catch (...) {
    ::close(fd);
    throw;
  }
  if (::close(fd) != 0) throw_io_error(path, "write failed", errno);
  if (::rename(temp.path().c_str(), path.c_str()) != 0) {
    throw_io_error(path, "cannot replace the file", errno);
  }
  temp.release();
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

Image decode_exr(const std::string& path) {
  try {
    Imf::RgbaInputFile file(path.c_str());
    const Imath::Box2i window = file.dataWindow();
    const int w = window.max.x - window.min.x + 1;
    const int h = window.max.y - window.min.y + 1;
    std::vector<Imf::Rgba> halves(size_t(w) * size_t(h));
    // The frame buffer is addressed by absolute pixel coordinates of the data window.
    Imf::Rgba* origin = halves.data() - window.min.x - ptrdiff_t(window.min.y) * w;
    file.setFrameBuffer(origin, 1, size_t(w));
    file.readPixels(window.min.y, window.max.y);
    Image image(w, h);
    for (size_t i = 0; i < halves.size(); ++i) {
      const Imf::Rgba& p = halves[i];
      image.pixels[i] = glm::vec4(float(p.r), float(p.g), float(p.b), float(p.a));
    }
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

std::vector<unsigned char> tonemap_srgb8(const Image& image, float exposure) {
  std::vector<unsigned char> out(image.pixels.size() * 4);
  unsigned char* o = out.data();
  for (const glm::vec4& p : image.pixels) {
    o[0] = encode_channel(p.r * exposure);
    o[1] = encode_channel(p.g * exposure);
    o[2] = encode_channel(p.b * exposure);
    o[3] = 255;
    o += 4;
  }
  return out;
}

float auto_exposure(float exposure, double mean_luminance) {
  const double gain = std::pow(kDayMeanLuminance / std::max(mean_luminance, 1e-30), 0.85);
  return float(exposure * std::min(gain, 1e7));
}

void write_image(const Image& image, const std::string& path, float exposure) {
  const ImageFormat format = format_of(path);
  if (format == ImageFormat::kUnsupported) {
    throw InputError("image path " + quoted(path) + ": unsupported image format " +
                     kAllowedFormats);
  }
  check_writable_image(image, path);
  std::vector<unsigned char> bytes;
  try {
    bytes = format == ImageFormat::kPng ? encode_png(image, exposure) : encode_exr(image);
  } catch (const std::exception& e) {
    throw RuntimeError("cannot encode image " + quoted(path) + ": " + e.what());
  }
  if (bytes.empty()) throw RuntimeError("cannot encode image " + quoted(path));
  replace_file(path, bytes);
}

void check_output_path(const std::string& path, const std::string& parameter) {
  const std::string prefix = parameter + " " + quoted(path) + ": ";
  if (format_of(path) == ImageFormat::kUnsupported) {
    throw InputError(prefix + "unsupported image format " + kAllowedFormats);
  }
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw InputError(prefix + "is a directory");
  const fs::path dir = directory_of(path);
  if (!fs::exists(dir, ec)) {
    throw InputError(prefix + "directory " + quoted(dir.string()) + " does not exist");
  }
  if (!fs::is_directory(dir, ec)) {
    throw InputError(prefix + quoted(dir.string()) + " is not a directory");
  }
  // Creating the temporary file and renaming it needs write and search permission.
  if (::access(dir.c_str(), W_OK | X_OK) != 0) {
    throw InputError(prefix + "directory " + quoted(dir.string()) + " is not writable");
  }
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

}  // namespace nephele
