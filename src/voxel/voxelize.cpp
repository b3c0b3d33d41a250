// nephele — voxel clouds: a closed mesh baked into a cloud, as the seed's artists do it in
// Houdini: mesh -> level set (OpenVDB) -> fog -> Curly-Alligator erosion at the surface.
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <map>
#include <tuple>

#include "io/obj_text.h"
#include "nephele/error.h"
#include "voxel/common.h"
#include "voxel/level_set.h"
#include "voxel/voxel_grid.h"

namespace nephele::voxel {
namespace {

// The finest voxel a mesh is baked at: a cloud's detail needs no finer, and OpenVDB's level
// set tools fail on micrometre voxels ("Non-zero scale values required").
constexpr float kMinVoxelM = 1e-3f;

struct Mesh {
  std::vector<glm::vec3> points_m;
  std::vector<glm::uvec3> triangles;
};

// `where` names the mesh in messages (file_prefix).
Mesh read_obj(std::istream& in, const std::string& where) {
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warning, error;
  // No material reader: a mesh's .mtl is of no use here and must not be read.
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warning, &error, &in, nullptr,
                        /*triangulate=*/true))
    throw InputError(where + "is not a readable OBJ mesh (" +
                     obj_error_for_message(error, "no geometry") + ")");
  // Positions that are equal are one vertex: exporters split vertices at UV and normal seams,
  // which must not count as open edges.
  Mesh mesh;
  std::map<std::tuple<float, float, float>, uint32_t> welded;
  std::vector<uint32_t> vertex_of(attrib.vertices.size() / 3);
  for (size_t v = 0; v < vertex_of.size(); ++v) {
    const glm::vec3 p(attrib.vertices[3 * v], attrib.vertices[3 * v + 1],
                      attrib.vertices[3 * v + 2]);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw InputError(where + "vertex " + std::to_string(v + 1) +
                       " is not finite (finite coordinates in metres are required)");
    auto [it, added] = welded.try_emplace({p.x, p.y, p.z}, uint32_t(mesh.points_m.size()));
    if (added) mesh.points_m.push_back(p);
    vertex_of[v] = it->second;
  }
  for (const tinyobj::shape_t& shape : shapes) {
    const std::vector<tinyobj::index_t>& idx = shape.mesh.indices;
    size_t offset = 0;
    for (unsigned char n : shape.mesh.num_face_vertices) {
      if (n == 3) {
        glm::uvec3 t;
        for (int c = 0; c < 3; ++c) {
          const int v = idx[offset + c].vertex_index;
          if (v < 0 || size_t(v) >= vertex_of.size())
            throw InputError(where + "a face refers to a missing vertex");
          t[c] = vertex_of[size_t(v)];
        }
        // A triangle collapsed to an edge or a point bounds nothing.
        if (t.x != t.y && t.y != t.z && t.z != t.x) mesh.triangles.push_back(t);
      }
      offset += n;
    }
  }
  if (mesh.triangles.empty())
    throw InputError(where + "has no triangles (a closed triangle or polygon mesh is required)");
  return mesh;
}

// Edges not shared by exactly two triangles: where a mesh is open (or not a manifold).
size_t count_open_edges(const Mesh& mesh) {
  std::vector<std::pair<uint32_t, uint32_t>> edges;
  edges.reserve(mesh.triangles.size() * 3);
  for (const glm::uvec3& t : mesh.triangles)
    for (int e = 0; e < 3; ++e) {
      const uint32_t a = t[e], b = t[(e + 1) % 3];
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  size_t open = 0;
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i != 2) ++open;
    i = j;
  }
  return open;
}

float smoothstep(float e0, float e1, float x) {
  const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

VoxelGrid voxelize(const Mesh& mesh, const std::string& where, int max_dim) {
  if (const size_t open = count_open_edges(mesh); open > 0)
    throw InputError(where + "is not watertight: " + std::to_string(open) +
                     " open edges (a closed mesh is required)");
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (const glm::vec3& p : mesh.points_m) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::vec3 extent = hi - lo;
  const float longest = std::max({extent.x, extent.y, extent.z});
  if (!(longest > 0.0f) || !std::isfinite(longest) || longest > 1e7f)
    throw InputError(where + "extent " + std::to_string(longest) + " m: must be in (0, 1e7] m");
  constexpr int kPad = 2;
  VoxelGrid grid;
  fit_grid(extent, kPad, max_dim, grid);
  if (grid.voxel_m < kMinVoxelM)
    throw InputError(where + "extent " + number_for_message(longest) + " m at resolution " +
                     std::to_string(max_dim) + " gives voxels of " + number_for_message(grid.voxel_m) +
                     " m (at least " + number_for_message(kMinVoxelM) + " m: a mesh of at least " +
                     number_for_message(kMinVoxelM * float(max_dim - 2 * kPad)) +
                     " m, or a lower resolution)");
  // In the mesh's frame first: the grid centred on the mesh's box, its base two voxels below.
  grid.origin_m = 0.5f * (lo + hi) - 0.5f * glm::vec3(grid.dims) * grid.voxel_m;
  grid.origin_m.z = lo.z - kPad * grid.voxel_m;
  grid.sdf_m = mesh_signed_distance(mesh.points_m, mesh.triangles, grid);
  // Fog from the level set: 1 inside, fading over a skin at the surface, where the
  // Curly-Alligator noise erodes it. The density stays above zero everywhere inside the
  // mesh (eroded to a faint haze, not cut away), so the level set remains the distance to
  // the cloud's surface.
  const float skin_m = std::max(0.08f * longest, 2.5f * grid.voxel_m);
  const float frequency_per_m = 1.0f / (1.3f * skin_m);
  grid.density.assign(grid.sdf_m.size(), 0.0f);
  for (int k = 0; k < grid.dims.z; ++k)
    for (int j = 0; j < grid.dims.y; ++j)
      for (int i = 0; i < grid.dims.x; ++i) {
        const size_t v = grid.index(i, j, k);
        const float d = grid.sdf_m[v];
        if (d >= 0.0f) continue;
        const float inside = std::min(-d / skin_m, 1.0f);
        float density = 1.0f;
        if (inside < 1.0f) {
          const glm::vec3 p = grid.origin_m + (glm::vec3(i, j, k) + 0.5f) * grid.voxel_m;
          const float n = curly_alligator(p, frequency_per_m);
          const float erosion = 0.9f * (1.0f - n);
          const float eroded = std::clamp((inside - erosion) / (1.0f - erosion), 0.0f, 1.0f);
          density = std::max(eroded, 0.05f * smoothstep(0.0f, 1.0f, inside) + 1e-4f);
        }
        grid.density[v] = density;
      }
  if (std::none_of(grid.density.begin(), grid.density.end(), [](float d) { return d > 0.0f; }))
    throw InputError(where + "encloses no voxel centre at resolution " + std::to_string(max_dim) +
                     " (a mesh thicker than a voxel is required)");
  // The cloud's frame: its anchor is the centre of the mesh's base.
  grid.origin_m -= glm::vec3(0.5f * (lo.x + hi.x), 0.5f * (lo.y + hi.y), lo.z);
  return grid;
}

}  // namespace

VoxelGrid voxelize_mesh(const std::string& obj_path, int max_dim) {
  check_max_dim(max_dim);
  const std::string where = file_prefix(obj_path);
  std::istringstream in(read_obj_text(obj_path, where));
  return voxelize(read_obj(in, where), where, max_dim);
}

VoxelGrid voxelize_mesh_text(const std::string& obj_text, const std::string& name, int max_dim) {
  check_max_dim(max_dim);
  if (const std::string problem = obj_number_problem(obj_text); !problem.empty())
    throw InputError(name + ": " + problem);
  std::istringstream in(obj_text);
  return voxelize(read_obj(in, name + ": "), name + ": ", max_dim);
}

}  // namespace nephele::voxel
