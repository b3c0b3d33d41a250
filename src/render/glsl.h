// The pure GLSL functions of shaders/common/*_inc.glsl compiled as C++ (Bruneton's trick):
// the CPU side computes per-frame lighting with them and the tests check them against closed
// forms, so the shaders and their tests share one definition.
#pragma once

#include <algorithm>

#include <glm/glm.hpp>

// The functions get internal linkage (unnamed namespace): each file that includes this one
// has its own copy, as a shader does.
// Each includer uses only some of them.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
namespace nephele::glsl {
using namespace glm;

// GLSL's sampler2D for the functions that take a table (atmosphere_lut_inc.glsl): RGBA texels,
// row by row, filtered bilinearly with the edges clamped, as the GPU's samplers are set up.
struct sampler2D {
  const vec4* texels = nullptr;
  int width = 0;
  int height = 0;
};

// Any float is safe: NaN reads the first texel, as the clamped edges do beyond the table.
inline float texel_coordinate(float u, int size) {
  const float x = u * float(size) - 0.5f;
  return x >= 0.0f ? std::min(x, float(size - 1)) : 0.0f;  // NaN fails x >= 0
}

inline vec4 textureLod(const sampler2D& s, vec2 uv, float /*lod*/) {
  const float x = texel_coordinate(uv.x, s.width);
  const float y = texel_coordinate(uv.y, s.height);
  const int x0 = int(x), y0 = int(y);
  const int x1 = min(x0 + 1, s.width - 1), y1 = min(y0 + 1, s.height - 1);
  const float fx = x - float(x0), fy = y - float(y0);
  const auto at = [&](int i, int j) { return s.texels[size_t(j) * size_t(s.width) + size_t(i)]; };
  return mix(mix(at(x0, y0), at(x1, y0), fx), mix(at(x0, y1), at(x1, y1), fx), fy);
}

namespace {
// In dependency order (clang-format would sort them).
// clang-format off
#include "common/math_inc.glsl"
#include "common/phase_inc.glsl"
#include "common/droplets_inc.glsl"
#include "common/sun_disk_inc.glsl"
#include "common/noise_inc.glsl"
#include "common/weather_inc.glsl"
#include "common/atmosphere_inc.glsl"
#include "common/atmosphere_lut_inc.glsl"
#include "common/preetham_inc.glsl"
#include "common/sky_view_inc.glsl"
#include "common/clouds_inc.glsl"
#include "common/precipitation_inc.glsl"
#include "common/lightning_inc.glsl"
#include "common/slab_light_inc.glsl"
#include "common/light_volume_inc.glsl"
#include "common/voxel_inc.glsl"
#include "common/particle_inc.glsl"
#include "common/impostor_inc.glsl"
#include "common/classic_inc.glsl"
#include "common/tonemap_inc.glsl"
#include "common/sh_inc.glsl"
#include "common/lebedev_inc.glsl"
// clang-format on
}  // namespace
}  // namespace nephele::glsl
#pragma GCC diagnostic pop
