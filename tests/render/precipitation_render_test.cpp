// The precipitation module (render/modules/precipitation) on the device: a medium in front of
// every layer of compose and of the stars. Its extinction law, profile and shafts are tested on
// the CPU in tests/unit/precipitation_test.cpp; here, what the image shows: the stars through
// rain, virga and snow dimmed as the law says, fair-weather cumulus that do not rain, and a
// storm's shafts under its base alone; the particles near the camera, streaks that lean with
// the wind, flakes, falling with the time and the same on a re-render.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
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
  // The medium's law: the particles drawn one by one near the camera (tested below) would hide
  // a star here and there.
  clear.precipitation.particles = false;
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

// The particles near the camera: the image with them less the image without (luminance), in
// a rain of `rate_mm_per_h` under the rain preset's deck, looking down at the dark ground
// (pitch atan 0.25) through a 40-degree lens, at `time_s`.
struct NearView {
  Scene scene;
  std::vector<double> on, off;
  int width = 0, height = 0;
  double at(const std::vector<double>& v, int x, int y) const { return v[size_t(y * width + x)]; }
  double diff(int x, int y) const { return at(on, x, y) - at(off, x, y); }
};

Scene near_rain(const char* kind, float rate_mm_per_h, glm::vec2 wind_mps, float time_s) {
  Scene s = nephele::load_preset("rain");
  s.output.width = 160;
  s.output.height = 120;
  s.camera.view_dir = {0.0f, 1.0f, -0.25f};
  s.camera.fov_deg = 40.0f;
  s.precipitation.kind = kind;
  s.precipitation.rate_mm_per_h = rate_mm_per_h;
  s.clouds.wind_mps = wind_mps;
  s.time_s = time_s;
  return s;
}

std::vector<double> luminances(const nephele::Image& image) {
  std::vector<double> l;
  for (const glm::vec4& p : image.pixels) l.push_back(nephele::luminance(p));
  return l;
}

NearView near_view(const Scene& s) {
  Scene off = s;
  off.precipitation.particles = false;
  return {s, luminances(render(s).color), luminances(render(off).color), s.output.width,
          s.output.height};
}

// The streaks' orientation in the image, from the structure tensor of the particles' light:
// the lean from the vertical (deg, positive: down to the right) and the anisotropy (the
// tensor's eigenvalues' ratio: 1 for round specks, large for long streaks).
struct Streaks {
  double lean_deg, anisotropy;
};
Streaks streaks(const NearView& v) {
  double jxx = 0.0, jyy = 0.0, jxy = 0.0;
  for (int y = 1; y + 1 < v.height; ++y)
    for (int x = 1; x + 1 < v.width; ++x) {
      const double gx = 0.5 * (v.diff(x + 1, y) - v.diff(x - 1, y));
      const double gy = 0.5 * (v.diff(x, y + 1) - v.diff(x, y - 1));
      jxx += gx * gx;
      jyy += gy * gy;
      jxy += gx * gy;
    }
  // The gradients' direction (image x right, y down); the streaks run across it.
  const double theta = 0.5 * std::atan2(2.0 * jxy, jxx - jyy);
  double sx = -std::sin(theta), sy = std::cos(theta);
  if (sy < 0.0) sx = -sx, sy = -sy;
  const double mean = 0.5 * (jxx + jyy);
  const double spread = std::sqrt(0.25 * (jxx - jyy) * (jxx - jyy) + jxy * jxy);
  return {glm::degrees(std::atan2(sx, sy)), (mean + spread) / std::max(mean - spread, 1e-30)};
}

// The particles' light is there, brighter than the dark ground, and the drops streak along
// their fall: upright in still air; in a 12 m/s wind at the base (5.6 m/s at the camera's
// 2 m by the 1/7 law) leaning by atan(5.6 / (5.9 cos 14 deg)) = 45 deg, the drops of 20 mm/h
// falling at 5.9 m/s; with the shutter closed to nothing, specks.
TEST_F(PrecipitationTest, RainStreaksFallWithTheWind) {
  const NearView still = near_view(near_rain("rain", 20.0f, {0.0f, 0.0f}, 3.0f));
  double light = 0.0;
  for (int y = 0; y < still.height; ++y)
    for (int x = 0; x < still.width; ++x) light += std::max(still.diff(x, y), 0.0);
  double ground = 0.0;
  for (double l : still.off) ground += l;
  EXPECT_GT(light, 0.01 * ground) << "no particles in view";
  const Streaks upright = streaks(still);
  EXPECT_NEAR(upright.lean_deg, 0.0, 5.0);
  EXPECT_GT(upright.anisotropy, 2.5);

  const Streaks windy = streaks(near_view(near_rain("rain", 20.0f, {12.0f, 0.0f}, 3.0f)));
  const double wind_mps =
      12.0 * std::pow(2.0 / double(still.scene.clouds.bottom_altitude_m), 1.0 / 7.0);
  const double fall_mps = 9.65 - 10.3 * std::exp(-0.6 * 3.67 / (4.1 * std::pow(20.0, -0.21)));
  const double expected_deg =
      glm::degrees(std::atan(wind_mps / (fall_mps * std::cos(std::atan(0.25)))));
  EXPECT_NEAR(windy.lean_deg, expected_deg, 6.0);
  std::printf("upright %.1f deg x%.2f, windy %.1f deg (expected %.1f)\n", upright.lean_deg,
              upright.anisotropy, windy.lean_deg, expected_deg);

  Scene frozen = near_rain("rain", 20.0f, {0.0f, 0.0f}, 3.0f);
  frozen.precipitation.shutter_s = 0.0f;
  const double specks = streaks(near_view(frozen)).anisotropy;
  EXPECT_LT(specks, 0.6 * upright.anisotropy) << specks << " against " << upright.anisotropy;
}

// Snowflakes fall at a metre a second: drawn out over the same shutter, far rounder than the
// drops' streaks.
TEST_F(PrecipitationTest, SnowflakesAreRounderThanRainStreaks) {
  const Streaks rain = streaks(near_view(near_rain("rain", 20.0f, {0.0f, 0.0f}, 3.0f)));
  const Streaks snow = streaks(near_view(near_rain("snow", 2.0f, {0.0f, 0.0f}, 3.0f)));
  EXPECT_LT(snow.anisotropy, 0.6 * rain.anisotropy)
      << snow.anisotropy << " against " << rain.anisotropy;
}

// The same time renders the same particles; a thirtieth of a second later they have fallen:
// the image is best matched shifted down, not up.
TEST_F(PrecipitationTest, ParticlesAreTheSameOnARerenderAndFall) {
  const NearView a = near_view(near_rain("rain", 20.0f, {0.0f, 0.0f}, 3.0f));
  const NearView again = near_view(near_rain("rain", 20.0f, {0.0f, 0.0f}, 3.0f));
  for (size_t i = 0; i < a.on.size(); ++i) ASSERT_EQ(a.on[i], again.on[i]) << i;
  const NearView later = near_view(near_rain("rain", 20.0f, {0.0f, 0.0f}, 3.0f + 1.0f / 30.0f));
  // The correlation of the particles' light now with theirs a moment later `shift` rows lower.
  const auto correlation = [&](int shift) {
    double ab = 0.0, aa = 0.0, bb = 0.0;
    for (int y = 20; y + 20 < a.height; ++y)
      for (int x = 0; x < a.width; ++x) {
        const double p = a.diff(x, y), q = later.diff(x, y + shift);
        ab += p * q;
        aa += p * p;
        bb += q * q;
      }
    return ab / std::sqrt(aa * bb + 1e-30);
  };
  double down = -1.0, up = -1.0;
  for (int k = 1; k <= 20; ++k) {
    down = std::max(down, correlation(k));
    up = std::max(up, correlation(-k));
  }
  EXPECT_LT(correlation(0), 0.5) << "the particles did not move";
  EXPECT_GT(down, up + 0.1) << "down " << down << ", up " << up;
}

// From a cockpit in the deck, above where it rains from, no particles are drawn.
TEST_F(PrecipitationTest, NoParticlesAboveTheBase) {
  Scene s = nephele::load_preset("rain-cockpit");
  s.output.width = 64;
  s.output.height = 48;
  const NearView v = near_view(s);
  for (size_t i = 0; i < v.on.size(); ++i) ASSERT_EQ(v.on[i], v.off[i]) << i;
}

}  // namespace
