#include "voxel/bricks.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/packing.hpp>

namespace nephele::voxel {

namespace {

int bricks_along(int voxels) { return (voxels + kBrick - 1) / kBrick; }

// The stored texel k (0..kBrick) of brick b along an axis of n voxels: the voxel it copies.
int voxel_of(int b, int k, int n) { return std::min(b * kBrick + k, n - 1); }

glm::ivec3 atlas_origin(int index) {
  return glm::ivec3(index % kAtlasBricksXY, (index / kAtlasBricksXY) % kAtlasBricksXY,
                    index / (kAtlasBricksXY * kAtlasBricksXY)) *
         kBrickTexels;
}

}  // namespace

BrickPool pack_bricks(const std::vector<const VoxelGrid*>& grids) {
  BrickPool pool;
  // Which bricks are stored, and the bound of the empty ones.
  struct Brick {
    int cloud;
    glm::ivec3 b;
  };
  std::vector<Brick> stored;
  glm::ivec3 page_max(1, 1, 0);
  std::vector<std::vector<float>> tables;
  for (size_t c = 0; c < grids.size(); ++c) {
    const VoxelGrid& g = *grids[c];
    BrickedCloud bc;
    bc.dims = g.dims;
    bc.bricks = glm::ivec3(bricks_along(g.dims.x), bricks_along(g.dims.y), bricks_along(g.dims.z));
    bc.page_z = page_max.z;
    page_max = glm::ivec3(std::max(page_max.x, bc.bricks.x), std::max(page_max.y, bc.bricks.y),
                          page_max.z + bc.bricks.z);
    std::vector<float> table(size_t(bc.bricks.x) * bc.bricks.y * bc.bricks.z);
    const float inv_voxel = 1.0f / g.voxel_m;
    for (int bz = 0; bz < bc.bricks.z; ++bz)
      for (int by = 0; by < bc.bricks.y; ++by)
        for (int bx = 0; bx < bc.bricks.x; ++bx) {
          float nearest = INFINITY;
          for (int k = 0; k <= kBrick; ++k)
            for (int j = 0; j <= kBrick; ++j)
              for (int i = 0; i <= kBrick; ++i) {
                const size_t v = g.index(voxel_of(bx, i, g.dims.x), voxel_of(by, j, g.dims.y),
                                         voxel_of(bz, k, g.dims.z));
                nearest = std::min(nearest, g.density[v] > 0.0f ? -1.0f : g.sdf_m[v] * inv_voxel);
              }
          float& entry = table[size_t(bx) + size_t(bc.bricks.x) * (by + size_t(bc.bricks.y) * bz)];
          if (nearest < kStoredBrickSdfVoxels) {
            entry = float(stored.size());
            stored.push_back({int(c), {bx, by, bz}});
            ++bc.stored_bricks;
          } else {
            entry = -nearest;
          }
        }
    bc.bytes = bc.stored_bricks * size_t(kBrickTexels * kBrickTexels * kBrickTexels) * 4 +
               table.size() * sizeof(float);
    pool.clouds.push_back(bc);
    tables.push_back(std::move(table));
  }

  // The page table texture: the clouds' tables one above the other.
  pool.page_texels = page_max;
  // At least two layers: the device's textures of depth 1 are 2D images.
  pool.page_texels.z = std::max(page_max.z, 2);
  pool.pages.assign(size_t(page_max.x) * page_max.y * size_t(pool.page_texels.z), -1e4f);
  for (size_t c = 0; c < grids.size(); ++c) {
    const BrickedCloud& bc = pool.clouds[c];
    for (int z = 0; z < bc.bricks.z; ++z)
      for (int y = 0; y < bc.bricks.y; ++y)
        for (int x = 0; x < bc.bricks.x; ++x)
          pool.pages[size_t(x) + size_t(page_max.x) * (y + size_t(page_max.y) * (bc.page_z + z))] =
              tables[c][size_t(x) + size_t(bc.bricks.x) * (y + size_t(bc.bricks.y) * z)];
  }

  // The atlas: layers of kAtlasBricksXY^2 bricks.
  const int layers = std::max(1, int((stored.size() + kAtlasBricksXY * kAtlasBricksXY - 1) /
                                     (kAtlasBricksXY * kAtlasBricksXY)));
  pool.atlas_texels = glm::ivec3(kAtlasBricksXY, kAtlasBricksXY, layers) * kBrickTexels;
  pool.atlas.assign(size_t(pool.atlas_texels.x) * pool.atlas_texels.y * pool.atlas_texels.z * 2, 0);
  for (size_t s = 0; s < stored.size(); ++s) {
    const VoxelGrid& g = *grids[size_t(stored[s].cloud)];
    const glm::ivec3 b = stored[s].b;
    const glm::ivec3 o = atlas_origin(int(s));
    for (int k = 0; k < kBrickTexels; ++k)
      for (int j = 0; j < kBrickTexels; ++j)
        for (int i = 0; i < kBrickTexels; ++i) {
          const size_t v = g.index(voxel_of(b.x, i, g.dims.x), voxel_of(b.y, j, g.dims.y),
                                   voxel_of(b.z, k, g.dims.z));
          const size_t t = 2 * (size_t(o.x + i) + size_t(pool.atlas_texels.x) *
                                                      (size_t(o.y + j) + size_t(pool.atlas_texels.y) * size_t(o.z + k)));
          pool.atlas[t] = glm::packHalf1x16(g.density[v]);
          pool.atlas[t + 1] = glm::packHalf1x16(g.sdf_m[v] / g.voxel_m);
        }
  }
  return pool;
}

glm::vec2 sample_bricks(const BrickPool& pool, int cloud, glm::vec3 u) {
  const BrickedCloud& bc = pool.clouds[size_t(cloud)];
  const glm::vec3 dims = glm::vec3(bc.dims);
  u = glm::clamp(u, glm::vec3(0.5f), dims - 0.5f);
  const glm::ivec3 b = glm::min(glm::ivec3(glm::floor((u - 0.5f) / float(kBrick))), bc.bricks - 1);
  const float page = pool.pages[size_t(b.x) + size_t(pool.page_texels.x) *
                                                  (size_t(b.y) + size_t(pool.page_texels.y) * size_t(bc.page_z + b.z))];
  if (page < 0.0f) return {0.0f, -page};
  // Trilinear between the texel centres of the brick (texel k holds voxel kBrick b + k).
  const glm::vec3 local = u - glm::vec3(b * kBrick) - 0.5f;  // in [0, kBrick]
  const glm::ivec3 o = atlas_origin(int(page));
  const glm::ivec3 i0 = glm::min(glm::ivec3(glm::floor(local)), glm::ivec3(kBrick - 1));
  const glm::vec3 f = local - glm::vec3(i0);
  glm::vec2 sum(0.0f);
  for (int c = 0; c < 8; ++c) {
    const glm::ivec3 d((c & 1), (c >> 1) & 1, (c >> 2) & 1);
    const glm::ivec3 t = o + i0 + d;
    const size_t at = 2 * (size_t(t.x) + size_t(pool.atlas_texels.x) *
                                             (size_t(t.y) + size_t(pool.atlas_texels.y) * size_t(t.z)));
    const float w = (d.x ? f.x : 1.0f - f.x) * (d.y ? f.y : 1.0f - f.y) * (d.z ? f.z : 1.0f - f.z);
    sum += w * glm::vec2(glm::unpackHalf1x16(pool.atlas[at]), glm::unpackHalf1x16(pool.atlas[at + 1]));
  }
  return sum;
}

}  // namespace nephele::voxel
