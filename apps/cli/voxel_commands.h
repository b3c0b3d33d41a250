// `nephele make-cloud` and `nephele voxelize`: voxel clouds (seed 002) written as OpenVDB.
#pragma once

#include <cstdint>
#include <string>

namespace CLI {
class App;
}

namespace nephele::voxel {
struct VoxelGrid;
}

namespace nephele::cli {

struct MakeCloudOptions {
  std::string type;  // cumulus, cumulus-congestus, cumulonimbus
  uint32_t seed = 1;
  std::string output;
  int resolution = 128;  // voxels on the longest axis
};

struct VoxelizeOptions {
  std::string mesh;  // OBJ
  std::string output;
  int resolution = 128;
};

void add_make_cloud_flags(CLI::App& cmd, MakeCloudOptions& options);
int run_make_cloud(const MakeCloudOptions& options);

void add_voxelize_flags(CLI::App& cmd, VoxelizeOptions& options);
int run_voxelize(const VoxelizeOptions& options);

// The one line the commands print: "<output>: NX x NY x NZ voxels of V m (EX x EY x EZ m),
// N active, S s".
std::string voxel_summary(const std::string& output, const voxel::VoxelGrid& grid, double seconds);

}  // namespace nephele::cli
