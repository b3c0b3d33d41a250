// nephele — voxel clouds: signed distances from a density or a mesh with OpenVDB's tools.
#include "voxel/level_set.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/VolumeToMesh.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <mutex>
#include <stdexcept>

namespace nephele::voxel {
namespace {

// The band (voxels) that covers every voxel of the grid, inside and out: the grid's diagonal.
float whole_grid_band(glm::ivec3 dims) {
  return std::sqrt(float(glm::dot(glm::vec3(dims), glm::vec3(dims)))) + 2.0f;
}

// Copies the level set at index (i, j, k) into the dense grid's voxel (i, j, k), scaled to
// metres (the level set is in voxel units when its transform is the unit one).
void copy_dense(const openvdb::FloatGrid& sdf, glm::ivec3 dims, float scale,
                std::vector<float>& out) {
  out.assign(size_t(dims.x) * dims.y * dims.z, 0.0f);
  tbb::parallel_for(0, dims.z, [&](int k) {
    openvdb::FloatGrid::ConstAccessor acc = sdf.getConstAccessor();
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i)
        out[size_t(i) + size_t(dims.x) * (size_t(j) + size_t(dims.y) * k)] =
            acc.getValue(openvdb::Coord(i, j, k)) * scale;
  });
}

}  // namespace

void initialize_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

void compute_sdf_from_density(VoxelGrid& grid) {
  initialize_openvdb();
  // In index space (voxel (i, j, k) at (i, j, k)); the density negated, so that "inside"
  // (below the isovalue, as volumeToMesh has it) is density > kIso and the mesh faces out.
  // A tiny isovalue puts the surface next to the first voxel centre without density: where
  // the trilinear density reaches zero.
  constexpr float kIso = 1e-6f;
  openvdb::FloatGrid::Ptr fog = openvdb::FloatGrid::create(0.0f);
  {
    openvdb::FloatGrid::Accessor acc = fog->getAccessor();
    for (int k = 0; k < grid.dims.z; ++k)
      for (int j = 0; j < grid.dims.y; ++j)
        for (int i = 0; i < grid.dims.x; ++i) {
          const float d = grid.density[grid.index(i, j, k)];
          if (d > 0.0f) acc.setValue(openvdb::Coord(i, j, k), -d);
        }
  }
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(*fog, points, triangles, quads, -kIso, 0.0);
  if (points.empty()) throw std::logic_error("compute_sdf_from_density: no density");
  const float band = whole_grid_band(grid.dims);
  openvdb::FloatGrid::Ptr sdf = openvdb::tools::meshToSignedDistanceField<openvdb::FloatGrid>(
      *openvdb::math::Transform::createLinearTransform(1.0), points, triangles, quads, band, band);
  copy_dense(*sdf, grid.dims, grid.voxel_m, grid.sdf_m);
}

std::vector<float> mesh_signed_distance(const std::vector<glm::vec3>& points_m,
                                        const std::vector<glm::uvec3>& triangles,
                                        const VoxelGrid& layout) {
  initialize_openvdb();
  // Index (i, j, k) is the centre of the dense grid's voxel (i, j, k).
  openvdb::math::Transform::Ptr xform =
      openvdb::math::Transform::createLinearTransform(layout.voxel_m);
  const glm::vec3 first_centre = layout.origin_m + 0.5f * layout.voxel_m;
  xform->postTranslate(openvdb::Vec3d(first_centre.x, first_centre.y, first_centre.z));
  std::vector<openvdb::Vec3s> points;
  points.reserve(points_m.size());
  for (const glm::vec3& p : points_m) points.emplace_back(p.x, p.y, p.z);
  std::vector<openvdb::Vec3I> tris;
  tris.reserve(triangles.size());
  for (const glm::uvec3& t : triangles) tris.emplace_back(t.x, t.y, t.z);
  const float band = whole_grid_band(layout.dims);
  openvdb::FloatGrid::Ptr sdf = openvdb::tools::meshToSignedDistanceField<openvdb::FloatGrid>(
      *xform, points, tris, {}, band, band);
  // The level set is in world units (metres) already.
  std::vector<float> out;
  copy_dense(*sdf, layout.dims, 1.0f, out);
  return out;
}

}  // namespace nephele::voxel
