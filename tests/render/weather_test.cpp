// Weather that evolves (clouds.weather_evolution_s): deterministic in the seed and the time,
// smooth from second to second, a different sky ten minutes on. A weather map from a PNG lies
// on the ground as a map is drawn: row 0 north, columns west to east (scene.h).
#include "render/modules/weather/weather.h"

#include <gtest/gtest.h>
#include <stb/stb_image_write.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "nephele/image_compare.h"
#include "nephele/renderer.h"
#include "nephele/scene_io.h"
#include "render/frame_renderer_impl.h"
#include "render/glsl.h"
#include "render_fixture.h"

using nephele::Frame;
using nephele::luminance_error;
using nephele::Scene;

namespace {

// Scattered cumulus from the ground, no wind (nor shear, nor detail drift): only the weather's
// evolution moves the clouds.
Scene still_air(float time_s) {
  Scene s = nephele::load_preset("scattered");
  s.output.width = 120;
  s.output.height = 80;
  s.clouds.wind_mps = {0.0f, 0.0f};
  s.clouds.wind_shear_mps = {0.0f, 0.0f};
  s.clouds.detail_drift_mps = {0.0f, 0.0f, 0.0f};
  s.time_s = time_s;
  return s;
}

// Mean absolute difference of cloud opacity (1 - transmittance) over the image.
double opacity_difference(const Frame& a, const Frame& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.clouds.pixels.size(); ++i)
    sum += std::abs(double(a.clouds.pixels[i].a) - double(b.clouds.pixels[i].a));
  return sum / double(a.clouds.pixels.size());
}

// Mean cloud opacity (1 - transmittance) over the pixels [x0, x1) x [y0, y1).
double mean_opacity(const Frame& f, int x0, int x1, int y0, int y1) {
  double sum = 0.0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) sum += 1.0 - double(f.clouds.at(x, y).a);
  return sum / double((x1 - x0) * (y1 - y0));
}

class WeatherTest : public RenderTest {};

}  // namespace

TEST_F(WeatherTest, TheSameSeedAndTimeGiveTheSameImage) {
  const Frame a = render(still_air(1800.0f));
  render(still_air(0.0f));  // another weather map in between
  const Frame b = render(still_air(1800.0f));
  EXPECT_EQ(a.color.pixels, b.color.pixels);
}

TEST_F(WeatherTest, OneSecondChangesLittleTenMinutesChangeTheSky) {
  // 1799.5 s and 1800.5 s: the map blended between states 10 s apart (WEATHER_STEPS).
  const Frame start = render(still_air(1799.5f));
  const Frame second = render(still_air(1800.5f));
  const Frame later = render(still_air(2399.5f));
  const double cloud_change_1s = opacity_difference(start, second);
  const double cloud_change_10min = opacity_difference(start, later);
  std::printf("cloud opacity change: 1 s %.4f, 10 min %.4f; luminance 1 s %.4f, 10 min %.4f\n",
              cloud_change_1s, cloud_change_10min, luminance_error(second.color, start.color),
              luminance_error(later.color, start.color));
  EXPECT_GT(cloud_change_1s, 0.0) << "the map should have moved on a step";
  EXPECT_LT(cloud_change_1s, 0.005);
  EXPECT_LT(luminance_error(second.color, start.color), 0.01);
  EXPECT_GT(cloud_change_10min, 0.05);
  EXPECT_GT(cloud_change_10min, 20.0 * cloud_change_1s);
  // A static map (evolution 0) keeps the sky as it is, in still air.
  Scene frozen = still_air(1800.0f), frozen_later = still_air(2400.0f);
  frozen.clouds.weather_evolution_s = frozen_later.clouds.weather_evolution_s = 0.0f;
  EXPECT_EQ(render(frozen).color.pixels, render(frozen_later).color.pixels);
}

// The procedural map, read back texel by texel, against weather_state evaluated on the CPU at
// each texel's centre: the device must compute the function the C++ build does (an H100 and
// an H200 drew other clouds than lavapipe from the same scene). Half floats hold the map: a
// texel may differ by its 8-bit state's rounding (1/255) and the half's (1/2048).
TEST(WeatherMapTest, EveryTexelOfTheProceduralMapIsItsCpuFunction) {
  nephele::RendererOptions options;
  options.validation = true;
  nephele::FrameRenderer::Impl impl(options);  // every binding bound, as in a frame
  impl.state.resize(16, 16);
  nephele::gpu::Context& ctx = impl.ctx;
  nephele::GpuState& state = impl.state;
  nephele::WeatherModule& weather = impl.weather;
  Scene scene = nephele::load_preset("default");
  scene.clouds.weather_evolution_s = 0.0f;
  nephele::gpu::FrameParams params{};
  params.size = glm::ivec4(16, 16, 0, int(scene.noise_seed));
  weather.prepare(scene, params);
  state.run_once(params, [&](VkCommandBuffer cmd) { weather.record(cmd, *state.timer); });
  const nephele::Image map = nephele::download(ctx, weather.map(), true);
  const int n = int(nephele::kWeatherMapSize);
  ASSERT_EQ(map.width, n);
  int wrong = 0;
  double worst = 0.0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const glm::vec4 cpu = nephele::glsl::weather_state(
          glm::vec3((float(x) + 0.5f) / float(n), (float(y) + 0.5f) / float(n), 0.0f),
          scene.noise_seed);
      const glm::vec4 gpu = map.at(x, y);
      for (int c = 0; c < 4; ++c) {
        const double d = std::abs(double(gpu[c]) - double(cpu[c]));
        if (d > 1.0 / 255.0 + 1e-3 && wrong++ < 8)
          std::printf("texel (%d, %d) channel %d: device %.4f, CPU %.4f\n", x, y, c, gpu[c],
                      cpu[c]);
        worst = std::max(worst, d);
      }
    }
  std::printf("procedural map: %d of %d values off by more than 1/255, the worst by %.4f\n",
              wrong, n * n * 4, worst);
  if (wrong > 0) {  // what the device computed instead, for the one who reads the log
    std::filesystem::create_directories(NEPHELE_TEST_OUTPUT_DIR);
    nephele::write_image(map, std::string(NEPHELE_TEST_OUTPUT_DIR) + "/weather_device.exr");
  }
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(ctx.validation_messages(), 0);
}

// A 64x64 map with cloud only in its north-east quadrant (image rows 0-31, columns 32-63),
// seen from 10 km straight down: looking down, the image's top is north and its right east
// (camera_basis), and the map's centre lies below the camera (no wind, time 0), so the cloud
// must fill the frame's top-right quadrant and nothing else. Before the fix (the image's row
// 0 uploaded as the texture's southern edge) it filled the bottom-right one.
TEST_F(WeatherTest, PngWeatherMapLiesNorthUpAndWestToEast) {
  const std::string path = std::string(NEPHELE_TEST_OUTPUT_DIR) + "/weather_north_east.png";
  std::filesystem::create_directories(NEPHELE_TEST_OUTPUT_DIR);
  constexpr int kMapSize = 64;
  std::vector<unsigned char> rgba(size_t(kMapSize) * kMapSize * 4);
  for (int row = 0; row < kMapSize; ++row)
    for (int column = 0; column < kMapSize; ++column) {
      unsigned char* p = &rgba[4 * (size_t(row) * kMapSize + column)];
      const bool north_east = row < kMapSize / 2 && column >= kMapSize / 2;
      p[0] = north_east ? 255 : 0;  // R: coverage
      p[1] = 0;                     // G: no storm cells
      p[2] = 128;                   // B: the layer's type
      p[3] = 255;                   // A: twice the layer's density
    }
  ASSERT_TRUE(stbi_write_png(path.c_str(), kMapSize, kMapSize, 4, rgba.data(), kMapSize * 4));

  Scene s = nephele::load_preset("default");
  s.clouds.weather_map = path;
  s.clouds.coverage = 0.5f;  // the local coverage is R
  s.clouds.weather_period_m = 8000.0f;
  s.clouds.wind_mps = {0.0f, 0.0f};  // the map's centre stays at the origin, at every height
  s.clouds.wind_shear_mps = {0.0f, 0.0f};
  s.camera.position_m = {0.0f, 0.0f, 10000.0f};
  s.camera.view_dir = {0.0f, 0.0f, -1.0f};
  // 40 degrees: the layer's bottom, 8.5 km below, is seen 3.1 km around the centre, inside
  // the tile's half-width of 4 km.
  s.camera.fov_deg = 40.0f;
  s.output.width = s.output.height = 64;
  const Frame f = render(s);

  // The quadrants, leaving out 4 pixels either side of the centre lines (the map's edges are
  // filtered over a texel, 125 m).
  const double north_east = mean_opacity(f, 36, 64, 0, 28);
  const double north_west = mean_opacity(f, 0, 28, 0, 28);
  const double south_east = mean_opacity(f, 36, 64, 36, 64);
  const double south_west = mean_opacity(f, 0, 28, 36, 64);
  std::printf("cloud opacity: north-east %.3f, north-west %.3f, south-east %.3f, south-west %.3f\n",
              north_east, north_west, south_east, south_west);
  EXPECT_GT(north_east, 0.3);
  EXPECT_LT(north_west, 0.01);
  EXPECT_LT(south_east, 0.01);
  EXPECT_LT(south_west, 0.01);
}
