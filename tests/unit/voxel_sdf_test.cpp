// Voxel clouds: the signed distance computed from a density is right over the whole grid
// (not only near the surface) for shapes whose distance is known.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "voxel/level_set.h"
#include "voxel/voxel_grid.h"

namespace nephele::voxel {
namespace {

// A grid whose density is 1 where `distance` (m) < 0 at a voxel centre.
VoxelGrid grid_of(glm::ivec3 dims, float voxel_m, const std::function<float(glm::vec3)>& distance) {
  VoxelGrid grid;
  grid.dims = dims;
  grid.voxel_m = voxel_m;
  grid.origin_m = -0.5f * glm::vec3(dims) * voxel_m;
  grid.density.assign(size_t(dims.x) * dims.y * dims.z, 0.0f);
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i)
        if (distance(grid.origin_m + (glm::vec3(i, j, k) + 0.5f) * voxel_m) < 0.0f)
          grid.density[grid.index(i, j, k)] = 1.0f;
  return grid;
}

// Every voxel's distance within one voxel of the analytic one; returns the largest error.
float expect_within_a_voxel(const VoxelGrid& grid,
                            const std::function<float(glm::vec3)>& distance) {
  float worst = 0.0f;
  for (int k = 0; k < grid.dims.z; ++k)
    for (int j = 0; j < grid.dims.y; ++j)
      for (int i = 0; i < grid.dims.x; ++i) {
        const glm::vec3 p = grid.origin_m + (glm::vec3(i, j, k) + 0.5f) * grid.voxel_m;
        const float error = grid.sdf_m[grid.index(i, j, k)] - distance(p);
        worst = std::max(worst, std::fabs(error));
        if (std::fabs(error) > grid.voxel_m) {
          ADD_FAILURE() << "voxel " << i << "," << j << "," << k << ": sdf "
                        << grid.sdf_m[grid.index(i, j, k)] << " m, analytic " << distance(p);
          return worst;
        }
      }
  return worst;
}

TEST(VoxelSdf, MatchesASphereOverTheWholeGrid) {
  const float radius_m = 30.0f;
  const auto sphere = [&](glm::vec3 p) { return glm::length(p) - radius_m; };
  VoxelGrid grid = grid_of(glm::ivec3(40, 36, 32), 2.5f, sphere);
  compute_sdf_from_density(grid);
  ASSERT_EQ(grid.sdf_m.size(), grid.density.size());
  const float worst = expect_within_a_voxel(grid, sphere);
  EXPECT_LT(worst, grid.voxel_m);
  // The corners are far outside the band a level set usually keeps.
  EXPECT_GT(grid.sdf_m[0], 20.0f);
}

TEST(VoxelSdf, MatchesABoxOverTheWholeGrid) {
  const glm::vec3 half_m(22.0f, 13.0f, 9.0f);
  const auto box = [&](glm::vec3 p) {
    const glm::vec3 q = glm::abs(p) - half_m;
    return glm::length(glm::max(q, 0.0f)) + std::min(std::max({q.x, q.y, q.z}), 0.0f);
  };
  VoxelGrid grid = grid_of(glm::ivec3(36, 28, 24), 2.0f, box);
  compute_sdf_from_density(grid);
  expect_within_a_voxel(grid, box);
  // Inside, the distance grows to the box's half thickness.
  EXPECT_LT(grid.sdf_m[grid.index(18, 14, 12)], -7.0f);
}

}  // namespace
}  // namespace nephele::voxel
