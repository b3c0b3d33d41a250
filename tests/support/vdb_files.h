// Test files for the voxel-cloud importer, written with OpenVDB's and NanoVDB's own writers.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace nephele::test {

// Fog balls of radius 6 voxels (0.5 m voxels, 13 active an axis), density 1 at the centre
// falling to 0 at the rim, one grid a name: a .vdb through openvdb::io::File, a .nvdb through
// nanovdb::io::writeGrids.
void write_fog_balls_vdb(const std::string& path, const std::vector<std::string>& names);
void write_fog_balls_nvdb(const std::string& path, const std::vector<std::string>& names);

// A "density" grid of Vec3s values.
void write_vector_density_vdb(const std::string& path);
// A "density" float grid without active voxels.
void write_empty_density_vdb(const std::string& path);
// A fog ball with a NaN in it.
void write_nan_density_vdb(const std::string& path);
// Two active voxels 100000 voxels apart on x.
void write_far_apart_density_vdb(const std::string& path);

// A cube of n^3 voxels of voxel_m, density 1 throughout, its base centre at the file's
// origin (nephele's own writer, voxel::write_vdb): a homogeneous medium for the lab.
void write_constant_cube_vdb(const std::string& path, int n, float voxel_m);

// Fog balls as write_fog_balls_vdb makes them, written with the given compression flags
// (openvdb::io::COMPRESS_*), as half floats where `half`, and through io::Stream (no grid
// offsets) where `stream`, else io::File.
void write_fog_balls_vdb_as(const std::string& path, const std::vector<std::string>& names,
                            uint32_t compression, bool half, bool stream);
// A stream (no grid offsets) of a Vec3s grid "velocity" and then a fog ball "density".
void write_vector_then_density_stream(const std::string& path);

// Boxes of active voxels of density `value` (inclusive index bounds, 1 m voxels); the other
// voxels of the leaves they touch inactive with `inactive`, over `background`.
struct VoxelBox {
  int lo[3], hi[3];
};
void write_boxes_vdb(const std::string& path, const std::vector<VoxelBox>& boxes, float value,
                     float inactive = 0.0f, float background = 0.0f);

}  // namespace nephele::test
