#include "render/modules/voxel_clouds/voxel_clouds.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "nephele/error.h"
#include "render/frame_params.h"
#include "voxel/bricks.h"

namespace nephele {

namespace {

constexpr VkFormat kAtlasFormat = VK_FORMAT_R16G16_SFLOAT;
constexpr VkFormat kPageFormat = VK_FORMAT_R32_SFLOAT;
// The largest 3D image every Vulkan device takes on each axis (maxImageDimension3D >= 256 is
// all the specification promises, but every desktop device and lavapipe take 2048).
constexpr int kMaxAtlasTexels = 2048;
// The noise clouds fade in over this distance (m) from a voxel cloud's box.
constexpr float kNoiseFadeM = 500.0f;
// How much the raised-frequency detail noise erodes a voxel cloud's surface, and its frequency
// as a multiple of the noise clouds' detail noise.
constexpr float kSurfaceErosion = 0.5f;
constexpr float kSurfaceDetailFrequency = 4.0f;

gpu::Texture texture_of(gpu::Context& ctx, glm::ivec3 size, VkFormat format) {
  return gpu::Texture(ctx, uint32_t(size.x), uint32_t(size.y), uint32_t(size.z), format,
                      VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
}

}  // namespace

VoxelCloudsModule::VoxelCloudsModule(gpu::Context& ctx, gpu::DescriptorSet& set)
    : ctx_(ctx),
      set_(set),
      // Until the first voxel cloud: 1 x 1 x 2 (a depth of 1 would make a 2D image).
      atlas_(texture_of(ctx, glm::ivec3(1, 1, 2), kAtlasFormat)),
      pages_(texture_of(ctx, glm::ivec3(1, 1, 2), kPageFormat)) {
  set_.bind_sampled_image(gpu::kVoxelAtlas, atlas_);
  set_.bind_sampled_image(gpu::kVoxelPages, pages_);
}

std::string VoxelCloudsModule::source_of(const VoxelCloudParams& cloud) {
  const std::string what =
      cloud.file.empty() ? "preset:" + cloud.preset + ":" + std::to_string(cloud.seed) : cloud.file;
  return what + "@" + std::to_string(cloud.resolution);
}

const voxel::VoxelGrid& VoxelCloudsModule::grid(const VoxelCloudParams& cloud) {
  const std::string key = source_of(cloud);
  auto it = grids_.find(key);
  if (it == grids_.end()) {
    voxel::VoxelGrid g =
        cloud.file.empty()
            ? voxel::make_cloud(voxel::parse_cloud_preset(cloud.preset, "voxel_clouds.preset"),
                                cloud.seed, cloud.resolution)
            : voxel::load_voxel_cloud(cloud.file, cloud.resolution);
    it = grids_.emplace(key, std::make_unique<voxel::VoxelGrid>(std::move(g))).first;
  }
  return *it->second;
}

void VoxelCloudsModule::upload(const std::vector<const voxel::VoxelGrid*>& grids) {
  const voxel::BrickPool pool = voxel::pack_bricks(grids);
  if (pool.atlas_texels.z > kMaxAtlasTexels || pool.page_texels.z > kMaxAtlasTexels) {
    size_t stored = 0;
    for (const voxel::BrickedCloud& c : pool.clouds) stored += c.stored_bricks;
    throw InputError("voxel_clouds: " + std::to_string(stored) + " bricks of " +
                     std::to_string(voxel::kBrick) +
                     "^3 voxels near the clouds' surfaces: at most " +
                     std::to_string(kMaxAtlasTexels / voxel::kBrickTexels * voxel::kAtlasBricksXY *
                                    voxel::kAtlasBricksXY) +
                     " fit (fewer clouds, or a lower resolution)");
  }
  ctx_.wait_queue_idle();  // the frames in flight read the textures replaced
  atlas_ = texture_of(ctx_, pool.atlas_texels, kAtlasFormat);
  pages_ = texture_of(ctx_, pool.page_texels, kPageFormat);
  gpu::Buffer atlas_staging(ctx_, pool.atlas_bytes(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  gpu::Buffer page_staging(ctx_, pool.page_bytes(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  std::memcpy(atlas_staging.data(), pool.atlas.data(), pool.atlas_bytes());
  std::memcpy(page_staging.data(), pool.pages.data(), pool.page_bytes());
  ctx_.submit_and_wait([&](VkCommandBuffer cmd) {
    atlas_.record_upload(cmd, atlas_staging);
    pages_.record_upload(cmd, page_staging);
  });
  set_.bind_sampled_image(gpu::kVoxelAtlas, atlas_);
  set_.bind_sampled_image(gpu::kVoxelPages, pages_);

  bricks_.clear();
  memory_.clear();
  device_bytes_ = pool.atlas_bytes() + pool.page_bytes();
  for (size_t i = 0; i < grids.size(); ++i) {
    const voxel::BrickedCloud& c = pool.clouds[i];
    bricks_.emplace_back(c.bricks, c.page_z);
    VoxelCloudMemory m;
    for (int a = 0; a < 3; ++a) m.dims[a] = grids[i]->dims[a];
    m.stored_bricks = c.stored_bricks;
    m.total_bricks = size_t(c.bricks.x) * size_t(c.bricks.y) * size_t(c.bricks.z);
    m.bytes = c.bytes;
    m.dense_bytes = size_t(c.dims.x) * size_t(c.dims.y) * size_t(c.dims.z) * 4;
    memory_.push_back(m);
  }
}

void VoxelCloudsModule::prepare(const Scene& scene, gpu::FrameParams& params) {
  const int n = int(std::min<size_t>(scene.voxel_clouds.size(), size_t(gpu::MAX_VOXEL_CLOUDS)));
  std::vector<std::string> sources;
  std::vector<const voxel::VoxelGrid*> grids;
  for (int i = 0; i < n; ++i) {
    sources.push_back(source_of(scene.voxel_clouds[size_t(i)]));
    grids.push_back(&grid(scene.voxel_clouds[size_t(i)]));
  }
  if (sources != uploaded_) {
    upload(grids);
    uploaded_ = sources;
  }
  params.voxel_info = glm::ivec4(n, int(scene.quality.voxel_march == VoxelMarch::ThreePhase),
                                 int(scene.quality.voxel_shadow == VoxelShadow::SdfCone), 0);
  params.voxel_light = glm::vec4(scene.quality.sdf_light_tangent, kNoiseFadeM, kSurfaceErosion,
                                 kSurfaceDetailFrequency);
  const float planet_m = params.radii_m.x;
  // The voxel clouds' sigma_t at density 1 as a share of cloud_shape.z (the droplets' cumulus).
  const CloudOptics optics = cloud_optics(scene);
  const float sigma_share = optics.voxel_sigma_t_per_m / optics.max_sigma_t_per_m();
  for (int i = 0; i < n; ++i) {
    const VoxelCloudParams& c = scene.voxel_clouds[size_t(i)];
    const voxel::VoxelGrid& g = *grids[size_t(i)];
    const glm::vec2 wind = c.follow_wind ? scene.clouds.wind_mps : c.wind_mps;
    const glm::vec3 enu = c.position_m + glm::vec3(wind * scene.time_s, 0.0f);
    // The anchor c.position_m.z above the sphere below (E, N), the cloud upright there.
    const float r = planet_m + enu.z;
    const glm::vec3 anchor(enu.x, enu.y,
                           std::sqrt(std::max(r * r - enu.x * enu.x - enu.y * enu.y, 0.0f)));
    const glm::vec3 up = glm::normalize(anchor);
    const glm::vec3 east = glm::normalize(glm::cross(glm::vec3(0.0f, 1.0f, 0.0f), up));
    const glm::vec3 north = glm::cross(up, east);
    // rotation_deg turns the cloud's north axis towards the east.
    const float a = glm::radians(c.rotation_deg);
    const glm::vec3 axes[3] = {std::cos(a) * east - std::sin(a) * north,
                               std::cos(a) * north + std::sin(a) * east, up};
    gpu::VoxelCloudGpu& out = params.voxel_clouds[i];
    const float voxel_m = g.voxel_m * c.scale;
    glm::vec4* rows[3] = {&out.to_grid_x, &out.to_grid_y, &out.to_grid_z};
    for (int k = 0; k < 3; ++k) *rows[k] = glm::vec4(axes[k] / voxel_m, -g.origin_m[k] / g.voxel_m);
    out.anchor_m = glm::vec4(anchor, c.density * sigma_share);
    out.dims = glm::vec4(glm::vec3(g.dims), voxel_m);
    out.bricks = bricks_[size_t(i)];
    // The cloud shell reaches from the lowest cloud's base to the highest top.
    const float bottom_m = enu.z + g.origin_m.z * c.scale;
    params.radii_m.z = std::min(params.radii_m.z, planet_m + bottom_m);
    params.radii_m.w = std::max(params.radii_m.w, planet_m + bottom_m + g.extent_m().z * c.scale);
    memory_[size_t(i)].source = sources[size_t(i)].substr(0, sources[size_t(i)].rfind('@'));
    memory_[size_t(i)].voxel_m = voxel_m;
  }
}

void VoxelCloudsModule::add_passes(FrameGraph& graph, const FrameSetup& /*frame*/) {
  graph.import("voxel_clouds");  // the atlas, uploaded before the frame
}

void VoxelCloudsModule::prepare(const FramePrepare& frame, FramePlan&) {
  prepare(frame.scene, frame.params);
}

}  // namespace nephele
