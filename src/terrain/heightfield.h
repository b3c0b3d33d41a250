// The terrain's heights on a regular east-north grid (issue 24), read from a 16-bit PNG, an
// EXR, a GeoTIFF elevation model (GDAL) or an OBJ mesh, or made by the procedural `mountains`.
// No Vulkan: render/modules/terrain.h puts it on the device.
#pragma once

#include <glm/vec2.hpp>

#include <cstddef>
#include <string>
#include <vector>

#include "nephele/scene.h"

namespace nephele::terrain {

// The most grid points a heightfield may hold a side (16384^2 floats: 1 GiB on the host and
// the device; the largest 2D image many devices take).
constexpr int kMaxSide = 16384;

// Heights in metres above the scene's ground (the sphere at location.altitude_m), at
// width x height points spanning extent_m (east-west, north-south) about center_m. Row 0 is
// the north edge, column 0 the west edge (as an image of a map is stored).
struct Heightfield {
  int width = 0;
  int height = 0;
  glm::vec2 extent_m{0.0f};
  glm::vec2 center_m{0.0f};
  std::vector<float> height_m;

  float at(int x, int y) const { return height_m[size_t(y) * size_t(width) + size_t(x)]; }
  // Bilinear between the grid points; `fallback` outside the extent.
  float sample(glm::vec2 east_north_m, float fallback) const;
  float min_height_m() const;
  float max_height_m() const;
  // The grid's spacing east-west and north-south (m).
  glm::vec2 spacing_m() const;
};

// The scene's terrain (scene.terrain), or an empty heightfield when it has none. Throws
// InputError naming terrain.file (or `file_key`, the flag the user gave) with the value and what
// is allowed: an unreadable or malformed file, a PNG that is not 16-bit grey, a GeoTIFF without
// georeferencing, more than kMaxSide points a side.
Heightfield load_heightfield(const Scene& scene, const std::string& file_key = "terrain.file");

// Why the file cannot be a heightfield, told from its name and header ("" when it may be one):
// an unknown extension, an unreadable file, a PNG that is not 16-bit grey, an EXR without a
// height channel, a GeoTIFF without georeferencing, more than kMaxSide points a side.
std::string heightfield_file_problem(const std::string& path);

// The procedural range: ridged fractal noise, eroded towards the valleys, its highest point
// terrain.height_m above terrain.base_m, falling to base_m at the extent's edges.
Heightfield make_mountains(const TerrainParams& params);

// The heights' maxima over blocks of `block` x `block` cells (a cell spans grid points i..i+1,
// so a block's maximum covers every bilinear height inside it), ceil((n - 1) / block) per axis.
std::vector<float> block_maxima(const Heightfield& field, int block, int& blocks_x, int& blocks_y);

}  // namespace nephele::terrain
