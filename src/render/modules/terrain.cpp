#include "render/modules/terrain.h"

#include <cstring>

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
  return scene_to_toml(only);
}

void upload(gpu::Context& ctx, const gpu::Texture& texture, const std::vector<float>& values) {
  gpu::Buffer staging(ctx, values.size() * sizeof(float), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  std::memcpy(staging.data(), values.data(), values.size() * sizeof(float));
  ctx.submit_and_wait([&](VkCommandBuffer cmd) { texture.record_upload(cmd, staging); });
}

}  // namespace

TerrainModule::TerrainModule(gpu::Context& ctx, gpu::DescriptorSet& set)
    : ctx_(ctx), set_(set), heights_(r32f(ctx, 1, 1)), maxima_(r32f(ctx, 1, 1)),
      out_(ctx, 1, 1, 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE) {
  set_.bind_sampled_image(gpu::kTerrainHeights, heights_);
  set_.bind_sampled_image(gpu::kTerrainMaxima, maxima_);
  set_.bind_image(gpu::kTerrainOut, gpu::kTerrain, out_);
  ctx_.submit_and_wait([&](VkCommandBuffer cmd) {
    for (const gpu::Texture* t : {&heights_, &maxima_, &out_}) t->record_clear(cmd);
  });
}

bool TerrainModule::prepare(const Scene& scene, int width, int height, gpu::FrameParams& params) {
  const bool present = !scene.terrain.file.empty() || !scene.terrain.preset.empty();
  if (present && (out_.width() != uint32_t(width) || out_.height() != uint32_t(height))) {
    ctx_.wait_queue_idle();  // a frame in flight may still read the old one
    out_ = gpu::Texture(ctx_, uint32_t(width), uint32_t(height), 1, VK_FORMAT_R32G32B32A32_SFLOAT,
                        VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
    set_.bind_image(gpu::kTerrainOut, gpu::kTerrain, out_);
  }
  if (!present) return false;
  const std::string key = terrain_key(scene);
  if (key != key_) {
    const terrain::Heightfield field = terrain::load_heightfield(scene);
    VkPhysicalDeviceProperties properties;
    vkGetPhysicalDeviceProperties(ctx_.physical_device(), &properties);
    const uint32_t largest = properties.limits.maxImageDimension2D;
    if (uint32_t(field.width) > largest || uint32_t(field.height) > largest)
      throw InputError("terrain.file '" + scene.terrain.file + "': " + std::to_string(field.width) +
                       " x " + std::to_string(field.height) + " points exceed this device's largest image (" +
                       std::to_string(largest) + " a side); resample it smaller");
    const terrain::MaxPyramid pyramid = terrain::max_pyramid(field);
    ctx_.wait_queue_idle();
    heights_ = r32f(ctx_, uint32_t(field.width), uint32_t(field.height));
    maxima_ = r32f(ctx_, uint32_t(pyramid.width), uint32_t(pyramid.height));
    upload(ctx_, heights_, field.height_m);
    upload(ctx_, maxima_, pyramid.texels);
    set_.bind_sampled_image(gpu::kTerrainHeights, heights_);
    set_.bind_sampled_image(gpu::kTerrainMaxima, maxima_);
    rect_ = glm::vec4(field.center_m.x - 0.5f * field.extent_m.x, field.center_m.y + 0.5f * field.extent_m.y,
                      field.extent_m);
    shape_ = glm::vec4(field.min_height_m(), field.max_height_m(), 1.0f, 0.0f);
    grid_ = glm::ivec4(field.width, field.height, pyramid.levels, pyramid.size(1).x);
    key_ = key;
  }
  params.terrain_rect = rect_;
  params.terrain_shape = glm::vec4(shape_.x, shape_.y, 1.0f, scene.terrain.snow_altitude_m);
  params.terrain_albedo = glm::vec4(scene.terrain.albedo, 0.0f);
  params.terrain_grid = grid_;
  return true;
}

void TerrainModule::record(VkCommandBuffer cmd, gpu::PassTimer& timer) {
  if (!kernel_) kernel_ = std::make_unique<gpu::Kernel>(ctx_, set_, "terrain.comp.spv");
  gpu::dispatch(cmd, *kernel_, set_, timer, "terrain", out_.width(), out_.height(), 1, 8, 8, 1);
}

}  // namespace nephele
