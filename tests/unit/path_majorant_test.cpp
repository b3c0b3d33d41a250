// The noise clouds' majorant grid (render/path_majorant.h) against the field's base shape
// evaluated as the shader does, on a random noise tile: at random points of every bin of both
// layers, under a wind that shears and skews the columns, the bound is never exceeded, and
// it is 0 where no texel can reach a cloud and below the layer's flat bound elsewhere.
#include <gtest/gtest.h>

#include <random>

#include "render/glsl.h"
#include "render/path_majorant.h"

namespace {

using nephele::gpu::FrameParams;
namespace glsl = nephele::glsl;

constexpr int kSize = 64;  // a smaller tile than the renderer's: the bounds' logic does not care

struct Tile {
  std::vector<uint8_t> rgba;
  // Trilinear, repeating, as the device samples a texture of unit coordinates.
  glm::vec4 sample(glm::vec3 u) const {
    const glm::vec3 t = u * float(kSize) - 0.5f;
    const glm::ivec3 i0(glm::floor(t));
    const glm::vec3 f = t - glm::floor(t);
    glm::vec4 sum(0.0f);
    for (int c = 0; c < 8; ++c) {
      const glm::ivec3 o(c & 1, (c >> 1) & 1, (c >> 2) & 1);
      const glm::ivec3 i = ((i0 + o) % kSize + kSize) % kSize;
      const uint8_t* p = &rgba[((size_t(i.z) * kSize + size_t(i.y)) * kSize + size_t(i.x)) * 4];
      const float w = (o.x ? f.x : 1.0f - f.x) * (o.y ? f.y : 1.0f - f.y) * (o.z ? f.z : 1.0f - f.z);
      sum += w * glm::vec4(p[0], p[1], p[2], p[3]) / 255.0f;
    }
    return sum;
  }
};

TEST(PathMajorant, TheGridBoundsTheBaseShapeEverywhere) {
  std::mt19937 rng(7);
  Tile tile;
  tile.rgba.resize(size_t(kSize) * kSize * kSize * 4);
  // Clouds (R high) in one column of blocks in 16, scattered over it; elsewhere R low and W
  // high, so that the noise there stays under 1 - coverage and the main layer's cells that
  // reach only such blocks bound it at 0.
  for (int z = 0; z < kSize; ++z)
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        uint8_t* t = &tile.rgba[((size_t(z) * kSize + size_t(y)) * kSize + size_t(x)) * 4];
        const bool column = (x / nephele::kNoiseBlock) % 4 == 1 && (y / nephele::kNoiseBlock) % 4 == 2;
        const bool cloud = column && rng() % 5 == 0;
        t[0] = uint8_t(cloud ? 150 + rng() % 106 : rng() % 30);
        for (int c = 1; c < 4; ++c) t[c] = uint8_t(cloud ? rng() % 256 : 230 + rng() % 26);
      }
  const nephele::NoiseBlockBounds bounds = nephele::noise_block_bounds(tile.rgba, kSize);

  FrameParams f{};
  const float planet = 6360e3f;
  f.radii_m.x = planet;
  f.cloud_shape.z = 0.5f;
  f.cloud_noise.x = 1.0f / 6000.0f;  // a tile every 6 km: 94 m texels, 750 m blocks
  f.cloud_layers[0] = {glm::vec4(planet + 1500.0f, planet + 4000.0f, 0.0f, 0.0f),
                       glm::vec4(0.4f, 0.6f, 0.5f, 0.0f), glm::vec4(800.0f, -300.0f, 8.0f, 2.0f)};
  f.cloud_layers[1] = {glm::vec4(planet + 6000.0f, planet + 7000.0f, 0.0f, 0.0f),
                       glm::vec4(0.8f, 0.3f, 0.5f, 0.5f), glm::vec4(0.0f, 0.0f, 15.0f, 4.0f)};
  f.cloud_wind = glm::vec4(1.0f, -0.5f, 200.0f, 600.0f);  // shear, skew (s), shear time (s)
  const float cell = 500.0f;
  const glm::vec2 corner(-0.5f * cell * nephele::gpu::PATH_GRID_XY);
  const std::vector<float> grid = nephele::noise_majorant_grid(f, bounds, corner, cell);

  const int n = nephele::gpu::PATH_GRID_XY, bins = nephele::gpu::PATH_GRID_BINS;
  int zero_cells = 0, checked = 0;
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int l = 0; l < 2; ++l) {
    const nephele::gpu::CloudLayerGpu& layer = f.cloud_layers[l];
    const float lo = layer.radii_m.x - nephele::gpu::PATH_SHELL_PAD_M;
    const float hi = layer.radii_m.y + nephele::gpu::PATH_SHELL_PAD_M;
    const float flat = 2.0f * layer.shape.y * f.cloud_shape.z;
    const float coverage = layer.shape.w > 0.0f ? 1.0f : std::min(1.0f, 2.0f * layer.shape.x);
    for (int k = 0; k < bins; ++k)
      for (int j = 100; j < 156; j += 5)
        for (int i = 100; i < 156; i += 5) {
          const float bound = grid[((size_t(l) * bins + size_t(k)) * n + size_t(j)) * n + size_t(i)];
          EXPECT_LE(bound, flat * 1.0001f);
          zero_cells += bound == 0.0f ? 1 : 0;
          for (int s = 0; s < 20; ++s) {
            const glm::vec2 xy = corner + (glm::vec2(i, j) + glm::vec2(unit(rng), unit(rng))) * cell;
            const float r = lo + (hi - lo) * (float(k) + unit(rng)) / float(bins);
            const float h = std::clamp((r - layer.radii_m.x) / (layer.radii_m.y - layer.radii_m.x), 0.0f, 1.0f);
            const glm::vec2 ground = xy - glsl::cloud_wind_offset(glm::vec2(layer.wind),
                                                                  glm::vec2(layer.wind.z, layer.wind.w),
                                                                  glm::vec2(f.cloud_wind), f.cloud_wind.w,
                                                                  f.cloud_wind.z, h);
            const glm::vec4 base = tile.sample(glm::vec3(ground, r - planet) * f.cloud_noise.x);
            // The shader's base shape with the type's gradient at its largest (1).
            const float worley = base.g * 0.625f + base.b * 0.25f + base.a * 0.125f;
            const float noise = std::clamp(glsl::remap(base.r, worley - 1.0f, 1.0f, 0.0f, 1.0f), 0.0f, 1.0f);
            const float field = glsl::cloud_apply_coverage(noise, coverage) * flat;
            EXPECT_LE(field, bound * 1.0001f + 1e-7f)
                << "layer " << l << " bin " << k << " cell " << i << ", " << j;
            ++checked;
          }
        }
  }
  EXPECT_GT(checked, 10000);
  EXPECT_GT(zero_cells, 10) << "a sparse tile leaves empty cells";
}

}  // namespace

namespace {

// The lab's brick majorants (lab_brick_majorants): a trilinear sample of a sparse random grid
// (clamped at its faces, as voxel_lookup reads it) never exceeds its brick's bound, which is
// the largest voxel that brick reads (so 0 where it reads none), and bricks far from any
// density are 0.
TEST(PathMajorant, EachLabBrickBoundsTheSamplesInsideIt) {
  const glm::ivec3 dims(21, 17, 12);
  std::vector<float> density(size_t(dims.x) * dims.y * dims.z, 0.0f);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const auto at = [&](glm::ivec3 i) -> float& {
    i = glm::clamp(i, glm::ivec3(0), dims - 1);
    return density[(size_t(i.z) * dims.y + size_t(i.y)) * dims.x + size_t(i.x)];
  };
  // A blob in one corner, a hot voxel on a brick boundary (voxel 8: read by bricks 0 and 1).
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 6; ++i) at({i, j, k}) = 0.5f * unit(rng);
  at({8, 3, 3}) = 0.9f;
  const float scale = 2.0f;
  const std::vector<float> bound = nephele::lab_brick_majorants(density, dims, scale);
  const glm::ivec3 bricks = (dims + 7) / 8;
  ASSERT_EQ(bound.size(), size_t(bricks.x) * bricks.y * bricks.z);
  const auto brick_bound = [&](glm::ivec3 b) {
    return bound[(size_t(b.z) * bricks.y + size_t(b.y)) * bricks.x + size_t(b.x)];
  };
  EXPECT_NEAR(brick_bound({0, 0, 0}), 0.9f * scale, 0.01f);  // the hot voxel reaches brick 0
  EXPECT_NEAR(brick_bound({1, 0, 0}), 0.9f * scale, 0.01f);  // and brick 1
  EXPECT_EQ(brick_bound({2, 1, 1}), 0.0f);
  EXPECT_EQ(brick_bound({0, 2, 0}), 0.0f);
  for (int n = 0; n < 200000; ++n) {
    const glm::vec3 u = glm::vec3(unit(rng), unit(rng), unit(rng)) * glm::vec3(dims);
    const glm::vec3 t = glm::clamp(u, glm::vec3(0.5f), glm::vec3(dims) - 0.5f) - 0.5f;
    const glm::ivec3 i0(glm::floor(t));
    const glm::vec3 f = t - glm::floor(t);
    float value = 0.0f;
    for (int c = 0; c < 8; ++c) {
      const glm::ivec3 o(c & 1, (c >> 1) & 1, (c >> 2) & 1);
      const glm::vec3 w = glm::mix(1.0f - f, f, glm::vec3(o));
      value += w.x * w.y * w.z * at(i0 + o);
    }
    const glm::ivec3 b = glm::min(glm::ivec3(glm::floor(t / 8.0f)), bricks - 1);
    ASSERT_LE(value * scale, brick_bound(b) * 1.0001f + 1e-7f) << u.x << " " << u.y << " " << u.z;
  }
}

}  // namespace
