#include "render/path_majorant.h"

#include <algorithm>
#include <cmath>

#include "render/glsl.h"

namespace nephele {

namespace {

int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }
int wrap(int a, int n) { return ((a % n) + n) % n; }

}  // namespace

glm::vec2 NoiseBlockBounds::at(int i, int j, int k) const {
  return r_max_w_min[(size_t(wrap(k, blocks)) * size_t(blocks) + size_t(wrap(j, blocks))) *
                         size_t(blocks) +
                     size_t(wrap(i, blocks))];
}

NoiseBlockBounds noise_block_bounds(const std::vector<uint8_t>& rgba, int size) {
  NoiseBlockBounds b;
  b.size = size;
  b.blocks = (size + kNoiseBlock - 1) / kNoiseBlock;
  b.r_max_w_min.assign(size_t(b.blocks) * b.blocks * b.blocks, glm::vec2(0.0f, 1.0f));
  for (int z = 0; z < size; ++z)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const uint8_t* t = &rgba[((size_t(z) * size + size_t(y)) * size + size_t(x)) * 4];
        const float r = float(t[0]) / 255.0f;
        const float w = 0.625f * float(t[1]) / 255.0f + 0.25f * float(t[2]) / 255.0f +
                        0.125f * float(t[3]) / 255.0f;
        glm::vec2& cell = b.r_max_w_min[(size_t(z / kNoiseBlock) * b.blocks + size_t(y / kNoiseBlock)) *
                                            b.blocks +
                                        size_t(x / kNoiseBlock)];
        cell.x = std::max(cell.x, r);
        cell.y = std::min(cell.y, w);
      }
  return b;
}

std::vector<float> noise_majorant_grid(const gpu::FrameParams& f, const NoiseBlockBounds& noise,
                                       glm::vec2 corner_m, float cell_m) {
  const int n = gpu::PATH_GRID_XY, bins = gpu::PATH_GRID_BINS;
  std::vector<float> grid(size_t(n) * n * gpu::CLOUD_LAYERS * bins, 0.0f);
  const float planet_m = f.radii_m.x;
  const float texels_per_m = f.cloud_noise.x * float(noise.size);
  // The texel indices a trilinear sample between coordinates lo and hi (metres) reads.
  const auto texels = [&](float lo_m, float hi_m) {
    return glm::ivec2(int(std::floor(lo_m * texels_per_m - 0.5f)),
                      int(std::floor(hi_m * texels_per_m - 0.5f)) + 1);
  };
  for (int l = 0; l < gpu::CLOUD_LAYERS; ++l) {
    const gpu::CloudLayerGpu& layer = f.cloud_layers[l];
    const glm::vec4 shape = layer.shape;
    if (!(shape.x > 0.0f || shape.w > 0.0f)) continue;
    const float bound = 2.0f * shape.y * f.cloud_shape.z;
    const float coverage = shape.w > 0.0f ? 1.0f : std::min(1.0f, 2.0f * shape.x);
    const float bottom = layer.radii_m.x, top = layer.radii_m.y;
    const float lo = bottom - gpu::PATH_SHELL_PAD_M, hi = top + gpu::PATH_SHELL_PAD_M;
    for (int k = 0; k < bins; ++k) {
      const float r0 = lo + (hi - lo) * float(k) / float(bins);
      const float r1 = lo + (hi - lo) * float(k + 1) / float(bins);
      // The wind's offset over the bin's heights: drift + h a + h^2 b per axis, extreme at
      // the ends or at its vertex.
      const float h0 = std::clamp((r0 - bottom) / (top - bottom), 0.0f, 1.0f);
      const float h1 = std::clamp((r1 - bottom) / (top - bottom), 0.0f, 1.0f);
      const auto offset = [&](float h) {
        return glsl::cloud_wind_offset(glm::vec2(layer.wind), glm::vec2(layer.wind.z, layer.wind.w),
                                       glm::vec2(f.cloud_wind), f.cloud_wind.w, f.cloud_wind.z, h);
      };
      glm::vec2 off_lo = glm::min(offset(h0), offset(h1)), off_hi = glm::max(offset(h0), offset(h1));
      const glm::vec2 a = glm::vec2(layer.wind.z, layer.wind.w) * f.cloud_wind.z +
                          glm::vec2(f.cloud_wind) * f.cloud_wind.w;
      const glm::vec2 b = glm::vec2(f.cloud_wind) * f.cloud_wind.z;
      for (int c = 0; c < 2; ++c)
        if (b[c] != 0.0f) {
          const float h = std::clamp(-a[c] / (2.0f * b[c]), h0, h1);
          off_lo[c] = std::min(off_lo[c], offset(h)[c]);
          off_hi[c] = std::max(off_hi[c], offset(h)[c]);
        }
      const glm::ivec2 tz = texels(r0 - planet_m, r1 - planet_m);
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const glm::vec2 x0 = corner_m + glm::vec2(i, j) * cell_m;
          const glm::ivec2 tx = texels(x0.x - off_hi.x, x0.x + cell_m - off_lo.x);
          const glm::ivec2 ty = texels(x0.y - off_hi.y, x0.y + cell_m - off_lo.y);
          const auto blocks = [&](glm::ivec2 t) {
            // A range over a whole tile reads every block once.
            if (t.y - t.x + 1 >= noise.size) return glm::ivec2(0, noise.blocks - 1);
            return glm::ivec2(floor_div(t.x, kNoiseBlock), floor_div(t.y, kNoiseBlock));
          };
          const glm::ivec2 bx = blocks(tx), by = blocks(ty), bz = blocks(tz);
          float r_max = 0.0f, w_min = 1.0f;
          for (int bk = bz.x; bk <= bz.y; ++bk)
            for (int bj = by.x; bj <= by.y; ++bj)
              for (int bi = bx.x; bi <= bx.y; ++bi) {
                const glm::vec2 v = noise.at(bi, bj, bk);
                r_max = std::max(r_max, v.x);
                w_min = std::min(w_min, v.y);
              }
          const float noise_max = std::clamp((r_max - w_min + 1.0f) / (2.0f - w_min), 0.0f, 1.0f);
          grid[((size_t(l) * bins + size_t(k)) * n + size_t(j)) * n + size_t(i)] =
              glsl::cloud_apply_coverage(noise_max, coverage) * bound;
        }
    }
  }
  return grid;
}

std::vector<float> lab_brick_majorants(const std::vector<float>& density, glm::ivec3 dims,
                                       float scale) {
  const int b = gpu::VOXEL_BRICK;
  const glm::ivec3 bricks = (dims + b - 1) / b;
  std::vector<float> out(size_t(bricks.x) * bricks.y * bricks.z, 0.0f);
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i) {
        const float v = density[(size_t(k) * dims.y + size_t(j)) * dims.x + size_t(i)];
        if (!(v > 0.0f)) continue;
        // Voxel i is read by brick i / b and, as its filter's last voxel, by brick i / b - 1.
        for (int bk = std::max(k - 1, 0) / b; bk <= std::min(k / b, bricks.z - 1); ++bk)
          for (int bj = std::max(j - 1, 0) / b; bj <= std::min(j / b, bricks.y - 1); ++bj)
            for (int bi = std::max(i - 1, 0) / b; bi <= std::min(i / b, bricks.x - 1); ++bi) {
              float& m = out[(size_t(bk) * bricks.y + size_t(bj)) * bricks.x + size_t(bi)];
              m = std::max(m, v);
            }
      }
  for (float& m : out) m *= scale * (1.0f + 1.0f / 1024.0f);
  return out;
}

}  // namespace nephele
