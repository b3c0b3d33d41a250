// nephele — voxel clouds: the signed distances of a VoxelGrid (level_set.cpp holds the
// OpenVDB includes of the mesh path, which take long to compile).
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "voxel/voxel_grid.h"

namespace nephele::voxel {

// Sets grid.sdf_m (resized to the grid) to the signed distance to the surface of
// {density > 0}: the zero crossing of the trilinear density, which lies next to the first
// voxel centre without density, so a sphere tracer stepping by it never skips density.
// Right over the whole grid, to within a voxel (exact Euclidean distance transforms).
// The density must have a voxel > 0.
void compute_sdf_from_density(VoxelGrid& grid);

// The signed distance (m) at the voxel centres of `layout` (dims, voxel_m, origin_m in the
// mesh's frame) to a closed triangle mesh: negative inside, over the whole grid; exact within
// three voxels of the surface (OpenVDB's meshToLevelSet), to within half a voxel beyond.
std::vector<float> mesh_signed_distance(const std::vector<glm::vec3>& points_m,
                                        const std::vector<glm::uvec3>& triangles,
                                        const VoxelGrid& layout);

// Initialises OpenVDB once (grid types, for io and the tools); safe from any thread.
void initialize_openvdb();

}  // namespace nephele::voxel
