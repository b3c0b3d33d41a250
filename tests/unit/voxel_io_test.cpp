// Voxel clouds: OpenVDB and NanoVDB files in, OpenVDB out; a bad file is one line of
// InputError naming it, what is wrong and what is allowed.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "nephele/error.h"
#include "support/vdb_files.h"
#include "voxel/level_set.h"
#include "voxel/voxel_grid.h"

namespace nephele::voxel {
namespace {

namespace fs = std::filesystem;

class VoxelIo : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(NEPHELE_TEST_OUTPUT_DIR) /
           ("voxel_io_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // A file as other tools make them (tests/support/vdb_files.h).
  std::string written(const std::string& name, void (*write)(const std::string&)) const {
    write(path(name));
    return path(name);
  }

  // load_voxel_cloud must throw InputError of one line holding every `expected` string.
  void expect_refused(const std::string& file, std::initializer_list<std::string> expected) {
    try {
      load_voxel_cloud(file, 32);
      ADD_FAILURE() << file << ": loaded";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      for (const std::string& s : expected)
        EXPECT_NE(message.find(s), std::string::npos) << "'" << s << "' not in: " << message;
    }
  }
  fs::path dir_;
};

// A grid whose density fills exactly the voxels 2 .. dims - 3 (the padding the importer
// adds), with values of every 1/255 step's size, and its distance.
VoxelGrid padded_grid() {
  VoxelGrid grid;
  grid.dims = glm::ivec3(20, 16, 12);
  grid.voxel_m = 25.0f;
  grid.origin_m = glm::vec3(-0.5f * grid.dims.x, -0.5f * grid.dims.y, -2.0f) * grid.voxel_m;
  grid.density.assign(size_t(grid.dims.x) * grid.dims.y * grid.dims.z, 0.0f);
  for (int k = 2; k < grid.dims.z - 2; ++k)
    for (int j = 2; j < grid.dims.y - 2; ++j)
      for (int i = 2; i < grid.dims.x - 2; ++i)
        grid.density[grid.index(i, j, k)] =
            0.05f + 0.9f * float((i * 7 + j * 13 + k * 29) % 97) / 96.0f;
  compute_sdf_from_density(grid);
  return grid;
}

TEST_F(VoxelIo, WriteThenLoadGivesTheSameGrid) {
  const VoxelGrid grid = padded_grid();
  const std::string file = path("cloud.vdb");
  write_vdb(grid, file);
  const VoxelGrid back = load_voxel_cloud(file, 64);
  ASSERT_EQ(back.dims, grid.dims);
  EXPECT_FLOAT_EQ(back.voxel_m, grid.voxel_m);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(back.origin_m[a], grid.origin_m[a], 1e-3f) << a;
  float density_error = 0.0f, sdf_error = 0.0f;
  for (size_t v = 0; v < grid.density.size(); ++v) {
    density_error = std::max(density_error, std::fabs(back.density[v] - grid.density[v]));
    sdf_error = std::max(sdf_error, std::fabs(back.sdf_m[v] - grid.sdf_m[v]));
  }
  EXPECT_LE(density_error, 1.0f / 255.0f);
  EXPECT_LE(sdf_error, 1e-3f * grid.voxel_m);
}

TEST_F(VoxelIo, LoadsAFogVolumeWithoutALevelSetAndResamples) {
  const std::string file = path("ball.vdb");
  test::write_fog_balls_vdb(file, {"density"});
  const VoxelGrid grid = load_voxel_cloud(file, 64);
  // 13 active voxels an axis, 2 of padding each side; 0.5 m voxels; base at z = 0.
  EXPECT_EQ(grid.dims, glm::ivec3(17));
  EXPECT_FLOAT_EQ(grid.voxel_m, 0.5f);
  EXPECT_NEAR(grid.origin_m.z, -1.0f, 1e-5f);
  EXPECT_NEAR(grid.origin_m.x, -4.25f, 1e-5f);
  EXPECT_NEAR(grid.density[grid.index(8, 8, 8)], 1.0f, 1e-5f);
  EXPECT_LT(grid.sdf_m[grid.index(8, 8, 8)], -2.0f);
  EXPECT_GT(grid.sdf_m[0], 2.0f);
  // At most 12 voxels: coarser voxels, the same box.
  const VoxelGrid small = load_voxel_cloud(file, 12);
  EXPECT_LE(std::max({small.dims.x, small.dims.y, small.dims.z}), 12);
  EXPECT_GT(small.voxel_m, 0.5f);
  EXPECT_GE(small.extent_m().x, 6.5f);
}

TEST_F(VoxelIo, LoadsNanoVdb) {
  const std::string file = path("ball.nvdb");
  test::write_fog_balls_nvdb(file, {"temperature", "density"});
  const VoxelGrid grid = load_voxel_cloud(file, 64);
  EXPECT_EQ(grid.dims, glm::ivec3(17));
  EXPECT_NEAR(grid.density[grid.index(8, 8, 8)], 1.0f, 1e-5f);
  EXPECT_LT(grid.sdf_m[grid.index(8, 8, 8)], -2.0f);

  // Half of it, and bytes that are no NanoVDB.
  std::ifstream in(file, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), {});
  std::ofstream(path("half.nvdb"), std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  expect_refused(path("half.nvdb"), {"half.nvdb: ", "truncated"});
  std::ofstream(path("text.nvdb")) << "not a grid at all, just some words in a file\n";
  expect_refused(path("text.nvdb"), {"text.nvdb: ", "not a NanoVDB file"});
  test::write_fog_balls_nvdb(path("smoke.nvdb"), {"smoke"});
  expect_refused(path("smoke.nvdb"), {"no grid named \"density\"", "\"smoke\""});
}

TEST_F(VoxelIo, RefusesMissingGridWrongTypeAndEmptyDensity) {
  expect_refused(path("nothing.vdb"), {"nothing.vdb: does not exist"});
  test::write_fog_balls_vdb(path("smoke.vdb"), {"smoke", "heat"});
  expect_refused(path("smoke.vdb"), {"smoke.vdb: has no grid named \"density\"", "\"smoke\"",
                                     "\"heat\"", "float fog volume"});
  expect_refused(written("vec.vdb", test::write_vector_density_vdb),
                 {"vec.vdb: grid \"density\" holds vec3s values", "a float grid is required"});
  expect_refused(written("empty.vdb", test::write_empty_density_vdb),
                 {"empty.vdb: ", "no active voxels"});
  expect_refused(written("nan.vdb", test::write_nan_density_vdb),
                 {"nan.vdb: ", "non-finite value"});
}

TEST_F(VoxelIo, RefusesHugeTruncatedAndGarbageFiles) {
  expect_refused(written("far.vdb", test::write_far_apart_density_vdb),
                 {"far.vdb: grid \"density\" spans 100001 x 1 x 1 voxels", "at most 4096"});

  write_vdb(padded_grid(), path("whole.vdb"));
  std::ifstream in(path("whole.vdb"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), {});
  std::ofstream(path("half.vdb"), std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  expect_refused(path("half.vdb"), {"half.vdb: is truncated or corrupt"});

  std::mt19937 rng(5);
  std::string garbage(4096, '\0');
  for (char& c : garbage) c = char(rng());
  std::ofstream(path("garbage.vdb"), std::ios::binary) << garbage;
  expect_refused(path("garbage.vdb"), {"garbage.vdb: is not a readable OpenVDB file"});
  std::ofstream(path("cloud.txt")) << "x";
  expect_refused(path("cloud.txt"), {"cloud.txt: ", ".vdb (OpenVDB) or .nvdb"});
}

TEST_F(VoxelIo, AFailedWriteLeavesNothing) {
  const std::string file = path("no/such/folder/cloud.vdb");
  EXPECT_THROW(write_vdb(padded_grid(), file), RuntimeError);
  EXPECT_FALSE(fs::exists(file));
  EXPECT_TRUE(fs::is_empty(dir_));
}

}  // namespace
}  // namespace nephele::voxel
