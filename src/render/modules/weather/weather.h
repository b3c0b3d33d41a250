// The weather module: the weather map the clouds read (binding kWeatherMap). A file (PNG or
// EXR, read as image/input_images.h says) is uploaded once. The procedural map evolves with
// time without a hitch: states of the weather at steps of clouds.weather_evolution_s /
// gpu::WEATHER_STEPS (360, shaders/common/params_inc.glsl) are computed ahead into one of
// three layers (weather.comp, the next one a band of rows a frame over kWeatherBuildFrames),
// and the map is blended between the two around the scene's time (weather_blend.comp), so it
// changes smoothly and never all at once. A GRIB forecast's cover around the observer
// (weather.grib: weather/grib.h) is uploaded once too, into the texture forecast_cover, which
// scales each layer's coverage where it is, fixed to the ground.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "gpu/kernel.h"
#include "nephele/scene.h"
#include "render/gpu_params.h"
#include "render/render_module.h"

namespace nephele {

constexpr uint32_t kWeatherMapSize = 512;  // procedural weather map 512^2
// Frames over which the next state of the evolving weather is computed (the states are 10 s
// apart at an hour's evolution: 200 frames at 20 frames/s).
constexpr int kWeatherBuildFrames = 64;
// The map is blended again when the share of the later state has moved by 1/kWeatherBlends
// (0.16 s of weather at an hour's evolution).
constexpr int kWeatherBlends = 64;

class WeatherModule : public RenderModule {
 public:
  WeatherModule(gpu::Context& ctx, gpu::DescriptorSet& set);
  void add_passes(FrameGraph& graph, const FrameSetup& frame) override;

  // Decides this frame's work, sets params.weather_build and the bindings; uploads a PNG map
  // (a host wait) when the file changes.
  void prepare(const Scene& scene, gpu::FrameParams& params);
  // The contract's (render_module.h): the above with the frame's values.
  void prepare(const FramePrepare& frame, FramePlan& plan) override;
  void record(VkCommandBuffer cmd, gpu::PassTimer& timer);
  // The weather's time in units of clouds.weather_evolution_s (0 for a static map).
  static double weather_time(const Scene& scene);
  // The map the clouds read (for tests: the procedural map against its CPU function).
  const gpu::Texture& map() const { return map_; }

 private:
  void upload_png(const std::string& path);
  void prepare_forecast(const Scene& scene, gpu::FrameParams& params);
  void upload_forecast(const std::vector<std::array<uint8_t, 4>>& texels, uint32_t side);
  void check_device_limit(const std::string& path, int width, int height) const;

  gpu::Context& ctx_;
  gpu::DescriptorSet& set_;
  gpu::Kernel build_kernel_, blend_kernel_;
  // Three states: steps k, k + 1 (blended) and k + 2 (being computed), at layer step mod 3.
  gpu::Texture states_;
  gpu::Texture map_;                           // the blended (or uploaded) map
  gpu::Texture forecast_;                      // a forecast's cover, or 1 x 1 white
  std::string forecast_key_;                   // what it holds
  std::optional<long long> step_in_layer_[3];  // which step each layer holds, when complete
  std::optional<uint32_t> seed_;               // the noise seed of the states
  std::string map_key_;                        // what the map holds: a file, or a blend
  long long building_step_ = -1;               // the state being computed in bands
  int next_row_ = 0;
  // This frame's work.
  int build_first_step_ = 0, build_steps_ = 0, build_first_row_ = 0, build_rows_ = 0;
  bool blend_ = false;
};

}  // namespace nephele
