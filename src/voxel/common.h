// nephele — voxel clouds: helpers shared by the importer, the generator and the mesh baker.
#pragma once

#include <string>

#include "voxel/voxel_grid.h"

namespace nephele::voxel {

// Throws InputError unless max_dim is in [kMinGridDim, kMaxGridDim].
constexpr int kMinGridDim = 8;
void check_max_dim(int max_dim);

// The voxel size (m) and dimensions of a grid holding `extent_m` with `pad` voxels of margin
// on each side, its longest axis `max_dim` voxels at most.
void fit_grid(glm::vec3 extent_m, int pad, int max_dim, VoxelGrid& grid);

// "file.vdb: " as error messages start.
std::string file_prefix(const std::string& path);

}  // namespace nephele::voxel
