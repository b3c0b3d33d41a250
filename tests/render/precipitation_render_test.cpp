// The precipitation module (render/modules/precipitation) on the device: a medium in front of
// every layer of compose and of the stars. Its extinction law, profile and shafts are tested on
// the CPU in tests/unit/precipitation_test.cpp; here, what the image shows: the stars through
// rain, virga and snow dimmed as the law says, fair-weather cumulus that do not rain, and a
// storm's shafts under its base alone.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "nephele/image_compare.h"
#include "nephele/renderer.h"
#include "nephele/scene_io.h"
#include "render/frame_params.h"
#include "render/glsl.h"
#include "render/modules/precipitation/precipitation.h"
#include "render_fixture.h"

using nephele::Scene;

namespace {

class PrecipitationTest : public RenderTest {};

// The stars' light in each pixel: the image less the same image without stars.
std::vector<double> star_light(const Scene& s) {
  Scene without = s;
  without.conditions.good.keys[0].set.star_visibility = 0.0f;
  const nephele::Image a = render(s).color, b = render(without).color;
  std::vector<double> light(a.pixels.size());
  for (size_t i = 0; i < light.size(); ++i)
    light[i] = nephele::luminance(a.pixels[i]) - nephele::luminance(b.pixels[i]);
  return light;
}

// Each pixel's ray's sine of elevation (flat: the rain lies within a few km).
std::vector<double> pixel_sines(const Scene& s) {
  const nephele::CameraBasis basis = nephele::camera_basis(s.camera);
  const float tan_half = std::tan(glm::radians(s.camera.fov_deg) * 0.5f);
  const float aspect = float(s.output.width) / float(s.output.height);
  std::vector<double> sines;
  for (int y = 0; y < s.output.height; ++y)
    for (int x = 0; x < s.output.width; ++x)
      sines.push_back(nephele::glsl::camera_ray(basis.forward, basis.right, basis.up, tan_half,
                                                aspect, float(x), float(y), float(s.output.width),
                                                float(s.output.height))
                          .z);
  return sines;
}

// The stars seen through an even curtain of precipitation (no clouds to fall from: shafts
// off) keep exp(-sigma_t column / sin(elevation)) of their light, the column the profile's
// integral from the eye to the base: as much rain as the law gives for the rate, virga only
// above its bottom, snow far more than rain.
TEST_F(PrecipitationTest, TheStarsDimAsTheLawSays) {
  Scene clear = starry_night(96, 64);
  clear.camera.fov_deg = 40.0f;
  const std::vector<double> through_clear = star_light(clear);
  const std::vector<double> sines = pixel_sines(clear);
  double total = 0.0;
  for (double l : through_clear) total += std::max(l, 0.0);
  ASSERT_GT(total, 0.0) << "no stars in view";
  const float base_m = clear.clouds.bottom_altitude_m;
  struct Case {
    const char* kind;
    float rate_mm_per_h, bottom_m;
  };
  for (const Case& c :
       {Case{"rain", 1.0f, 0.0f}, Case{"rain", 1.0f, 800.0f}, Case{"snow", 0.2f, 0.0f}}) {
    Scene s = clear;
    s.precipitation.kind = c.kind;
    s.precipitation.rate_mm_per_h = c.rate_mm_per_h;
    s.precipitation.bottom_m = c.bottom_m;
    s.precipitation.shafts = false;
    const float sigma = nephele::precipitation_sigma_t_per_m(s.precipitation);
    const double column_m =
        nephele::glsl::precipitation_column_m(base_m, c.bottom_m, base_m) -
        nephele::glsl::precipitation_column_m(s.camera.position_m.z, c.bottom_m, base_m);
    const std::vector<double> through = star_light(s);
    double expected = 0.0, measured = 0.0;
    for (size_t i = 0; i < through.size(); ++i) {
      if (through_clear[i] <= 0.0) continue;
      expected += through_clear[i] * std::exp(-sigma * column_m / sines[i]);
      measured += through[i];
    }
    EXPECT_NEAR(measured / total, expected / total, 0.02 * expected / total)
        << c.kind << " at " << c.rate_mm_per_h << " mm/h down to " << c.bottom_m << " m";
    EXPECT_LT(measured / total, 0.9) << c.kind << ": the stars must dim";
  }
}

// A scattered layer of fair-weather cumulus does not rain: with a rate set and shafts on, the
// image is the dry one.
TEST_F(PrecipitationTest, FairWeatherCumulusDoNotRain) {
  Scene dry = nephele::load_preset("scattered");
  dry.output.width = 48;
  dry.output.height = 32;
  Scene wet = dry;
  wet.precipitation.rate_mm_per_h = 10.0f;
  const nephele::Image a = render(dry).color, b = render(wet).color;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    ASSERT_NEAR(nephele::luminance(b.pixels[i]), nephele::luminance(a.pixels[i]),
                1e-5 * nephele::luminance(a.pixels[i]) + 1e-9)
        << i;
}

// A storm seen from 70 km: its shafts hang under the base near the horizon and change nothing
// above it; with the same rate as an even curtain the whole view is veiled.
TEST_F(PrecipitationTest, AStormsShaftsHangUnderItsBase) {
  Scene dry = nephele::load_preset("cumulonimbus-storm");
  dry.output.width = 96;
  dry.output.height = 64;
  Scene wet = dry;
  wet.precipitation.rate_mm_per_h = 20.0f;
  const nephele::Image a = render(dry).color, b = render(wet).color;
  // The horizon's row: the view's pitch is atan(0.22) up, the vertical field 65 deg.
  const double pitch = std::atan(0.22), tan_half = std::tan(glm::radians(65.0) / 2.0);
  const int horizon_row = int(std::lround(32.0 + 32.0 * std::tan(pitch) / tan_half));
  int changed_above = 0, changed_near_horizon = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const double la = nephele::luminance(a.at(x, y)), lb = nephele::luminance(b.at(x, y));
      const bool changed = std::abs(lb - la) > 0.05 * la;
      if (y < horizon_row - 6) changed_above += changed;
      if (std::abs(y - horizon_row) <= 2) changed_near_horizon += changed;
    }
  EXPECT_EQ(changed_above, 0) << "rain above the storm's base (horizon row " << horizon_row << ")";
  EXPECT_GT(changed_near_horizon, 10) << "no shafts under the storm";
  EXPECT_LT(changed_near_horizon, 5 * 96) << "the shafts fill the whole horizon";
}

}  // namespace
