// nephele — voxel clouds: helpers shared by the importer, the generator and the mesh baker.
#include "voxel/common.h"

#include <algorithm>
#include <cmath>

#include "nephele/error.h"

namespace nephele::voxel {

void check_max_dim(int max_dim) {
  if (max_dim < kMinGridDim || max_dim > kMaxGridDim)
    throw InputError("resolution " + std::to_string(max_dim) + ": must be in [" +
                     std::to_string(kMinGridDim) + ", " + std::to_string(kMaxGridDim) + "]");
}

void fit_grid(glm::vec3 extent_m, int pad, int max_dim, VoxelGrid& grid) {
  const float longest = std::max({extent_m.x, extent_m.y, extent_m.z});
  const float voxel = longest / float(max_dim - 2 * pad);
  if (grid.voxel_m <= 0.0f || grid.voxel_m < voxel) grid.voxel_m = voxel;
  for (int a = 0; a < 3; ++a)
    grid.dims[a] =
        std::clamp(int(std::ceil(extent_m[a] / grid.voxel_m - 1e-4f)), 1, max_dim - 2 * pad) +
        2 * pad;
}

std::string file_prefix(const std::string& path) {
  return shorten_path_for_message(path) + ": ";
}

}  // namespace nephele::voxel
