// `nephele make-cloud` and `nephele voxelize`: voxel clouds (seed 002) written as OpenVDB.
#include "voxel_commands.h"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <iostream>

#include "nephele/error.h"
#include "nephele/output_file.h"
#include "voxel/voxel_grid.h"

namespace nephele::cli {
namespace {

void check_resolution(int resolution) {
  if (resolution < 16 || resolution > voxel::kMaxGridDim)
    throw InputError("--resolution " + std::to_string(resolution) + ": must be in [16, " +
                     std::to_string(voxel::kMaxGridDim) + "]");
}

// Checked before any work: a .vdb where a file can be written.
void check_vdb_output(const std::string& path) {
  if (path.size() < 4 || path.compare(path.size() - 4, 4, ".vdb") != 0)
    throw InputError("--output '" + shorten_path_for_message(path) + "': must end in .vdb");
  check_output_file(path, "--output");
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

std::string voxel_summary(const std::string& output, const voxel::VoxelGrid& grid, double seconds) {
  size_t active = 0;
  for (float d : grid.density) active += d > 0.0f;
  const glm::vec3 extent = grid.extent_m();
  char line[512];
  std::snprintf(line, sizeof line,
                "%s: %d x %d x %d voxels of %.3g m (%.0f x %.0f x %.0f m), %zu active, %.2f s",
                shorten_path_for_message(output).c_str(), grid.dims.x, grid.dims.y, grid.dims.z,
                grid.voxel_m, extent.x, extent.y, extent.z, active, seconds);
  return line;
}

void add_make_cloud_flags(CLI::App& cmd, MakeCloudOptions& options) {
  cmd.add_option("--type", options.type,
                 "cumulus, cumulus-congestus, cumulonimbus, cumulus-mesh (the shipped mesh, baked) "
                 "or cube (1 km, density 1: the lab's test body)")
      ->required();
  cmd.add_option("--seed", options.seed, "the same seed gives the same cloud")
      ->capture_default_str();
  cmd.add_option("-o,--output", options.output, "OpenVDB file to write (.vdb)")->required();
  cmd.add_option("--resolution", options.resolution, "voxels on the longest axis, [16, 256]")
      ->capture_default_str();
}

int run_make_cloud(const MakeCloudOptions& options) {
  const voxel::CloudPreset preset = voxel::parse_cloud_preset(options.type, "--type");
  check_resolution(options.resolution);
  check_vdb_output(options.output);
  const auto start = std::chrono::steady_clock::now();
  const voxel::VoxelGrid grid = voxel::make_cloud(preset, options.seed, options.resolution);
  voxel::write_vdb(grid, options.output);
  std::cout << voxel_summary(options.output, grid, seconds_since(start)) << "\n";
  return 0;
}

void add_voxelize_flags(CLI::App& cmd, VoxelizeOptions& options) {
  cmd.add_option("mesh", options.mesh, "closed triangle mesh (OBJ, metres, z up)")->required();
  cmd.add_option("-o,--output", options.output, "OpenVDB file to write (.vdb)")->required();
  cmd.add_option("--resolution", options.resolution, "voxels on the longest axis, [16, 256]")
      ->capture_default_str();
}

int run_voxelize(const VoxelizeOptions& options) {
  check_resolution(options.resolution);
  check_vdb_output(options.output);
  check_outputs_not_inputs({{"--output", options.output}}, {{"mesh", options.mesh}});
  const auto start = std::chrono::steady_clock::now();
  const voxel::VoxelGrid grid = voxel::voxelize_mesh(options.mesh, options.resolution);
  voxel::write_vdb(grid, options.output);
  std::cout << voxel_summary(options.output, grid, seconds_since(start)) << "\n";
  return 0;
}

}  // namespace nephele::cli
