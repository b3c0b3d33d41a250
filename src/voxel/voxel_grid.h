// nephele — voxel clouds (seed 002, 体素云建模): a cloud's density and signed distance on a
// dense grid in the cloud's own frame, as imported from OpenVDB/NanoVDB, baked from a mesh or
// generated procedurally. The renderer packs it into bricks on the device (render/modules/voxel).
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace nephele::voxel {

// The cloud's frame: x east, y north, z up (metres at scale 1). Voxel (i, j, k) is the cube
// [origin_m + (i, j, k) * voxel_m, origin_m + (i + 1, j + 1, k + 1) * voxel_m); values are
// at voxel centres. Index of (i, j, k): i + dims.x * (j + dims.y * k).
struct VoxelGrid {
  glm::ivec3 dims{0};
  float voxel_m = 0.0f;
  glm::vec3 origin_m{0.0f};      // min corner, relative to the cloud's anchor (its base centre)
  // Where the anchor lies in the file's own frame (m), and the factor the file's densities
  // were divided by to bring them into [0, 1] (1 when they were): the lab scene renders the
  // grid where and as dense as the file has it.
  glm::vec3 file_anchor_m{0.0f};
  float file_density_scale = 1.0f;
  std::vector<float> density;    // in [0, 1]: sigma_t = density x the cloud's density scale
  std::vector<float> sdf_m;      // signed distance (m) to the surface of the cloud (where
                                 // density > 0): negative inside, exact to within one voxel
                                 // over the whole grid (not only a narrow band)

  size_t index(int i, int j, int k) const {
    return static_cast<size_t>(i) + static_cast<size_t>(dims.x) * (static_cast<size_t>(j) +
                                    static_cast<size_t>(dims.y) * static_cast<size_t>(k));
  }
  glm::vec3 extent_m() const { return glm::vec3(dims) * voxel_m; }
};

// The largest grid the renderer takes, per axis, and in all: an import resamples to fit.
constexpr int kMaxGridDim = 256;

// Reads a voxel cloud: OpenVDB (.vdb: a float grid named "density" (fog volume), optionally a
// float level set named "sdf") or NanoVDB (.nvdb: the same grids). Where the file has no "sdf",
// the signed distance is computed from the density with OpenVDB's tools. The grid is resampled
// so its longest axis has at most `max_dim` voxels (at most kMaxGridDim). Throws InputError
// with one line naming the file, what is wrong and what is allowed (missing grid, wrong grid
// type, truncated or unreadable file, empty density, dimensions too large).
VoxelGrid load_voxel_cloud(const std::string& path, int max_dim = 128);

// Writes `grid` as OpenVDB: "density" (fog volume, zero background) and "sdf" (level set).
// Atomic: the file is whole or not written (write_file_atomically).
void write_vdb(const VoxelGrid& grid, const std::string& path);

// The presets of `nephele make-cloud` and of scenes' voxel clouds: three generated, and one
// baked from the mesh shipped in data/meshes/cumulus.obj (embedded), as an artist's would be.
enum class CloudPreset { Cumulus, CumulusCongestus, Cumulonimbus, CumulusMesh, Cube };
inline constexpr std::string_view kCloudPresetNames[] = {"cumulus", "cumulus-congestus",
                                                         "cumulonimbus", "cumulus-mesh", "cube"};
// One of kCloudPresetNames; InputError names the allowed values.
CloudPreset parse_cloud_preset(const std::string& name, const std::string& parameter);
const char* cloud_preset_name(CloudPreset preset);

// A cloud of `preset`'s shape (metaball clusters eroded at their surface by Curly-Alligator
// noise), the same for the same seed. About the size of a real cloud of its kind (cumulus
// ~1 km wide, congestus ~2-3 km tall, cumulonimbus ~8-10 km tall with an anvil).
// CumulusMesh: the shipped mesh baked by voxelize_mesh_text (the seed is not used).
// Cube: a cube of 1 km, density 1 throughout, its base at z = 0 (the lab's test body, whose
// multiple scattering a model must match; the seed is not used).
VoxelGrid make_cloud(CloudPreset preset, uint32_t seed, int max_dim = 128);

// Bakes a closed (watertight) triangle mesh (OBJ, metres, z up unless told otherwise) into a
// cloud: a level set from OpenVDB's mesh-to-volume, the density from it with Curly-Alligator
// erosion at the surface. Throws InputError naming the file when it cannot be read, has no
// triangles or is not watertight (names an open edge's count).
VoxelGrid voxelize_mesh(const std::string& obj_path, int max_dim = 128);
// The same from the OBJ's text; `name` stands for the file in messages.
VoxelGrid voxelize_mesh_text(const std::string& obj_text, const std::string& name,
                             int max_dim = 128);

// The seed's Curly-Alligator noise at p (cloud frame, metres): alligator (cellular) noise of
// two rising frequencies, its domain displaced by curl noise; in [0, 1].
float curly_alligator(glm::vec3 p_m, float frequency_per_m);

}  // namespace nephele::voxel
