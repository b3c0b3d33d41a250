#include "render/modules/host_lighting/host_lighting.h"

#include <cmath>
#include <cstring>
#include <string>

#include "nephele/error.h"
#include "nephele/sky.h"
#include "render/glsl.h"

namespace nephele {
namespace {

// Meteorological visibility: the distance where a black object's contrast against the horizon
// falls to 2% (Koschmieder): -ln 0.02 / sigma_t.
// sin 3 degrees: cloud_shadow_map.comp's SHADOW_MAP_MIN_LIGHT_Z.
constexpr float kShadowMapMinLightZ = 0.0523f;

gpu::Texture shadow_texture(gpu::Context& ctx, uint32_t size) {
  return gpu::Texture(ctx, size, size, 1, VK_FORMAT_R32_SFLOAT,
                      VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
}

gpu::Texture environment_texture(gpu::Context& ctx, uint32_t face) {
  return gpu::Texture(ctx, 6 * face, face, 1, VK_FORMAT_R16G16B16A16_SFLOAT,
                      VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
}

}  // namespace

glm::vec3 HostLighting::sky_irradiance_lux(const glm::vec3& normal) const {
  const glsl::Sh9 basis = glsl::sh9_basis(glm::normalize(normal));
  glm::vec3 e(0.0f);
  for (int k = 0; k < 9; ++k) e += glsl::sh9_cosine_lobe(k) * basis.y[k] * sky_radiance_sh[k];
  return glm::max(e, glm::vec3(0.0f));
}

HostLighting host_lighting(const Scene& scene, const SkyLights& lights, const glm::vec4* device) {
  const KeyLight& key = lights.key;
  const KeyLight& second = lights.second;
  const float key_clouds = device[0].x, second_clouds = device[0].y;
  HostLighting out;
  // The sun: the key light by day, at night the second while it lights the sky.
  out.sun_direction = scene_sun_direction(scene, lights.ephemeris);
  out.sun_cloud_transmittance = !key.moon                                   ? key_clouds
                                : second.illuminance > 0.0f && !second.moon ? second_clouds
                                                                            : 1.0f;
  out.sun_illuminance_lux = scene.sun.illuminance_lux * out.sun_cloud_transmittance *
                            camera_air_transmittance(scene, out.sun_direction);
  // The moon, with a date and place.
  if (lights.ephemeris) {
    const KeyLight* moon = key.moon                                   ? &key
                           : second.moon && second.illuminance > 0.0f ? &second
                                                                      : nullptr;
    out.moon_direction = lights.ephemeris->moon.direction;
    out.moon_cloud_transmittance = moon == &key ? key_clouds : moon ? second_clouds : 1.0f;
    const float toa_lux =
        moon ? moon->illuminance
             : scene.sun.illuminance_lux *
                   float(moon_illuminance_ratio(lights.ephemeris->moon_illuminated_fraction,
                                                lights.ephemeris->moon.distance_km));
    out.moon_illuminance_lux = toa_lux * out.moon_cloud_transmittance *
                               camera_air_transmittance(scene, out.moon_direction);
  }
  const glm::vec3 key_lux(key.illuminance);
  out.sky_cloud_share = device[0].w;
  for (int k = 0; k < 9; ++k)
    out.sky_radiance_sh[k] = glm::vec3(device[1 + k]) * key_lux * out.sky_cloud_share;
  out.cloud_sigma_t_per_m = device[0].z;
  out.inside_cloud = out.cloud_sigma_t_per_m > 0.0f;
  const float sigma_t = camera_air_sigma_t(scene).g + out.cloud_sigma_t_per_m;
  out.visibility_m = sigma_t > 0.0f ? glsl::KOSCHMIEDER / sigma_t : 1.0e9f;
  return out;
}

glm::mat4 shadow_map_matrix(const glm::vec3& light, float base_m, const glm::vec2& west_north_m,
                            float extent_m) {
  const float sx = light.x / light.z, sy = light.y / light.z;
  glm::mat4 m(0.0f);  // columns: m[c][r]
  m[0] = glm::vec4(1.0f / extent_m, 0.0f, 0.0f, 0.0f);
  m[1] = glm::vec4(0.0f, -1.0f / extent_m, 0.0f, 0.0f);
  m[2] = glm::vec4(-sx / extent_m, sy / extent_m, 1.0f, 0.0f);
  m[3] = glm::vec4((sx * base_m - west_north_m.x) / extent_m,
                   (west_north_m.y - sy * base_m) / extent_m, -base_m, 1.0f);
  return m;
}

HostLightingModule::HostLightingModule(gpu::Context& ctx, gpu::DescriptorSet& set)
    : ctx_(ctx),
      set_(set),
      shadow_map_(shadow_texture(ctx, 1)),
      environment_(environment_texture(ctx, 1)) {
  for (gpu::Buffer& b : buffers_)
    b = gpu::Buffer(ctx, kHostLightingVec4s * sizeof(glm::vec4),
                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  set_.bind_buffer(gpu::kHostLighting, buffers_[0], VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  set_.bind_storage_image(gpu::kCloudShadowMapOut, shadow_map_);
  set_.bind_storage_image(gpu::kEnvironmentOut, environment_);
  ctx_.submit_and_wait([&](VkCommandBuffer cmd) {
    shadow_map_.record_clear(cmd);
    environment_.record_clear(cmd);
  });
}

std::string host_lighting_problem(const HostLightingOptions& options) {
  if (!options.enabled) return {};
  if (!(options.shadow_map_extent_m >= 100.0f && options.shadow_map_extent_m <= 1.0e6f))
    return "FrameOptions::lighting.shadow_map_extent_m " +
           number_for_message(options.shadow_map_extent_m) + " is outside [100, 1e6] m";
  if (options.shadow_map_size < 8 || options.shadow_map_size > 4096)
    return "FrameOptions::lighting.shadow_map_size " + std::to_string(options.shadow_map_size) +
           " is outside [8, 4096] texels";
  if (options.environment_size < 4 || options.environment_size > 256)
    return "FrameOptions::lighting.environment_size " + std::to_string(options.environment_size) +
           " is outside [4, 256] texels";
  return {};
}

bool HostLightingModule::prepare(const HostLightingOptions& options, const Scene& scene,
                                 const SkyLights& lights, int slot, gpu::FrameParams& params) {
  pending_[slot].reset();
  if (!options.enabled) return false;
  if (options.environment_size != environment_size_) {
    ctx_.wait_queue_idle();  // a frame in flight may still write the old one
    environment_ = environment_texture(ctx_, options.environment_size);
    set_.bind_storage_image(gpu::kEnvironmentOut, environment_);
    environment_size_ = options.environment_size;
  }
  if (options.shadow_map_size != map_size_) {
    ctx_.wait_queue_idle();  // a frame in flight may still write the old one
    shadow_map_ = shadow_texture(ctx_, options.shadow_map_size);
    set_.bind_storage_image(gpu::kCloudShadowMapOut, shadow_map_);
    map_size_ = options.shadow_map_size;
  }
  set_.bind_buffer(gpu::kHostLighting, buffers_[slot], VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  // The square about where the light through the ground below the camera crosses the clouds'
  // bottom, on a grid of whole texels (the map does not crawl as the camera moves).
  // The key light, kept 3 degrees above the horizon (as cloud_shadow_map.comp does): a light
  // on the horizon would carry points to infinity.
  glm::vec3 light = glm::vec3(params.sun_dir);
  light.z = std::max(light.z, kShadowMapMinLightZ);
  light = glm::normalize(light);
  const float base_m = params.radii_m.z - params.radii_m.x;
  const float extent = options.shadow_map_extent_m;
  const float texel = extent / float(options.shadow_map_size);
  const glm::vec2 foot = glm::vec2(scene.camera.position_m) + glm::vec2(light) / light.z * base_m;
  const glm::vec2 center = glm::round(foot / texel) * texel;
  const glm::vec2 west_north = center + glm::vec2(-0.5f, 0.5f) * extent;
  params.host_shadow_map = glm::vec4(west_north, extent, base_m);
  params.host_shadow_grid =
      glm::ivec4(int(options.shadow_map_size), 1, int(options.environment_size), 0);
  world_to_map_ = shadow_map_matrix(light, base_m, west_north, extent);
  pending_[slot] = Pending{scene, lights};
  return true;
}

void HostLightingModule::record(VkCommandBuffer cmd, gpu::PassTimer& timer) {
  // The host may have read the map and the environment of the frame before in this queue (its
  // shaders, copies): those reads end before they are written again.
  VkPipelineStageFlags readers =
      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
  if (ctx_.has_graphics())
    readers |= VK_PIPELINE_STAGE_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
  vkCmdPipelineBarrier(cmd, readers, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 0,
                       nullptr, 0, nullptr);
  if (!lighting_kernel_) {
    lighting_kernel_ = std::make_unique<gpu::Kernel>(ctx_, set_, "host_lighting.comp.spv");
    map_kernel_ = std::make_unique<gpu::Kernel>(ctx_, set_, "cloud_shadow_map.comp.spv");
    environment_kernel_ = std::make_unique<gpu::Kernel>(ctx_, set_, "environment.comp.spv");
  }
  gpu::dispatch(cmd, *lighting_kernel_, timer, "host_lighting", 64, 1, 1, 64, 1, 1);
  gpu::dispatch(cmd, *map_kernel_, timer, "shadow_map", map_size_, map_size_, 1, 8, 8, 1);
  gpu::dispatch(cmd, *environment_kernel_, timer, "environment", 6 * environment_size_,
                environment_size_, 1, 8, 8, 1);
}

std::optional<HostLighting> HostLightingModule::collect(int slot) {
  if (!pending_[slot]) return std::nullopt;
  glm::vec4 device[kHostLightingVec4s];
  std::memcpy(device, buffers_[slot].data(), sizeof device);
  const HostLighting out = host_lighting(pending_[slot]->scene, pending_[slot]->lights, device);
  pending_[slot].reset();
  return out;
}

void HostLightingModule::add_passes(FrameGraph& graph, const FrameSetup& frame) {
  graph.output("host_lighting");
  if (frame.params.host_shadow_grid.y > 0)
    graph.add_pass(
        "host_lighting",
        {"weather_map", "noise", "voxel_clouds", "light_volume", "ground_light", "sky_view"},
        {"host_lighting"},
        [timer = frame.timer, this](VkCommandBuffer cmd) { record(cmd, timer()); });
}

void HostLightingModule::prepare(const FramePrepare& frame, FramePlan& plan) {
  plan.host_lighting =
      frame.options && frame.lights &&
      prepare(frame.options->lighting, frame.scene, *frame.lights, frame.slot, frame.params);
}

}  // namespace nephele
