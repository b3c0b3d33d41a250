// Voxel clouds: the procedural presets (make_cloud), meshes baked into clouds (voxelize_mesh)
// and the Curly-Alligator noise both erode them with.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "nephele/error.h"
#include "voxel/voxel_grid.h"

namespace nephele::voxel {
namespace {

namespace fs = std::filesystem;

// The cloud's extent where it has density: lowest and highest voxel centres, and the width.
struct Extent {
  glm::vec3 lo{1e30f}, hi{-1e30f};
};
Extent density_extent(const VoxelGrid& grid) {
  Extent e;
  for (int k = 0; k < grid.dims.z; ++k)
    for (int j = 0; j < grid.dims.y; ++j)
      for (int i = 0; i < grid.dims.x; ++i)
        if (grid.density[grid.index(i, j, k)] > 0.0f) {
          const glm::vec3 p = grid.origin_m + (glm::vec3(i, j, k) + 0.5f) * grid.voxel_m;
          e.lo = glm::min(e.lo, p);
          e.hi = glm::max(e.hi, p);
        }
  return e;
}

// The signed distance bounds the distance to the density from below (to within a voxel):
// checked against brute force at a sample of voxels outside.
void expect_sdf_bounds_density(const VoxelGrid& grid) {
  std::vector<glm::vec3> dense;
  for (int k = 0; k < grid.dims.z; ++k)
    for (int j = 0; j < grid.dims.y; ++j)
      for (int i = 0; i < grid.dims.x; ++i)
        if (grid.density[grid.index(i, j, k)] > 0.0f) {
          dense.push_back(grid.origin_m + (glm::vec3(i, j, k) + 0.5f) * grid.voxel_m);
          EXPECT_LE(grid.sdf_m[grid.index(i, j, k)], grid.voxel_m) << i << "," << j << "," << k;
        }
  ASSERT_FALSE(dense.empty());
  int checked = 0;
  for (size_t v = 0; v < grid.sdf_m.size(); v += 97) {
    if (grid.density[v] > 0.0f) continue;
    const int i = int(v % grid.dims.x), j = int((v / grid.dims.x) % grid.dims.y),
              k = int(v / (size_t(grid.dims.x) * grid.dims.y));
    const glm::vec3 p = grid.origin_m + (glm::vec3(i, j, k) + 0.5f) * grid.voxel_m;
    float nearest = 1e30f;
    for (const glm::vec3& q : dense) nearest = std::min(nearest, glm::length(p - q));
    // The surface lies between the last voxel with density and the next: within a voxel.
    EXPECT_LE(grid.sdf_m[v], nearest + 0.01f * grid.voxel_m) << v;
    EXPECT_GE(grid.sdf_m[v], nearest - 1.8f * grid.voxel_m) << v;
    ++checked;
  }
  EXPECT_GT(checked, 50);
}

TEST(VoxelNoise, CurlyAlligatorIsDeterministicInRangeAndVaries) {
  float lo = 1.0f, hi = 0.0f;
  for (int n = 0; n < 4000; ++n) {
    const glm::vec3 p(float(n % 17) * 13.1f, float(n % 23) * 7.7f, float(n) * 0.91f);
    const float v = curly_alligator(p, 0.02f);
    EXPECT_EQ(v, curly_alligator(p, 0.02f));
    ASSERT_GE(v, 0.0f);
    ASSERT_LE(v, 1.0f);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  EXPECT_LT(lo, 0.15f);
  EXPECT_GT(hi, 0.6f);
  EXPECT_EQ(curly_alligator(glm::vec3(NAN), 1.0f), 0.0f);
  EXPECT_GE(curly_alligator(glm::vec3(1e30f), 1.0f), 0.0f);
}

// The lab's cube (data/lab.toml): 1 km of density 1 from its base at z = 0, centred, its
// faces on voxel boundaries, nothing outside.
TEST(VoxelMakeCloud, TheCubeIsOneKilometreOfDensityOne) {
  const VoxelGrid cube = make_cloud(parse_cloud_preset("cube", "--type"), 0, 36);
  EXPECT_EQ(cube.dims, glm::ivec3(36));
  EXPECT_FLOAT_EQ(cube.voxel_m, 1000.0f / 32.0f);
  const Extent e = density_extent(cube);  // voxel centres: half a voxel inside each face
  const float half = 0.5f * cube.voxel_m;
  EXPECT_NEAR(e.lo.x, -500.0f + half, 1e-3f);
  EXPECT_NEAR(e.hi.x, 500.0f - half, 1e-3f);
  EXPECT_NEAR(e.lo.y, -500.0f + half, 1e-3f);
  EXPECT_NEAR(e.lo.z, half, 1e-3f);
  EXPECT_NEAR(e.hi.z, 1000.0f - half, 1e-3f);
  size_t ones = 0;
  for (float d : cube.density) {
    ASSERT_TRUE(d == 0.0f || d == 1.0f) << d;
    ones += d == 1.0f;
  }
  EXPECT_EQ(ones, size_t(32 * 32 * 32));
  expect_sdf_bounds_density(cube);
}

TEST(VoxelMakeCloud, PresetsAreDeterministicSizedLikeTheirKindAndBoundedBySdf) {
  const VoxelGrid a = make_cloud(CloudPreset::Cumulus, 7, 32);
  const VoxelGrid b = make_cloud(CloudPreset::Cumulus, 7, 32);
  const VoxelGrid c = make_cloud(CloudPreset::Cumulus, 8, 32);
  EXPECT_EQ(a.dims, b.dims);
  EXPECT_EQ(a.density, b.density);
  EXPECT_EQ(a.sdf_m, b.sdf_m);
  EXPECT_NE(a.density, c.density);
  for (float d : a.density) ASSERT_TRUE(d >= 0.0f && d <= 1.0f) << d;
  EXPECT_LE(std::max({a.dims.x, a.dims.y, a.dims.z}), 32);
  expect_sdf_bounds_density(a);

  const VoxelGrid congestus = make_cloud(CloudPreset::CumulusCongestus, 7, 32);
  const VoxelGrid nimbus = make_cloud(CloudPreset::Cumulonimbus, 7, 32);
  const Extent cu = density_extent(a), cg = density_extent(congestus), cb = density_extent(nimbus);
  EXPECT_GT(cb.hi.z, cg.hi.z);
  EXPECT_GT(cg.hi.z, cu.hi.z);
  EXPECT_NEAR(cu.hi.z, 1000.0f, 250.0f);
  EXPECT_NEAR(cg.hi.z, 3000.0f, 600.0f);
  EXPECT_NEAR(cb.hi.z, 9000.0f, 1200.0f);
  EXPECT_NEAR(cu.hi.x - cu.lo.x, 1000.0f, 500.0f);
  EXPECT_GT(std::max(cb.hi.x - cb.lo.x, cb.hi.y - cb.lo.y), 4500.0f);  // the anvil
  // The base at z = 0, flat: the lowest density within two voxels of it.
  for (const VoxelGrid* g : {&a, &congestus, &nimbus}) {
    const Extent e = density_extent(*g);
    EXPECT_GE(e.lo.z, 0.0f);
    EXPECT_LT(e.lo.z, 2.0f * g->voxel_m);
    EXPECT_NEAR(g->origin_m.z, -2.0f * g->voxel_m, 1e-3f);
  }
  EXPECT_EQ(parse_cloud_preset("cumulus-congestus", "--type"), CloudPreset::CumulusCongestus);
  EXPECT_STREQ(cloud_preset_name(CloudPreset::Cumulonimbus), "cumulonimbus");
  try {
    parse_cloud_preset("stratus", "--type");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--type stratus: must be one of cumulus"),
              std::string::npos)
        << e.what();
  }
}

class VoxelVoxelize : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(NEPHELE_TEST_OUTPUT_DIR) /
           ("voxel_obj_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  // A box of half sizes `half_m` around `centre_m` as six quads (the loader triangulates);
  // `faces` drops the last ones to open it.
  std::string write_box(const std::string& name, glm::vec3 centre_m, glm::vec3 half_m,
                        int faces = 6) const {
    const std::string p = (dir_ / name).string();
    std::ofstream obj(p);
    for (int v = 0; v < 8; ++v) {
      const glm::vec3 q =
          centre_m + half_m * glm::vec3(v & 1 ? 1 : -1, v & 2 ? 1 : -1, v & 4 ? 1 : -1);
      obj << "v " << q.x << " " << q.y << " " << q.z << "\n";
    }
    const char* quads[6] = {"1 3 4 2", "5 6 8 7", "1 2 6 5", "3 7 8 4", "1 5 7 3", "2 4 8 6"};
    for (int f = 0; f < faces; ++f) obj << "f " << quads[f] << "\n";
    return p;
  }
  void expect_refused(const std::string& file, const std::string& expected) {
    try {
      voxelize_mesh(file, 32);
      ADD_FAILURE() << file;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  }
  fs::path dir_;
};

TEST_F(VoxelVoxelize, AClosedBoxBecomesABoxShapedCloud) {
  const glm::vec3 half_m(50.0f, 30.0f, 20.0f), centre_m(1000.0f, -40.0f, 320.0f);
  const VoxelGrid grid = voxelize_mesh(write_box("box.obj", centre_m, half_m), 40);
  EXPECT_EQ(std::max({grid.dims.x, grid.dims.y, grid.dims.z}), 40);
  EXPECT_NEAR(grid.voxel_m, 100.0f / 36.0f, 1e-3f);
  // The anchor is the box's base centre.
  const auto box = [&](glm::vec3 p) {
    const glm::vec3 q = glm::abs(p - glm::vec3(0.0f, 0.0f, half_m.z)) - half_m;
    return glm::length(glm::max(q, 0.0f)) + std::min(std::max({q.x, q.y, q.z}), 0.0f);
  };
  for (int k = 0; k < grid.dims.z; ++k)
    for (int j = 0; j < grid.dims.y; ++j)
      for (int i = 0; i < grid.dims.x; ++i) {
        const size_t v = grid.index(i, j, k);
        const glm::vec3 p = grid.origin_m + (glm::vec3(i, j, k) + 0.5f) * grid.voxel_m;
        ASSERT_NEAR(grid.sdf_m[v], box(p), grid.voxel_m) << i << "," << j << "," << k;
        ASSERT_TRUE(grid.density[v] >= 0.0f && grid.density[v] <= 1.0f);
        // Density exactly inside the box: the distance is the cloud's.
        if (box(p) < -0.5f * grid.voxel_m) ASSERT_GT(grid.density[v], 0.0f);
        if (box(p) > 0.5f * grid.voxel_m) ASSERT_EQ(grid.density[v], 0.0f);
      }
  // Deep inside it is whole; near the surface the noise erodes it.
  EXPECT_EQ(grid.density[grid.index(grid.dims.x / 2, grid.dims.y / 2, grid.dims.z / 2)], 1.0f);
}

TEST_F(VoxelVoxelize, RefusesOpenEmptyAndMissingMeshes) {
  expect_refused(write_box("open.obj", glm::vec3(0.0f), glm::vec3(1.0f), 5),
                 "open.obj: is not watertight: 4 open edges (a closed mesh is required)");
  std::ofstream((dir_ / "points.obj").string()) << "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  expect_refused((dir_ / "points.obj").string(), "points.obj: has no triangles");
  expect_refused((dir_ / "missing.obj").string(), "missing.obj: does not exist");
}

}  // namespace
}  // namespace nephele::voxel
