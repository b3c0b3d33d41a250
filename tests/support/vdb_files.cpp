// Test files for the voxel-cloud importer, written with OpenVDB's and NanoVDB's own writers.
#include "support/vdb_files.h"

#include <nanovdb/util/IO.h>
#include <nanovdb/util/OpenToNanoVDB.h>
#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>

#include <cmath>
#include <fstream>

#include "voxel/voxel_grid.h"

namespace nephele::test {
namespace {

openvdb::FloatGrid::Ptr fog_ball(const std::string& name) {
  openvdb::initialize();
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
  grid->setName(name);
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  grid->setTransform(openvdb::math::Transform::createLinearTransform(0.5));
  openvdb::FloatGrid::Accessor acc = grid->getAccessor();
  for (int k = -6; k <= 6; ++k)
    for (int j = -6; j <= 6; ++j)
      for (int i = -6; i <= 6; ++i) {
        const float r = std::sqrt(float(i * i + j * j + k * k)) / 6.5f;
        if (r < 1.0f) acc.setValue(openvdb::Coord(i, j, k), 1.0f - r);
      }
  return grid;
}

void write(const std::string& path, openvdb::GridBase::Ptr grid) {
  openvdb::io::File(path).write(openvdb::GridPtrVec{grid});
}

}  // namespace

void write_fog_balls_vdb(const std::string& path, const std::vector<std::string>& names) {
  openvdb::GridPtrVec grids;
  for (const std::string& n : names) grids.push_back(fog_ball(n));
  openvdb::io::File(path).write(grids);
}

void write_fog_balls_nvdb(const std::string& path, const std::vector<std::string>& names) {
  std::vector<nanovdb::GridHandle<>> handles;
  for (const std::string& n : names) handles.push_back(nanovdb::openToNanoVDB(*fog_ball(n)));
  nanovdb::io::writeGrids(path, handles);
}

void write_vector_density_vdb(const std::string& path) {
  openvdb::initialize();
  openvdb::Vec3SGrid::Ptr grid = openvdb::Vec3SGrid::create();
  grid->setName("density");
  grid->tree().setValue(openvdb::Coord(0, 0, 0), openvdb::Vec3s(1, 0, 0));
  write(path, grid);
}

void write_empty_density_vdb(const std::string& path) {
  openvdb::initialize();
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  write(path, grid);
}

void write_nan_density_vdb(const std::string& path) {
  openvdb::FloatGrid::Ptr grid = fog_ball("density");
  grid->tree().setValue(openvdb::Coord(1, 2, 3), std::nanf(""));
  write(path, grid);
}

void write_far_apart_density_vdb(const std::string& path) {
  openvdb::initialize();
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  grid->tree().setValue(openvdb::Coord(0, 0, 0), 1.0f);
  grid->tree().setValue(openvdb::Coord(100000, 0, 0), 1.0f);
  write(path, grid);
}

void write_constant_cube_vdb(const std::string& path, int n, float voxel_m) {
  voxel::VoxelGrid g;
  g.dims = glm::ivec3(n);
  g.voxel_m = voxel_m;
  g.origin_m = glm::vec3(-0.5f * float(n) * voxel_m, -0.5f * float(n) * voxel_m, 0.0f);
  g.density.assign(size_t(n) * size_t(n) * size_t(n), 1.0f);
  g.sdf_m.assign(g.density.size(), -voxel_m);
  voxel::write_vdb(g, path);
}

void write_fog_balls_vdb_as(const std::string& path, const std::vector<std::string>& names,
                            uint32_t compression, bool half, bool stream) {
  openvdb::GridPtrVec grids;
  for (const std::string& n : names) {
    grids.push_back(fog_ball(n));
    grids.back()->setSaveFloatAsHalf(half);
  }
  if (stream) {
    std::ofstream out(path, std::ios::binary);
    openvdb::io::Stream writer(out);
    writer.setCompression(compression);
    writer.write(grids);
  } else {
    openvdb::io::File file(path);
    file.setCompression(compression);
    file.write(grids);
  }
}

void write_vector_then_density_stream(const std::string& path) {
  openvdb::initialize();
  openvdb::Vec3SGrid::Ptr velocity = openvdb::Vec3SGrid::create();
  velocity->setName("velocity");
  velocity->tree().setValue(openvdb::Coord(0, 0, 0), openvdb::Vec3s(1, 0, 0));
  std::ofstream out(path, std::ios::binary);
  openvdb::io::Stream(out).write(openvdb::GridPtrVec{velocity, fog_ball("density")});
}

void write_boxes_vdb(const std::string& path, const std::vector<VoxelBox>& boxes, float value,
                     float inactive, float background) {
  openvdb::initialize();
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(background);
  grid->setName("density");
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  for (const VoxelBox& b : boxes)
    grid->tree().fill(openvdb::CoordBBox(openvdb::Coord(b.lo[0], b.lo[1], b.lo[2]),
                                         openvdb::Coord(b.hi[0], b.hi[1], b.hi[2])),
                      value, /*active=*/true);
  for (auto leaf = grid->tree().beginLeaf(); leaf; ++leaf)
    for (auto it = leaf->beginValueOff(); it; ++it) it.setValue(inactive);
  write(path, grid);
}

}  // namespace nephele::test
