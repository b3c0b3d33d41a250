// Weather that evolves (clouds.weather_evolution_s): deterministic in the seed and the time,
// smooth from second to second, a different sky ten minutes on.
#include <gtest/gtest.h>

#include "nephele/image_compare.h"
#include "nephele/renderer.h"
#include "nephele/scene_io.h"
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

class WeatherTest : public RenderTest {};

}  // namespace

TEST_F(WeatherTest, TheSameSeedAndTimeGiveTheSameImage) {
  const Frame a = render(still_air(1800.0f));
  render(still_air(0.0f));  // another weather map in between
  const Frame b = render(still_air(1800.0f));
  EXPECT_EQ(a.color.pixels, b.color.pixels);
}

TEST_F(WeatherTest, OneSecondChangesLittleTenMinutesChangeTheSky) {
  // 1799.5 s and 1800.5 s straddle a step of the map's time (weather_time: 2 s at an hour).
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
