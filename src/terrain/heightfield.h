// The terrain's heights on a regular east-north grid (issue 24), read from a 16-bit PNG, an
// EXR, a GeoTIFF elevation model (GDAL) or an OBJ mesh, or made by the procedural `mountains`.
// No Vulkan: render/modules/terrain/terrain.h puts it on the device.
#pragma once

#include <glm/vec2.hpp>
#include <glm/ext/vector_int2.hpp>

#include <cstddef>
#include <string>
#include <vector>

#include "nephele/scene.h"

namespace nephele::terrain {

// The most grid points a heightfield file may hold a side, checked from its header before it is
// decoded: 8192^2 floats are 256 MiB, and the terrain module holds them with their max pyramid
// several times over while it uploads them (about 1.5 GiB at this limit on lavapipe, whose
// device memory is the process's).
constexpr int kMaxSide = 8192;

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

// What a heightfield file's name must end with (a message's "what is allowed").
inline constexpr const char* kHeightfieldExtensions =
    "must name a .png (16-bit grey), .exr, .tif/.tiff (GeoTIFF) or .obj file";
bool has_heightfield_extension(const std::string& path);

// Why the file cannot be a heightfield, told from its name and header ("" when it may be one):
// an unknown extension, an unreadable file, a PNG that is not 16-bit grey, an EXR without a
// height channel, a GeoTIFF without georeferencing, more than kMaxSide points a side.
std::string heightfield_file_problem(const std::string& path);

// The procedural range: ridged fractal noise, eroded towards the valleys, its highest point
// terrain.height_m above terrain.base_m, falling to base_m at the extent's edges.
Heightfield make_mountains(const TerrainParams& params);

// The heights' maxima over squares of cells, for rays to skip the space above the terrain
// (terrain_inc.glsl): level k >= 1 holds, per square of 2^k x 2^k cells (a cell spans grid
// points i..i+1, so its bilinear heights are bounded by its four corners), the largest height
// in it; ceil((n - 1) / 2^k) squares per axis, up to the level of one square. The levels are
// packed into one image: level 1 at the origin, levels 2 and up stacked down a column to its
// right (offset() says where).
struct MaxPyramid {
  int cells_x = 0, cells_y = 0;  // the heightfield's cells (points - 1)
  int levels = 0;                // the top level (1 square); level 0 is the cells themselves
  int width = 0, height = 0;     // the packed image
  std::vector<float> texels;

  glm::ivec2 size(int level) const;    // squares per axis at a level >= 1
  glm::ivec2 offset(int level) const;  // where a level >= 1 starts in the image
  float at(int level, int x, int y) const {
    const glm::ivec2 o = offset(level);
    return texels[size_t(o.y + y) * size_t(width) + size_t(o.x + x)];
  }
};

MaxPyramid max_pyramid(const Heightfield& field);

}  // namespace nephele::terrain
