// Not a check but a look (run with --gtest_also_run_disabled_tests): the vertical mid-slices
// of each preset's density, and the time each preset takes at full resolution, written to
// test-output/voxel_preview/<preset>.png, and the time to load each back from .vdb.
#include <gtest/gtest.h>
#include <stb/stb_image_write.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "voxel/voxel_grid.h"

namespace nephele::voxel {
namespace {

TEST(VoxelPreview, DISABLED_WritesMidSlicesOfThePresets) {
  const std::filesystem::path dir =
      std::filesystem::path(NEPHELE_TEST_OUTPUT_DIR) / "voxel_preview";
  std::filesystem::create_directories(dir);
  for (CloudPreset preset :
       {CloudPreset::Cumulus, CloudPreset::CumulusCongestus, CloudPreset::Cumulonimbus}) {
    const auto start = std::chrono::steady_clock::now();
    const VoxelGrid grid = make_cloud(preset, 1, 128);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%s: %d x %d x %d, %.3g m, %.2f s\n", cloud_preset_name(preset), grid.dims.x,
                grid.dims.y, grid.dims.z, grid.voxel_m, seconds);
    const std::string vdb = (dir / (std::string(cloud_preset_name(preset)) + ".vdb")).string();
    write_vdb(grid, vdb);
    const auto load_start = std::chrono::steady_clock::now();
    const VoxelGrid loaded = load_voxel_cloud(vdb, 128);
    std::printf(
        "  load: %d x %d x %d, %.2f s\n", loaded.dims.x, loaded.dims.y, loaded.dims.z,
        std::chrono::duration<double>(std::chrono::steady_clock::now() - load_start).count());
    // x-z slice through the middle (density, top up), beside it the density summed over y
    // (a crude side view).
    const int w = grid.dims.x, h = grid.dims.z;
    std::vector<unsigned char> pixels(size_t(2 * w) * h);
    for (int k = 0; k < h; ++k)
      for (int i = 0; i < w; ++i) {
        const float slice = grid.density[grid.index(i, grid.dims.y / 2, k)];
        float sum = 0.0f;
        for (int j = 0; j < grid.dims.y; ++j) sum += grid.density[grid.index(i, j, k)];
        const size_t row = size_t(h - 1 - k) * 2 * w;
        pixels[row + i] = (unsigned char)(255.0f * slice);
        pixels[row + w + i] = (unsigned char)(255.0f * (1.0f - std::exp(-sum * 0.1f)));
      }
    const std::string file = (dir / (std::string(cloud_preset_name(preset)) + ".png")).string();
    stbi_write_png(file.c_str(), 2 * w, h, 1, pixels.data(), 2 * w);
  }
}

}  // namespace
}  // namespace nephele::voxel
