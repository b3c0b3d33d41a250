#include "render/modules/weather/weather.h"

#include <cmath>
#include <cstring>
#include <glm/common.hpp>

#include "image/input_images.h"
#include "nephele/error.h"
#include "weather/grib.h"

namespace nephele {

namespace {
// The blended map keeps 16 bits: blends of 8-bit states between 8-bit steps, so that the map
// moves a little every frame instead of jumping by 1/255 now and then. Half floats (steps of
// 1/2048 or finer in [0, 1]): a storage format every Vulkan device has, where 16-bit UNORM is
// an extended one that needs shaderStorageImageExtendedFormats enabled (nephele enables no
// features, and a host's device need not have it).
constexpr VkFormat kBlendedFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr int kRowsPerFrame = int(kWeatherMapSize) / kWeatherBuildFrames;
int layer_of(long long step) {
  return int(((step % 3) + 3) % 3);
}
}  // namespace

WeatherModule::WeatherModule(gpu::Context& ctx, gpu::DescriptorSet& set)
    : ctx_(ctx),
      set_(set),
      build_kernel_(ctx, set, "weather.comp.spv"),
      blend_kernel_(ctx, set, "weather_blend.comp.spv"),
      states_(ctx, kWeatherMapSize, kWeatherMapSize, 3, VK_FORMAT_R8G8B8A8_UNORM),
      map_(ctx, kWeatherMapSize, kWeatherMapSize, 1, kBlendedFormat),
      forecast_(ctx, 1, 1, 1, VK_FORMAT_R8G8B8A8_UNORM) {
  set_.bind_storage_image(gpu::kWeatherStates, states_);
  set_.bind_image(gpu::kWeatherMapOut, gpu::kWeatherMap, map_);
  upload_forecast({{255, 255, 255, 255}}, 1);
  forecast_key_ = "none";
}

// A forecast of another size replaces the texture once the frames in flight that read it have
// completed.
void WeatherModule::upload_forecast(const std::vector<std::array<uint8_t, 4>>& texels,
                                    uint32_t side) {
  if (forecast_.width() != side) {
    ctx_.wait_queue_idle();
    forecast_ = gpu::Texture(ctx_, side, side, 1, VK_FORMAT_R8G8B8A8_UNORM);
  }
  set_.bind_sampled_image(gpu::kForecastCover, forecast_);
  gpu::Buffer staging(ctx_, VkDeviceSize(texels.size() * 4), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  std::memcpy(staging.data(), texels.data(), texels.size() * 4);
  ctx_.submit_and_wait([&](VkCommandBuffer cmd) {
    gpu::full_barrier(cmd);  // after the frames in flight that read it
    forecast_.record_upload(cmd, staging);
  });
}

// The forecast's texels depend on the file, the place, the time and the layers' coverage and
// types (forecast_texels): uploaded again only when one of them changes.
void WeatherModule::prepare_forecast(const Scene& scene, gpu::FrameParams& params) {
  params.forecast = glm::vec4(0.0f);
  if (scene.weather.grib.empty()) {
    if (forecast_key_ != "none") upload_forecast({{255, 255, 255, 255}}, 1);
    forecast_key_ = "none";
    return;
  }
  const std::shared_ptr<const weather::GribCover> cover = weather::grib_cover(scene);
  char key[256];
  std::snprintf(key, sizeof(key), "%p|%.6g|%.6g|%.6g|%.6g|%.6g",
                static_cast<const void*>(cover.get()), scene.clouds.coverage, scene.clouds.type,
                scene.high_clouds.coverage, scene.high_clouds.type, scene.cirrus.coverage);
  if (forecast_key_ != key)
    upload_forecast(weather::forecast_texels(*cover, scene), uint32_t(weather::kForecastMapSize));
  forecast_key_ = key;
  params.forecast = glm::vec4(0.5f / weather::kForecastHalfExtentM,
                              0.5f / float(weather::kForecastMapSize), 0.0f, 0.0f);
}

double WeatherModule::weather_time(const Scene& scene) {
  const float evolution_s = scene.clouds.weather_evolution_s;
  if (evolution_s <= 0.0f || !scene.clouds.weather_map.empty()) return 0.0;
  return double(scene.time_s) / double(evolution_s);
}

// A map of another size replaces the map texture, once the frames in flight that read the old
// one have completed. The texture's v grows northward (cloud_field_inc.glsl reads it at ground
// y / period), so texture row 0 is the southern edge; an image's row 0 is its top, north as
// maps are drawn (scene.h): the rows go up in reverse order. The procedural map is written in
// texture space and needs no flip. The file is read as 8-bit RGBA (read_weather_map), checked
// against its stated limit and this device's before anything is allocated for it.
void WeatherModule::upload_png(const std::string& path) {
  const Rgba8Image png = read_weather_map(path);
  check_device_limit(path, png.width, png.height);
  if (map_.width() != uint32_t(png.width) || map_.height() != uint32_t(png.height) ||
      map_key_.rfind("file:", 0) != 0) {
    ctx_.wait_queue_idle();
    map_ =
        gpu::Texture(ctx_, uint32_t(png.width), uint32_t(png.height), 1, VK_FORMAT_R8G8B8A8_UNORM);
    set_.bind_image(gpu::kWeatherMapOut, gpu::kWeatherMap, map_);
  }
  const size_t row_bytes = size_t(png.width) * 4;
  gpu::Buffer staging(ctx_, VkDeviceSize(row_bytes) * VkDeviceSize(png.height),
                      VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  auto* bytes = static_cast<unsigned char*>(staging.data());
  for (int row = 0; row < png.height; ++row)
    std::memcpy(bytes + size_t(row) * row_bytes,
                png.texels.data() + size_t(png.height - 1 - row) * row_bytes, row_bytes);
  ctx_.submit_and_wait([&](VkCommandBuffer cmd) {
    gpu::full_barrier(cmd);  // after the frames in flight that read the map
    map_.record_upload(cmd, staging);
  });
}

// A device may take smaller images than kMaxWeatherMapSide (Vulkan promises 4096 a side).
void WeatherModule::check_device_limit(const std::string& path, int width, int height) const {
  VkPhysicalDeviceProperties properties;
  vkGetPhysicalDeviceProperties(ctx_.physical_device(), &properties);
  const uint32_t largest = properties.limits.maxImageDimension2D;
  if (uint32_t(width) > largest || uint32_t(height) > largest)
    throw InputError("clouds.weather_map '" + shorten_path_for_message(path) +
                     "': " + std::to_string(width) + " x " + std::to_string(height) +
                     " pixels exceed this device's largest image (" + std::to_string(largest) +
                     " a side); resample it smaller");
}

void WeatherModule::prepare(const Scene& scene, gpu::FrameParams& params) {
  prepare_forecast(scene, params);
  build_steps_ = build_rows_ = 0;
  blend_ = false;
  if (!scene.clouds.weather_map.empty()) {
    const std::string key = "file:" + scene.clouds.weather_map;
    if (map_key_ != key) upload_png(scene.clouds.weather_map);
    map_key_ = key;
    return;
  }
  if (map_key_.rfind("file:", 0) == 0) {  // the map held a file, in another format
    ctx_.wait_queue_idle();
    map_ = gpu::Texture(ctx_, kWeatherMapSize, kWeatherMapSize, 1, kBlendedFormat);
    set_.bind_image(gpu::kWeatherMapOut, gpu::kWeatherMap, map_);
    map_key_.clear();
  }
  if (seed_ != scene.noise_seed) {
    for (auto& s : step_in_layer_) s.reset();
    building_step_ = -1;
    seed_ = scene.noise_seed;
  }
  const double steps = weather_time(scene) * gpu::WEATHER_STEPS;
  const long long k = (long long)std::floor(steps);
  const float f = std::floor(float(steps - double(k)) * kWeatherBlends) / kWeatherBlends;
  const auto have = [&](long long step) { return step_in_layer_[layer_of(step)] == step; };
  // The two states blended must be complete now: computed whole in this frame when they are
  // not (the first frame, a jump in time). Then the next one, a band a frame.
  const bool blended_states_built = !have(k) || !have(k + 1);
  if (blended_states_built) {
    const long long first = have(k) ? k + 1 : k;
    build_first_step_ = int(first);
    build_steps_ = int(k + 2 - first);
    build_first_row_ = 0;
    build_rows_ = int(kWeatherMapSize);
    for (long long s = first; s <= k + 1; ++s) step_in_layer_[layer_of(s)] = s;
    building_step_ = -1;  // its layer may be one of these
  } else if (scene.clouds.weather_evolution_s > 0.0f && !have(k + 2)) {
    if (building_step_ != k + 2) {
      building_step_ = k + 2;
      next_row_ = 0;
      step_in_layer_[layer_of(k + 2)].reset();
    }
    build_first_step_ = int(k + 2);
    build_steps_ = 1;
    build_first_row_ = next_row_;
    build_rows_ = std::min(kRowsPerFrame, int(kWeatherMapSize) - next_row_);
    next_row_ += build_rows_;
    if (next_row_ >= int(kWeatherMapSize)) {
      step_in_layer_[layer_of(k + 2)] = k + 2;
      building_step_ = -1;
    }
  }
  params.weather_build = glm::ivec4(build_first_step_, build_steps_, build_first_row_, build_rows_);
  params.weather_blend = glm::vec4(f, float(layer_of(k)), float(layer_of(k + 1)), 0.0f);
  // The map is blended again when its inputs change.
  const std::string key = "blend:" + std::to_string(scene.noise_seed) + ":" + std::to_string(k) +
                          ":" + std::to_string(f);
  blend_ = map_key_ != key || blended_states_built;
  map_key_ = key;
}

void WeatherModule::record(VkCommandBuffer cmd, gpu::PassTimer& timer) {
  if (build_steps_ > 0)
    gpu::dispatch(cmd, build_kernel_, timer, "weather", kWeatherMapSize, uint32_t(build_rows_),
                  uint32_t(build_steps_), 8, 8, 1);
  if (blend_)
    gpu::dispatch(cmd, blend_kernel_, timer, "weather_blend", kWeatherMapSize, kWeatherMapSize, 1,
                  8, 8, 1);
}

void WeatherModule::add_passes(FrameGraph& graph, const FrameSetup& frame) {
  graph.import("weather_map", true);  // advanced over several frames
  graph.add_pass("weather", {}, {"weather_map"},
                 [timer = frame.timer, this](VkCommandBuffer cmd) { record(cmd, timer()); });
}

void WeatherModule::prepare(const FramePrepare& frame, FramePlan&) {
  prepare(frame.scene, frame.params);
}

}  // namespace nephele
