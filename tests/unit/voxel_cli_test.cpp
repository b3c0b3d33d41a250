// `nephele make-cloud` and `nephele voxelize` end to end: a cloud file and one summary line;
// bad input gets one line, exit status 2 and no file.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "voxel/voxel_grid.h"

#include "support/process_run.h"

namespace fs = std::filesystem;

namespace {

using CliRun = nephele::test::ProcessRun;
using nephele::test::run_cli;

class VoxelCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(NEPHELE_TEST_OUTPUT_DIR) /
           ("voxel_cli_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write_cube(const std::string& name, int faces = 6) const {
    std::ofstream obj(path(name));
    obj << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n";
    const char* quads[6] = {"1 3 4 2", "5 6 8 7", "1 2 6 5", "3 7 8 4", "1 5 7 3", "2 4 8 6"};
    for (int f = 0; f < faces; ++f) obj << "f " << quads[f] << "\n";
    return path(name);
  }
  // Exit status 2, one line holding `expected`, and no output file.
  void expect_rejected(const std::string& args, const std::string& output,
                       const std::string& expected) {
    const CliRun r = run_cli(args);
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << "'" << expected << "' in " << r.output;
    EXPECT_FALSE(fs::exists(output)) << args;
  }
  fs::path dir_;
};

TEST_F(VoxelCli, MakeCloudWritesALoadableCloudAndOneLine) {
  const std::string out = path("cu.vdb");
  const CliRun r = run_cli("make-cloud --type cumulus --seed 4 --resolution 24 -o " + out);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_NE(r.output.find("voxels of"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("active"), std::string::npos) << r.output;
  const nephele::voxel::VoxelGrid grid = nephele::voxel::load_voxel_cloud(out, 24);
  EXPECT_LE(std::max({grid.dims.x, grid.dims.y, grid.dims.z}), 24);
}

TEST_F(VoxelCli, VoxelizeWritesACloud) {
  const std::string out = path("cube.vdb");
  const CliRun r = run_cli("voxelize " + write_cube("cube.obj") + " --resolution 20 -o " + out);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("20 x 20 x 20 voxels"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(out));
}

TEST_F(VoxelCli, RejectsBadInputWritingNothing) {
  const std::string out = path("x.vdb");
  expect_rejected("make-cloud --type stratus -o " + out, out, "--type stratus: must be one of");
  expect_rejected("make-cloud --type cumulus --resolution 1000 -o " + out, out,
                  "--resolution 1000: must be in [16, 256]");
  expect_rejected("make-cloud --type cumulus -o " + path("x.png"), path("x.png"),
                  "must end in .vdb");
  expect_rejected("make-cloud --type cumulus -o " + path("no/dir/x.vdb"), path("no/dir/x.vdb"),
                  "--output");
  expect_rejected("make-cloud --type cumulus --seed -3 -o " + out, out, "--seed");
  expect_rejected("voxelize " + path("missing.obj") + " -o " + out, out,
                  "missing.obj: does not exist (an OBJ mesh file is required)");
  expect_rejected("voxelize " + write_cube("open.obj", 5) + " -o " + out, out,
                  "open.obj: is not watertight: 4 open edges");
  expect_rejected("voxelize " + write_cube("cube.obj") + " --resolution 8 -o " + out, out,
                  "--resolution 8");
}

}  // namespace
