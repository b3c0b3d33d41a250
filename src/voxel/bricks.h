// nephele — voxel clouds on the device, stored sparsely (seed 002: "several small voxel
// textures written into one large virtual 3D texture"): each cloud's grid is cut into bricks
// of kBrick^3 voxels; only the bricks near its surface are stored, in one shared atlas, and a
// page table per cloud says for each brick where it lies in the atlas or, for an empty brick,
// how far the cloud is from it (what a sphere tracer may step across it).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "voxel/voxel_grid.h"

namespace nephele::voxel {

constexpr int kBrick = 8;  // voxels per brick edge
// Texels stored per brick edge: its kBrick voxels and the next brick's first, so that trilinear
// filtering between voxel centres never leaves a brick. Brick b serves the grid coordinates
// u in [kBrick b + 0.5, kBrick (b + 1) + 0.5) (voxel units, voxel centres at i + 0.5).
constexpr int kBrickTexels = kBrick + 1;
constexpr int kAtlasBricksXY = 16;  // bricks per row and column of an atlas layer
// A brick is stored where some of its texels are nearer the surface than this (voxels), so
// that an empty brick can be stepped across in steps of at least this much less one voxel.
constexpr float kStoredBrickSdfVoxels = 2.0f;

struct BrickedCloud {
  glm::ivec3 dims{0};         // the grid's voxels
  glm::ivec3 bricks{0};       // page table size (bricks per axis)
  int page_z = 0;             // its first layer in the page table texture
  size_t stored_bricks = 0;   // bricks in the atlas
  size_t bytes = 0;           // its atlas bricks and page table on the device
};

// What goes to the device: an atlas of RG16F texels (x density, y signed distance in voxels)
// and an R32F page table (per brick: >= 0 its index in the atlas; < 0 an empty brick whose
// texels are all at least -value voxels from the surface).
struct BrickPool {
  glm::ivec3 atlas_texels{0};
  std::vector<uint16_t> atlas;  // 2 halves per texel, x fastest
  glm::ivec3 page_texels{0};
  std::vector<float> pages;
  std::vector<BrickedCloud> clouds;
  size_t atlas_bytes() const { return atlas.size() * sizeof(uint16_t); }
  size_t page_bytes() const { return pages.size() * sizeof(float); }
};

BrickPool pack_bricks(const std::vector<const VoxelGrid*>& grids);

// The pool's (density, signed distance in voxels) of cloud `cloud` at grid coordinate u
// (voxel units), as the shaders sample it (shaders/voxel_field_inc.glsl): trilinear in a
// stored brick, (0, the brick's bound) in an empty one. For tests.
glm::vec2 sample_bricks(const BrickPool& pool, int cloud, glm::vec3 u);

}  // namespace nephele::voxel
