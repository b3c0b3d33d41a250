#include "render/modules/terrain/terrain.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "image/input_images.h"
#include "nephele/error.h"
#include "nephele/scene_io.h"
#include "terrain/heightfield.h"

namespace nephele {
namespace {

gpu::Texture r32f(gpu::Context& ctx, uint32_t w, uint32_t h) {
  return gpu::Texture(ctx, w, h, 1, VK_FORMAT_R32_SFLOAT, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
}

// What the heights depend on: [terrain], the place (a GeoTIFF's) and the planet's radius.
std::string terrain_key(const Scene& scene) {
  Scene only;
  only.terrain = scene.terrain;
  only.location = scene.location;
  only.atmosphere.planet_radius_km = scene.atmosphere.planet_radius_km;
  only.terrain.albedo = glm::vec3(0.0f);
  only.terrain.snow_altitude_m = 0.0f;
  only.terrain.albedo_map.clear();
  return scene_to_toml(only);
}

// The albedo map as half floats, linear, alpha 1 (read_albedo_map: a PNG's sRGB decoded; its
// errors are one line naming terrain.albedo_map). Its texels are freed before the texture is
// made, so that at most two copies of the map are held at once.
gpu::Texture albedo_texture(gpu::Context& ctx, const std::string& path) {
  HalfRgbaImage map = read_albedo_map(path);
  const uint32_t width = uint32_t(map.width), height = uint32_t(map.height);
  gpu::Buffer staging(ctx, map.halfs.size() * sizeof(uint16_t), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  std::memcpy(staging.data(), map.halfs.data(), map.halfs.size() * sizeof(uint16_t));
  map = {};
  gpu::Texture texture(ctx, width, height, 1, VK_FORMAT_R16G16B16A16_SFLOAT,
                       VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  ctx.submit_and_wait([&](VkCommandBuffer cmd) { texture.record_upload(cmd, staging); });
  return texture;
}

void upload(gpu::Context& ctx, const gpu::Texture& texture, const std::vector<float>& values) {
  gpu::Buffer staging(ctx, values.size() * sizeof(float), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  std::memcpy(staging.data(), values.data(), values.size() * sizeof(float));
  ctx.submit_and_wait([&](VkCommandBuffer cmd) { texture.record_upload(cmd, staging); });
}

}  // namespace

TerrainModule::TerrainModule(gpu::Context& ctx, gpu::DescriptorSet& set, ImageLayers& layers)
    : ctx_(ctx),
      set_(set),
      heights_(r32f(ctx, 1, 1)),
      albedo_(ctx, 1, 1, 1, VK_FORMAT_R16G16B16A16_SFLOAT, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE),
      layers_(layers) {
  set_.bind_sampled_image(gpu::kTerrainHeights, heights_);
  set_.bind_sampled_image(gpu::kTerrainAlbedoMap, albedo_);
  ctx_.submit_and_wait([&](VkCommandBuffer cmd) {
    for (const gpu::Texture* t : {&heights_, &albedo_}) t->record_clear(cmd);
  });
}

bool TerrainModule::prepare(const Scene& scene, int width, int height, bool host_scene,
                            gpu::FrameParams& params) {
  const bool present = !scene.terrain.file.empty() || !scene.terrain.preset.empty();
  if (present || host_scene) layers_.require(width, height);
  width_ = width;
  height_ = height;
  if (!present) return false;
  raster_frame_ = scene.terrain.method == "raster";
  if (raster_frame_ && (depth_.width() != uint32_t(width) || depth_.height() != uint32_t(height))) {
    ctx_.wait_queue_idle();
    depth_ = gpu::DepthTarget(ctx_, uint32_t(width), uint32_t(height));
  }
  const std::string key = terrain_key(scene);
  if (key != key_) {
    const terrain::Heightfield field = terrain::load_heightfield(scene);
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(ctx_.physical_device(), &properties);
    const uint32_t largest = properties.limits.maxImageDimension2D;
    if (uint32_t(field.width) > largest || uint32_t(field.height) > largest)
      throw InputError("terrain.file '" + scene.terrain.file + "': " + std::to_string(field.width) +
                       " x " + std::to_string(field.height) +
                       " points exceed this device's largest image (" + std::to_string(largest) +
                       " a side); resample it smaller");
    const terrain::MaxPyramid pyramid = terrain::max_pyramid(field);
    ctx_.wait_queue_idle();
    // The heights, and their pyramid below them (one sampler: lavapipe allows 32 a stage).
    const int w = std::max(field.width, pyramid.width), h = field.height + pyramid.height;
    std::vector<float> texels(size_t(w) * size_t(h), 0.0f);
    for (int y = 0; y < field.height; ++y)
      std::copy_n(field.height_m.begin() + ptrdiff_t(y) * field.width, field.width,
                  texels.begin() + ptrdiff_t(y) * w);
    for (int y = 0; y < pyramid.height; ++y)
      std::copy_n(pyramid.texels.begin() + ptrdiff_t(y) * pyramid.width, pyramid.width,
                  texels.begin() + ptrdiff_t(field.height + y) * w);
    heights_ = r32f(ctx_, uint32_t(w), uint32_t(h));
    upload(ctx_, heights_, texels);
    set_.bind_sampled_image(gpu::kTerrainHeights, heights_);
    rect_ = glm::vec4(field.center_m.x - 0.5f * field.extent_m.x,
                      field.center_m.y + 0.5f * field.extent_m.y, field.extent_m);
    shape_ = glm::vec4(field.min_height_m(), field.max_height_m(), 1.0f, 0.0f);
    grid_ = glm::ivec4(field.width, field.height, pyramid.levels, pyramid.size(1).x);
    key_ = key;
  }
  if (scene.terrain.albedo_map != albedo_path_ && !scene.terrain.albedo_map.empty()) {
    gpu::Texture map = albedo_texture(ctx_, scene.terrain.albedo_map);
    ctx_.wait_queue_idle();
    albedo_ = std::move(map);
    set_.bind_sampled_image(gpu::kTerrainAlbedoMap, albedo_);
  }
  albedo_path_ = scene.terrain.albedo_map;
  params.terrain_rect = rect_;
  params.terrain_shape = glm::vec4(shape_.x, shape_.y, 1.0f, scene.terrain.snow_altitude_m);
  params.terrain_albedo = glm::vec4(scene.terrain.albedo, albedo_path_.empty() ? 0.0f : 1.0f);
  params.terrain_grid = grid_;
  return true;
}

void TerrainModule::record(VkCommandBuffer cmd, gpu::PassTimer& timer) {
  if (!raster_frame_) {
    if (!kernel_) kernel_ = std::make_unique<gpu::Kernel>(ctx_, set_, "terrain.comp.spv");
    gpu::dispatch(cmd, *kernel_, timer, "terrain", uint32_t(width_), uint32_t(height_), 1, 8, 8, 1);
    return;
  }
  if (!raster_) {
    raster_ = std::make_unique<gpu::RasterPass>(
        ctx_, set_, std::vector<VkFormat>{ImageLayers::kFormat}, true,
        std::vector<gpu::RasterShaders>{{"terrain.vert.spv", "terrain.frag.spv"}}, true);
    raster_kernel_ =
        std::make_unique<gpu::Kernel>(ctx_, set_, "terrain.comp.spv", std::vector<int32_t>{1});
  }
  gpu::RasterDraw mesh;
  const glm::ivec2 cells = glm::ivec2(grid_) - 1;
  mesh.vertex_count = uint32_t(cells.x) * uint32_t(cells.y) * 6u;
  mesh.constants.info = glm::ivec4(cells.x, 0, 0, 0);
  raster_->record(cmd, timer, "terrain_mesh",
                  {layers_.target(gpu::LAYER_SURFACES, width_, height_)}, {mesh}, &depth_);
  gpu::dispatch(cmd, *raster_kernel_, timer, "terrain", uint32_t(width_), uint32_t(height_), 1, 8,
                8, 1);
}

void TerrainModule::add_passes(FrameGraph& graph, const FrameSetup& frame) {
  graph.import("terrain");  // read whether or not it is drawn this frame
  if (frame.params.terrain_shape.z > 0.0f)
    graph.add_pass("terrain",
                   {"ground_light", "light_volume", "weather_map", "noise", "sky_view",
                    "atmosphere", FrameGraph::kView},
                   {"terrain"},
                   [timer = frame.timer, this](VkCommandBuffer cmd) { record(cmd, timer()); });
}

void TerrainModule::prepare(const FramePrepare& frame, FramePlan& plan) {
  prepare(frame.scene, frame.width, frame.height, plan.host_scene, frame.params);
}

}  // namespace nephele
