#include "terrain/heightfield.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <stb/stb_image.h>
#include <glm/glm.hpp>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <limits>
#include <memory>

#include "image/input_images.h"
#include "io/obj_text.h"
#include "nephele/error.h"
#include "scene/scene_fields.h"
#include "terrain/geotiff.h"

namespace nephele::terrain {

float Heightfield::sample(glm::vec2 p, float fallback) const {
  const glm::vec2 west_north = center_m + glm::vec2(-0.5f, 0.5f) * extent_m;
  const float gx = (p.x - west_north.x) / extent_m.x * float(width - 1);
  const float gy = (west_north.y - p.y) / extent_m.y * float(height - 1);
  if (!(gx >= 0.0f && gy >= 0.0f && gx <= float(width - 1) && gy <= float(height - 1)))
    return fallback;
  const int x0 = std::min(int(gx), width - 2), y0 = std::min(int(gy), height - 2);
  const float fx = gx - float(x0), fy = gy - float(y0);
  const float top = at(x0, y0) + (at(x0 + 1, y0) - at(x0, y0)) * fx;
  const float bottom = at(x0, y0 + 1) + (at(x0 + 1, y0 + 1) - at(x0, y0 + 1)) * fx;
  return top + (bottom - top) * fy;
}

float Heightfield::min_height_m() const {
  return height_m.empty() ? 0.0f : *std::min_element(height_m.begin(), height_m.end());
}

float Heightfield::max_height_m() const {
  return height_m.empty() ? 0.0f : *std::max_element(height_m.begin(), height_m.end());
}

glm::vec2 Heightfield::spacing_m() const {
  return extent_m / glm::vec2(float(width - 1), float(height - 1));
}

glm::ivec2 MaxPyramid::size(int level) const {
  return glm::ivec2((cells_x + (1 << level) - 1) >> level, (cells_y + (1 << level) - 1) >> level);
}

glm::ivec2 MaxPyramid::offset(int level) const {
  if (level <= 1) return glm::ivec2(0);
  int y = 0;
  for (int k = 2; k < level; ++k) y += size(k).y;
  return glm::ivec2(size(1).x, y);
}

MaxPyramid max_pyramid(const Heightfield& field) {
  MaxPyramid p;
  p.cells_x = field.width - 1;
  p.cells_y = field.height - 1;
  p.levels = 1;
  while (p.size(p.levels).x > 1 || p.size(p.levels).y > 1) ++p.levels;
  p.width = p.size(1).x + (p.levels >= 2 ? p.size(2).x : 0);
  p.height = p.size(1).y;
  if (p.levels >= 2) p.height = std::max(p.height, p.offset(p.levels).y + p.size(p.levels).y);
  p.texels.assign(size_t(p.width) * size_t(p.height), 0.0f);
  const auto put = [&](int level, int x, int y, float v) {
    const glm::ivec2 o = p.offset(level);
    p.texels[size_t(o.y + y) * size_t(p.width) + size_t(o.x + x)] = v;
  };
  // Level 1: the points of each 2 x 2 cells (3 x 3 points, fewer at the far edges).
  const glm::ivec2 one = p.size(1);
  for (int y = 0; y < one.y; ++y)
    for (int x = 0; x < one.x; ++x) {
      float m = -std::numeric_limits<float>::max();
      for (int py = 2 * y; py <= std::min(2 * y + 2, field.height - 1); ++py)
        for (int px = 2 * x; px <= std::min(2 * x + 2, field.width - 1); ++px) m = std::max(m, field.at(px, py));
      put(1, x, y, m);
    }
  for (int level = 2; level <= p.levels; ++level) {
    const glm::ivec2 n = p.size(level), below = p.size(level - 1);
    for (int y = 0; y < n.y; ++y)
      for (int x = 0; x < n.x; ++x) {
        float m = -std::numeric_limits<float>::max();
        for (int cy = 2 * y; cy <= std::min(2 * y + 1, below.y - 1); ++cy)
          for (int cx = 2 * x; cx <= std::min(2 * x + 1, below.x - 1); ++cx) m = std::max(m, p.at(level - 1, cx, cy));
        put(level, x, y, m);
      }
  }
  return p;
}

namespace {

[[noreturn]] void fail(const std::string& key, const std::string& path, const std::string& why) {
  throw InputError(key + " '" + shorten_path_for_message(path) + "': " + why);
}

using scene_detail::ends_with_ignoring_case;

// Why a grid of w x h points cannot be a heightfield; "" when it can.
std::string size_problem(long long w, long long h) {
  const std::string size = std::to_string(w) + " x " + std::to_string(h) + " points: ";
  if (w < 2 || h < 2) return size + "a heightfield needs at least 2 x 2";
  if (w > kMaxSide || h > kMaxSide)
    return size + "at most " + std::to_string(kMaxSide) + " a side are allowed (resample it smaller)";
  return "";
}

// The EXR channel heights are read from: Y, R, Z or height, or a file's only channel; "" none.
std::string exr_height_channel(const std::vector<std::string>& names) {
  for (const char* name : {"Y", "R", "Z", "height"})
    if (std::find(names.begin(), names.end(), name) != names.end()) return name;
  return names.size() == 1 ? names.front() : "";
}

std::string png_problem(const std::string& path) {
  ImageHeader header;
  if (std::string why = read_image_header(path, header, kMaxSide, "points"); !why.empty()) return why;
  if (header.exr) return "is an EXR file named .png";
  if (header.bits != 16)
    return std::string(header.bits == 8 ? "is an " : "is a ") + std::to_string(header.bits) +
           "-bit PNG; heights need a 16-bit greyscale PNG (256 levels are too coarse for a terrain)";
  if (header.channels != 1)
    return "has " + std::to_string(header.channels) + " channels; heights need a 16-bit greyscale PNG (1 channel)";
  return size_problem(header.width, header.height);
}

// The header read without OpenEXR (which sizes its tables as the file declares), then the
// channel heights are read from.
std::string exr_problem(const std::string& path) {
  ImageHeader header;
  if (std::string why = read_image_header(path, header, kMaxSide, "points"); !why.empty()) return why;
  if (!header.exr) return "is a PNG file named .exr";
  if (std::string why = size_problem(header.width, header.height); !why.empty()) return why;
  if (exr_height_channel(header.channel_names).empty())
    return "has no Y, R, Z or height channel (heights are read from one of them)";
  return "";
}

// Values scaled so that the largest is base + height (PNG, EXR).
Heightfield scaled(const TerrainParams& t, int w, int h, std::vector<float> values) {
  float largest = 0.0f;
  for (float v : values) largest = std::max(largest, v);
  const float scale = largest > 0.0f ? t.height_m / largest : 0.0f;
  for (float& v : values) v = t.base_m + std::max(v, 0.0f) * scale;
  return Heightfield{w, h, t.extent_m, t.center_m, std::move(values)};
}

Heightfield read_png(const TerrainParams& t, const std::string& key) {
  ImageHeader header;
  if (const std::string why = read_image_header(t.file, header, kMaxSide, "points"); !why.empty())
    fail(key, t.file, why);
  if (const std::string why = png_data_problem(t.file, header); !why.empty()) fail(key, t.file, why);
  int w = 0, h = 0, channels = 0;
  std::unique_ptr<stbi_us, void (*)(void*)> pixels(stbi_load_16(t.file.c_str(), &w, &h, &channels, 1),
                                                   stbi_image_free);
  if (!pixels) {
    const char* reason = stbi_failure_reason();
    fail(key, t.file, std::string("cannot decode the PNG (") + (reason ? reason : "unknown error") + ")");
  }
  std::vector<float> values(size_t(w) * size_t(h));
  for (size_t i = 0; i < values.size(); ++i) values[i] = float(pixels.get()[i]);
  return scaled(t, w, h, std::move(values));
}

Heightfield read_exr(const TerrainParams& t, const std::string& key) {
  const std::string& path = t.file;
  try {
    Imf::InputFile file(path.c_str());
    std::vector<std::string> names;
    for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it)
      names.emplace_back(it.name());
    const std::string channel = exr_height_channel(names);
    const Imath::Box2i window = file.header().dataWindow();
    const long long w = window.max.x - window.min.x + 1, h = window.max.y - window.min.y + 1;
    std::vector<float> values(size_t(w) * size_t(h));
    char* origin = reinterpret_cast<char*>(values.data() - window.min.x - ptrdiff_t(window.min.y) * w);
    Imf::FrameBuffer frame;
    frame.insert(channel, Imf::Slice(Imf::FLOAT, origin, sizeof(float), sizeof(float) * size_t(w)));
    file.setFrameBuffer(frame);
    file.readPixels(window.min.y, window.max.y);
    for (float v : values)
      if (!std::isfinite(v)) fail(key, path, "holds a height that is not finite");
    return scaled(t, int(w), int(h), std::move(values));
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    fail(key, path, std::string("cannot read the EXR: ") + e.what());
  }
}

// The mesh's surface seen from above (x east, y up, -z north), on a grid of `resolution`
// points along its longer side centred on center_m: the highest triangle over each point,
// the mesh's lowest height where none is.
Heightfield read_obj(const TerrainParams& t, const std::string& key) {
  const std::string& path = t.file;
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warning, error;
  std::istringstream in(read_obj_text(path, key + " '" + shorten_path_for_message(path) + "': "));
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &error, &in, nullptr, true) ||
      attrib.vertices.size() < 9)
    fail(key, path,
         "is not a readable OBJ mesh (" + obj_error_for_message(error, "no triangles") + ")");
  std::vector<glm::vec3> points;  // east, north, up
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (size_t v = 0; v + 2 < attrib.vertices.size(); v += 3) {
    const glm::vec3 p(attrib.vertices[v], -attrib.vertices[v + 2], attrib.vertices[v + 1]);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      fail(key, path, "vertex " + std::to_string(v / 3 + 1) + " is not finite");
    points.push_back(p);
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const glm::vec2 size(hi.x - lo.x, hi.y - lo.y);
  if (!(size.x > 0.0f && size.y > 0.0f))
    fail(key, path, "is flat seen from above (its x or z extent is 0); a terrain mesh spans x and z");
  const float step = std::max(size.x, size.y) / float(t.resolution - 1);
  const int w = std::max(2, int(std::ceil(size.x / step)) + 1), h = std::max(2, int(std::ceil(size.y / step)) + 1);
  Heightfield field{w, h, glm::vec2(float(w - 1), float(h - 1)) * step, t.center_m,
                    std::vector<float>(size_t(w) * size_t(h), -std::numeric_limits<float>::max())};
  const glm::vec2 mid = 0.5f * (glm::vec2(lo) + glm::vec2(hi));
  const auto grid = [&](const glm::vec3& p) {  // grid coordinates (x east, y south)
    return glm::vec2((p.x - mid.x) / step + 0.5f * float(w - 1), (mid.y - p.y) / step + 0.5f * float(h - 1));
  };
  for (const tinyobj::shape_t& shape : shapes)
    for (size_t i = 0; i + 2 < shape.mesh.indices.size(); i += 3) {
      glm::vec3 p[3];
      glm::vec2 g[3];
      for (int c = 0; c < 3; ++c) {
        const int v = shape.mesh.indices[i + c].vertex_index;
        if (v < 0 || size_t(v) >= points.size()) fail(key, path, "a face refers to a missing vertex");
        p[c] = points[size_t(v)];
        g[c] = grid(p[c]);
      }
      const float area = (g[1].x - g[0].x) * (g[2].y - g[0].y) - (g[2].x - g[0].x) * (g[1].y - g[0].y);
      if (std::abs(area) < 1e-12f) continue;  // seen edge-on from above
      const int x0 = std::max(0, int(std::ceil(std::min({g[0].x, g[1].x, g[2].x}))));
      const int x1 = std::min(w - 1, int(std::floor(std::max({g[0].x, g[1].x, g[2].x}))));
      const int y0 = std::max(0, int(std::ceil(std::min({g[0].y, g[1].y, g[2].y}))));
      const int y1 = std::min(h - 1, int(std::floor(std::max({g[0].y, g[1].y, g[2].y}))));
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) {
          const glm::vec2 q{float(x), float(y)};
          const float b1 = ((q.x - g[0].x) * (g[2].y - g[0].y) - (g[2].x - g[0].x) * (q.y - g[0].y)) / area;
          const float b2 = ((g[1].x - g[0].x) * (q.y - g[0].y) - (q.x - g[0].x) * (g[1].y - g[0].y)) / area;
          const float b0 = 1.0f - b1 - b2;
          if (b0 < -1e-5f || b1 < -1e-5f || b2 < -1e-5f) continue;
          float& out = field.height_m[size_t(y) * size_t(w) + size_t(x)];
          out = std::max(out, b0 * p[0].z + b1 * p[1].z + b2 * p[2].z);
        }
    }
  for (float& v : field.height_m)
    if (v == -std::numeric_limits<float>::max()) v = lo.z;
  return field;
}

// Hash of a lattice point to [-1, 1].
float lattice(int x, int y, uint32_t seed) {
  uint32_t h = uint32_t(x) * 0x8da6b343u ^ uint32_t(y) * 0xd8163841u ^ seed * 0xcb1ab31fu;
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  h ^= h >> 15;
  return float(h & 0xffffffu) / float(0x7fffff) - 1.0f;
}

// Value noise with a quintic fade, in [-1, 1].
float value_noise(glm::vec2 p, uint32_t seed) {
  const int x = int(std::floor(p.x)), y = int(std::floor(p.y));
  const glm::vec2 f = p - glm::vec2(float(x), float(y));
  const glm::vec2 u = f * f * f * (f * (f * 6.0f - 15.0f) + 10.0f);
  const float a = lattice(x, y, seed), b = lattice(x + 1, y, seed);
  const float c = lattice(x, y + 1, seed), d = lattice(x + 1, y + 1, seed);
  return a + (b - a) * u.x + (c - a) * u.y + (a - b - c + d) * u.x * u.y;
}

}  // namespace

Heightfield make_mountains(const TerrainParams& t) {
  const int n = t.resolution;
  Heightfield field{n, n, t.extent_m, t.center_m, std::vector<float>(size_t(n) * size_t(n))};
  // Ridges about 6 km apart over the range, five octaves of ridged noise (1 - |noise|)^2, each
  // weighted by the one above it so the valleys stay smooth (Musgrave's ridged multifractal).
  const float ridge_m = 6000.0f;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const glm::vec2 p_m = glm::vec2(float(x) / float(n - 1) - 0.5f, 0.5f - float(y) / float(n - 1)) * t.extent_m;
      glm::vec2 p = p_m / ridge_m;
      // Warp the domain so the ridges wander.
      p += 0.35f * glm::vec2(value_noise(p * 0.7f, t.seed + 11u), value_noise(p * 0.7f + 5.2f, t.seed + 12u));
      float sum = 0.0f, amplitude = 1.0f, weight = 1.0f, norm = 0.0f;
      for (int octave = 0; octave < 6; ++octave) {
        float r = 1.0f - std::abs(value_noise(p, t.seed + uint32_t(octave)));
        r *= r * weight;
        weight = std::clamp(r * 1.6f, 0.0f, 1.0f);
        sum += r * amplitude;
        norm += amplitude;
        amplitude *= 0.5f;
        p = glm::vec2(1.6f * p.x - 1.2f * p.y, 1.2f * p.x + 1.6f * p.y);  // rotated, doubled
      }
      // Fall to the base over the outer sixth of the extent, so the range stands on the plain.
      const glm::vec2 edge = glm::abs(p_m / t.extent_m) * 2.0f;
      const float fade = glm::clamp((1.0f - std::max(edge.x, edge.y)) * 6.0f, 0.0f, 1.0f);
      field.height_m[size_t(y) * size_t(n) + size_t(x)] = sum / norm * fade * fade * (3.0f - 2.0f * fade);
    }
  const float top = field.max_height_m();
  for (float& h : field.height_m) h = t.base_m + (top > 0.0f ? h / top * t.height_m : 0.0f);
  return field;
}

bool has_heightfield_extension(const std::string& path) {
  for (const char* suffix : {".png", ".exr", ".tif", ".tiff", ".obj"})
    if (ends_with_ignoring_case(path, suffix)) return true;
  return false;
}

std::string heightfield_file_problem(const std::string& path) {
  if (ends_with_ignoring_case(path, ".png")) return png_problem(path);
  if (ends_with_ignoring_case(path, ".exr")) return exr_problem(path);
  if (ends_with_ignoring_case(path, ".tif") || ends_with_ignoring_case(path, ".tiff")) return geotiff_problem(path);
  if (ends_with_ignoring_case(path, ".obj")) return "";
  return kHeightfieldExtensions;
}

Heightfield load_heightfield(const Scene& scene, const std::string& file_key) {
  const TerrainParams& t = scene.terrain;
  if (t.preset == "mountains") return make_mountains(t);
  if (t.file.empty()) return {};
  if (const std::string why = heightfield_file_problem(t.file); !why.empty()) fail(file_key, t.file, why);
  if (ends_with_ignoring_case(t.file, ".png")) return read_png(t, file_key);
  if (ends_with_ignoring_case(t.file, ".exr")) return read_exr(t, file_key);
  if (ends_with_ignoring_case(t.file, ".obj")) return read_obj(t, file_key);
  return read_geotiff(scene, file_key);
}

}  // namespace nephele::terrain
