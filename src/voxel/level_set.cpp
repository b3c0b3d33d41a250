// nephele — voxel clouds: signed distances from a density (exact distance transforms) or a
// mesh (OpenVDB's mesh-to-level-set near it, distance transforms beyond).
#include "voxel/level_set.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <mutex>
#include <stdexcept>

namespace nephele::voxel {
namespace {

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

// Squared Euclidean distance transform along one line (Felzenszwalb & Huttenlocher 2012):
// f[q] = min over p of (q - p)^2 + f[p], through the lower envelope of the parabolas.
void edt_line(float* f, int n, int stride, std::vector<float>& d, std::vector<int>& v,
              std::vector<float>& z) {
  constexpr float kInf = 1e20f;
  d.resize(n);
  v.resize(n);
  z.resize(n + 1);
  int k = -1;
  for (int q = 0; q < n; ++q) {
    const float fq = f[size_t(q) * stride];
    if (fq >= kInf) continue;
    float s = -kInf;
    while (k >= 0) {
      const int p = v[k];
      const float fp = f[size_t(p) * stride];
      s = ((fq + float(q) * q) - (fp + float(p) * p)) / (2.0f * float(q - p));
      if (s > z[k]) break;
      --k;
    }
    ++k;
    v[k] = q;
    z[k] = k == 0 ? -kInf : s;
    z[k + 1] = kInf;
  }
  if (k < 0) return;  // no finite value on the line: all stay infinite
  int j = 0;
  for (int q = 0; q < n; ++q) {
    while (z[j + 1] < float(q)) ++j;
    const float dq = float(q - v[j]);
    d[q] = dq * dq + f[size_t(v[j]) * stride];
  }
  for (int q = 0; q < n; ++q) f[size_t(q) * stride] = d[q];
}

// The distance (voxels) from every voxel centre to the nearest centre where `target` holds:
// exact (Euclidean, not chamfer), separable in x, y and z, linear in the voxel count.
std::vector<float> distance_to(const std::vector<uint8_t>& target, glm::ivec3 dims) {
  std::vector<float> f(target.size());
  for (size_t v = 0; v < f.size(); ++v) f[v] = target[v] ? 0.0f : 1e20f;
  const size_t nx = size_t(dims.x), nxy = nx * dims.y;
  tbb::parallel_for(0, dims.z, [&](int k) {
    std::vector<float> d, z;
    std::vector<int> v;
    for (int j = 0; j < dims.y; ++j) edt_line(&f[k * nxy + j * nx], dims.x, 1, d, v, z);
    for (int i = 0; i < dims.x; ++i) edt_line(&f[k * nxy + i], dims.y, int(nx), d, v, z);
  });
  tbb::parallel_for(0, dims.y, [&](int j) {
    std::vector<float> d, z;
    std::vector<int> v;
    for (int i = 0; i < dims.x; ++i) edt_line(&f[j * nx + i], dims.z, int(nxy), d, v, z);
  });
  for (float& x : f) x = std::sqrt(x);
  return f;
}

}  // namespace

void initialize_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

void compute_sdf_from_density(VoxelGrid& grid) {
  // Exact distance transforms of the voxel centres with and without density. OpenVDB's
  // volume-to-mesh then mesh-to-level-set with bands as wide as the grid gave the same
  // distances to within a voxel, but took 30-50 s at 128^3 on two cores (its band grows a
  // voxel layer at a time); these take well under a second.
  // The density's trilinear interpolation reaches zero next to the first centre without
  // density: outside, the distance to the nearest centre with density less one voxel (over
  // by at most (sqrt(3) - 1) voxels, diagonally); inside, the distance to the nearest centre
  // without density.
  const size_t count = grid.density.size();
  std::vector<uint8_t> dense(count), empty(count);
  bool any = false;
  for (size_t v = 0; v < count; ++v) {
    dense[v] = grid.density[v] > 0.0f;
    empty[v] = !dense[v];
    any = any || dense[v];
  }
  if (!any) throw std::logic_error("compute_sdf_from_density: no density");
  const std::vector<float> to_dense = distance_to(dense, grid.dims);
  const std::vector<float> to_empty = distance_to(empty, grid.dims);
  grid.sdf_m.resize(count);
  for (int k = 0; k < grid.dims.z; ++k)
    for (int j = 0; j < grid.dims.y; ++j)
      for (int i = 0; i < grid.dims.x; ++i) {
        const size_t v = grid.index(i, j, k);
        // Beyond the grid there is no density: the inside distance is at most the way out.
        const int out =
            std::min({i + 1, j + 1, k + 1, grid.dims.x - i, grid.dims.y - j, grid.dims.z - k});
        const float voxels = dense[v] ? -std::min(to_empty[v], float(out)) : to_dense[v] - 1.0f;
        grid.sdf_m[v] = voxels * grid.voxel_m;
      }
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
  // A narrow band, exact (distances to the triangles), and its sign everywhere (OpenVDB
  // flood-fills the inside). A band as wide as the grid took tens of seconds at 128^3.
  constexpr float kHalfWidth = 3.0f;
  openvdb::FloatGrid::Ptr level_set =
      openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(*xform, points, tris, kHalfWidth);
  std::vector<float> out;
  copy_dense(*level_set, layout.dims, 1.0f, out);
  // Beyond the band: the distance to the nearest centre on the other side, less half a voxel
  // (the surface lies between, within half a voxel's diagonal of that centre).
  const size_t count = out.size();
  std::vector<uint8_t> inside(count), outside(count);
  for (size_t v = 0; v < count; ++v) inside[v] = out[v] < 0.0f, outside[v] = !inside[v];
  const std::vector<float> to_inside = distance_to(inside, layout.dims);
  const std::vector<float> to_outside = distance_to(outside, layout.dims);
  const float band_m = (kHalfWidth - 0.5f) * layout.voxel_m;
  for (size_t v = 0; v < count; ++v) {
    if (std::fabs(out[v]) < band_m) continue;
    out[v] = inside[v] ? -std::min((to_outside[v] - 0.5f) * layout.voxel_m, 1e30f)
                       : std::min((to_inside[v] - 0.5f) * layout.voxel_m, 1e30f);
  }
  return out;
}

}  // namespace nephele::voxel
