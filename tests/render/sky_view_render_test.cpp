// The sky-view LUT (sky_view.comp, sampled by compose.comp) against the brute-force sky it
// replaced: cloudless frames rendered on the device compared, pixel by pixel, with
// sky_hillaire evaluated per pixel on the CPU (the same function compiled as C++, with tables
// computed on the CPU).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "nephele/image_compare.h"
#include "nephele/scene_io.h"
#include "render/frame_params.h"
#include "frame_atmosphere.h"
#include "render_fixture.h"

using nephele::Scene;

namespace {

struct SkyError {
  double mean = 0.0;  // mean over pixels of the relative error, averaged over r, g, b
  double max = 0.0;
  double mean_near_sun = 0.0;  // the same within 20 degrees of the sun (the Mie peak)
  int pixels = 0;
};

// No clouds, so each pixel is the sky (or ground) alone: a lower resolution than the presets',
// every pixel compared.
Scene cloudless(const std::string& preset) {
  Scene s = nephele::load_preset(preset);
  s.clouds.coverage = 0.0f;
  s.output.width = 180;
  s.output.height = 120;
  return s;
}

SkyError sky_error(const Scene& scene) {
  const nephele::Frame frame = render(scene);
  const nephele::AtmosphereTables tables = nephele::compute_atmosphere_tables(scene);
  const nephele::gpu::FrameParams f =
      nephele::make_frame_params(scene, 0, nephele::sky_lights(scene), tables);
  const nephele::glsl::Atmosphere atmosphere = frame_atmosphere(f);
  const nephele::CameraBasis basis = nephele::camera_basis(scene.camera.view_dir);
  const glm::vec3 eye(f.camera_pos_m), sun(f.sun_dir), illuminance(f.sun_illuminance);
  const glm::vec3 ground_sky = glm::vec3(f.ground_sky_light) / illuminance;
  // The sun disk is drawn apart from the LUT: leave out its pixels (three disk radii).
  const float cos_disk = std::cos(3.0f * glm::radians(scene.sun.disk_angular_radius_deg));
  const float cos_near_sun = std::cos(glm::radians(20.0f));
  SkyError e;
  int near_sun = 0;
  for (int y = 0; y < frame.color.height; ++y)
    for (int x = 0; x < frame.color.width; ++x) {
      const glm::vec3 dir = nephele::glsl::camera_ray(
          basis.forward, basis.right, basis.up, f.camera_pos_m.w, f.camera_forward.w, float(x),
          float(y), float(frame.color.width), float(frame.color.height));
      if (glm::dot(dir, sun) > cos_disk) continue;
      const nephele::glsl::SkySample sky = nephele::glsl::sky_hillaire(
          atmosphere, tables.transmittance_lut(), tables.ms_lut(), tables.ms_field_lut(),
          f.sky_options.x, false, eye, dir, sun,
          scene.atmosphere.view_samples, scene.atmosphere.ground_albedo, ground_sky);
      const glm::vec3 expected = (sky.radiance + sky.ground_sun) * illuminance;
      const glm::vec4 got = frame.color.at(x, y);
      double error = 0.0;
      for (int c = 0; c < 3; ++c)
        error += std::abs(double(got[c]) - double(expected[c])) / double(expected[c]) / 3.0;
      e.mean += error;
      e.max = std::max(e.max, error);
      ++e.pixels;
      if (glm::dot(dir, sun) > cos_near_sun) {
        e.mean_near_sun += error;
        ++near_sun;
      }
    }
  e.mean /= std::max(e.pixels, 1);
  e.mean_near_sun /= std::max(near_sun, 1);
  std::printf(
      "sky-view LUT vs per-pixel sky: mean %.3f%%, within 20 deg of the sun %.3f%%, "
      "max %.2f%% over %d pixels\n",
      100.0 * e.mean, 100.0 * e.mean_near_sun, 100.0 * e.max, e.pixels);
  return e;
}

// Measured (180 x 120): mean 0.04% (noon), 0.08% (sunset), 0.07% (10 km); within 20 degrees of
// the sun 0.13% (noon), 0.16% (sunset). The largest errors, 2-6%, are ground pixels a fraction
// of a pixel below the horizon, where the ground's distance changes fastest. A LUT read a
// quarter texel off in v fails these bounds (0.6-1.2%), half a texel off in u and v (1.3-2.7%)
// or mirrored in azimuth (12%) by far.
constexpr double kMeanTolerance = 0.005;
constexpr double kMeanNearSunTolerance = 0.005;

}  // namespace

class SkyViewTest : public RenderTest {};

TEST_F(SkyViewTest, NoonFromTheGroundMatchesThePerPixelSky) {
  Scene s = cloudless("default");
  s.sun.direction = {0.1f, -0.25f, 1.0f};   // elevation 75 degrees
  s.camera.view_dir = {0.0f, -1.0f, 0.9f};  // towards the sun's azimuth: horizon, sky, sun
  s.camera.fov_deg = 100.0f;
  const SkyError e = sky_error(s);
  EXPECT_GT(e.pixels, 15000);
  EXPECT_LT(e.mean, kMeanTolerance);
  EXPECT_LT(e.mean_near_sun, kMeanNearSunTolerance);
}

TEST_F(SkyViewTest, SunsetMatchesThePerPixelSky) {
  Scene s = cloudless("sunset");            // sun 4 degrees up in the west
  s.sun.direction = {-1.0f, 0.0f, 0.035f};  // 2 degrees
  s.camera.view_dir = {-1.0f, 0.1f, 0.05f};
  s.camera.fov_deg = 60.0f;
  const SkyError e = sky_error(s);
  EXPECT_LT(e.mean, kMeanTolerance);
  EXPECT_LT(e.mean_near_sun, kMeanNearSunTolerance);
}

// Hillaire's isotropic multiple scattering (atmosphere.angular_multiple_scattering = false)
// stays selectable and the LUT serves it as well.
TEST_F(SkyViewTest, IsotropicMultipleScatteringMatchesThePerPixelSky) {
  Scene s = cloudless("sunset");
  s.atmosphere.angular_multiple_scattering = false;
  s.camera.view_dir = {-1.0f, 0.1f, 0.05f};
  s.camera.fov_deg = 60.0f;
  const SkyError e = sky_error(s);
  EXPECT_LT(e.mean, kMeanTolerance);
  EXPECT_LT(e.mean_near_sun, kMeanNearSunTolerance);
}

TEST_F(SkyViewTest, GroundFromTenKilometresMatchesThePerPixelSky) {
  Scene s = cloudless("default");
  s.camera.position_m = {0.0f, 0.0f, 10000.0f};
  s.camera.view_dir = {0.2f, 1.0f, -0.35f};  // the ground up to the horizon and some sky
  s.camera.fov_deg = 80.0f;
  const SkyError e = sky_error(s);
  EXPECT_LT(e.mean, kMeanTolerance);
}

// Looking straight up (issue 21: the LUT's top row held the sky 88.35 degrees up, so the
// last 1.65 degrees read it at their own azimuth and the two sides of the zenith differed by
// 6.8%): every pixel within 10 degrees of the zenith matches the per-pixel sky.
TEST_F(SkyViewTest, TheZenithHasNoSeam) {
  for (float elevation_deg : {15.0f, 45.0f}) {
    Scene s = cloudless("default");
    const float e = glm::radians(elevation_deg);
    s.sun.direction = {0.0f, std::cos(e), std::sin(e)};
    s.camera.view_dir = {0.0f, 1e-3f, 1.0f};
    s.camera.fov_deg = 20.0f;
    const SkyError err = sky_error(s);
    EXPECT_GT(err.pixels, 15000);
    EXPECT_LT(err.max, 0.005) << "sun " << elevation_deg << " deg";
    EXPECT_LT(err.mean, 0.002) << "sun " << elevation_deg << " deg";
  }
}

namespace {

bool has_pass(const nephele::Frame& frame, const std::string& name) {
  for (const nephele::PassTiming& p : frame.stats.passes)
    if (p.name == name) return true;
  return false;
}

}  // namespace

TEST_F(SkyViewTest, LutIsRecomputedOnlyWhenItsInputsChange) {
  Scene a = cloudless("default");
  a.output.width = 48;
  a.output.height = 32;
  const nephele::Frame first = render(a);
  if (first.stats.passes.empty()) GTEST_SKIP() << "the device has no timestamps";
  EXPECT_FALSE(has_pass(render(a), "sky_view"));
  Scene turned = a;  // the camera turns, the clouds change: the same LUT
  turned.camera.view_dir = {1.0f, 0.2f, -0.1f};
  turned.camera.fov_deg = 40.0f;
  turned.clouds.coverage = 0.6f;
  EXPECT_FALSE(has_pass(render(turned), "sky_view"));
  Scene moved_sun = a;
  moved_sun.sun.direction = {0.3f, 0.2f, 0.5f};
  EXPECT_TRUE(has_pass(render(moved_sun), "sky_view"));
  const nephele::Frame again = render(a);  // back to a's LUT, not moved_sun's
  EXPECT_TRUE(has_pass(again, "sky_view"));
  for (size_t i = 0; i < again.color.pixels.size(); ++i)
    ASSERT_EQ(again.color.pixels[i], first.color.pixels[i]) << "pixel " << i;
  Scene climbed = a;
  climbed.camera.position_m.z = 800.0f;
  EXPECT_TRUE(has_pass(render(climbed), "sky_view"));
  Scene hazier = climbed;
  hazier.atmosphere.mie_scattering_per_m *= 2.0f;
  hazier.atmosphere.mie_extinction_per_m *= 2.0f;
  EXPECT_TRUE(has_pass(render(hazier), "sky_view"));
}

// A camera flying along reuses the LUT until it has moved kSkyViewReuseM (or 1% of its
// altitude up or down), and the sky it then shows matches a LUT built where it is.
TEST_F(SkyViewTest, LutIsReusedWhileTheCameraMovesALittle) {
  Scene a = cloudless("default");
  a.output.width = 48;
  a.output.height = 32;
  a.camera.position_m = {0.0f, 0.0f, 300.0f};
  if (render(a).stats.passes.empty()) GTEST_SKIP() << "the device has no timestamps";
  Scene flown = a;
  flown.camera.position_m.y += 0.8f * nephele::kSkyViewReuseM;
  const nephele::Frame reused = render(flown);
  EXPECT_FALSE(has_pass(reused, "sky_view"));
  Scene far = a;
  far.camera.position_m.y += 1.2f * nephele::kSkyViewReuseM;
  EXPECT_TRUE(has_pass(render(far), "sky_view"));
  Scene climbed = a;
  climbed.camera.position_m.z += 4.0f;  // more than 1% of 300 m
  EXPECT_TRUE(has_pass(render(climbed), "sky_view"));
  // A fresh LUT at the flown position: the reused one differs by far less than a texel.
  nephele::Renderer fresh;
  const nephele::Frame exact = fresh.render(flown);
  EXPECT_LT(nephele::luminance_error(reused.color, exact.color), 1e-3);
}

// A sun moving with the clock (a date and an animation time) rebuilds the LUT only every
// kSkyViewReuseSunDeg, not every frame.
TEST_F(SkyViewTest, LutFollowsTheClockInSteps) {
  Scene a = cloudless("default");
  a.output.width = 48;
  a.output.height = 32;
  a.time = "2026-06-21T08:00:00Z";
  a.sun.from_time = true;
  a.location = {45.0f, 6.0f, 0.0f};
  if (render(a).stats.passes.empty()) GTEST_SKIP() << "the device has no timestamps";
  Scene later = a;
  later.time_s = 5.0f;  // the sun moves about 0.02 deg
  EXPECT_FALSE(has_pass(render(later), "sky_view"));
  later.time_s = 30.0f;  // about 0.12 deg
  EXPECT_TRUE(has_pass(render(later), "sky_view"));
}

// At night the moon is the key light and the twilight sun the second: the LUT follows both in
// steps too, and a second light that turns, brightens, appears or vanishes rebuilds it.
TEST_F(SkyViewTest, LutFollowsTheSecondLight) {
  Scene a = cloudless("default");
  a.output.width = 48;
  a.output.height = 32;
  a.time = "2026-06-24T21:30:00Z";  // Paris: moon 18.5 deg up, sun -11 deg
  a.sun.from_time = true;
  a.location = {48.85f, 2.35f, 0.0f};
  const nephele::gpu::FrameParams f = nephele::make_frame_params(a, 0);
  ASSERT_GT(f.second_light.w, 0.0f);
  const nephele::SkyViewKey built = nephele::sky_view_key(f);
  EXPECT_TRUE(nephele::sky_view_reusable(built, built));
  nephele::SkyViewKey turned = built;
  const float angle = glm::radians(2.0f * nephele::kSkyViewReuseSunDeg);
  turned.second_light = glm::vec4(glm::normalize(glm::vec3(built.second_light) +
                                                 angle * glm::vec3(0.0f, 0.0f, 1.0f)),
                                  built.second_light.w);
  EXPECT_FALSE(nephele::sky_view_reusable(built, turned));
  nephele::SkyViewKey brighter = built;
  brighter.second_light.w *= 1.02f;
  EXPECT_FALSE(nephele::sky_view_reusable(built, brighter));
  nephele::SkyViewKey none = built;
  none.second_light = glm::vec4(0.0f);
  EXPECT_FALSE(nephele::sky_view_reusable(built, none));
  EXPECT_FALSE(nephele::sky_view_reusable(none, built));
  EXPECT_TRUE(nephele::sky_view_reusable(none, none));
  if (render(a).stats.passes.empty()) GTEST_SKIP() << "the device has no timestamps";
  Scene later = a;
  later.time_s = 5.0f;
  EXPECT_FALSE(has_pass(render(later), "sky_view"));
  later.time_s = 30.0f;
  EXPECT_TRUE(has_pass(render(later), "sky_view"));
}

// The sun's centre 0.1 degrees above the horizon, its disk 0.27 degrees in radius: the part of
// the disk above the horizon shines, the planet hides the rest.
TEST_F(SkyViewTest, TheGroundHidesTheSunDiskBelowTheHorizon) {
  Scene s = cloudless("default");
  s.camera.position_m = {0.0f, 0.0f, 2.0f};
  const float elevation = glm::radians(0.1f);
  s.sun.direction = {0.0f, std::cos(elevation), std::sin(elevation)};
  s.camera.view_dir = s.sun.direction;
  s.camera.fov_deg = 2.0f;  // a disk radius is 16 pixels
  const nephele::Frame frame = render(s);
  const nephele::gpu::FrameParams f = nephele::make_frame_params(s, 0);
  const nephele::CameraBasis basis = nephele::camera_basis(s.camera.view_dir);
  const glm::vec3 sun(f.sun_dir);
  const auto sky_frame = nephele::glsl::sky_view_frame_from(f.sky_view_up, f.sky_view_forward);
  const float cos_inner = std::cos(0.8f * glm::radians(s.sun.disk_angular_radius_deg));
  const float cos_outer = std::cos(1.2f * glm::radians(s.sun.disk_angular_radius_deg));
  const float margin_rad = 2.0f * glm::radians(s.camera.fov_deg) / float(s.output.height);
  float above_min = INFINITY, below_max = 0.0f, ground_max = 0.0f;
  for (int y = 0; y < frame.color.height; ++y)
    for (int x = 0; x < frame.color.width; ++x) {
      const glm::vec3 dir = nephele::glsl::camera_ray(
          basis.forward, basis.right, basis.up, f.camera_pos_m.w, f.camera_forward.w, float(x),
          float(y), float(frame.color.width), float(frame.color.height));
      // Elevation above the horizon: clear of it by two pixels on either side.
      const float l = std::asin(glm::dot(dir, sky_frame.up)) - sky_frame.horizon_elevation_rad;
      const float red = frame.color.at(x, y).r;
      const bool in_disk = glm::dot(dir, sun) > cos_inner;
      if (in_disk && l > margin_rad) above_min = std::min(above_min, red);
      if (in_disk && l < -margin_rad) below_max = std::max(below_max, red);
      if (glm::dot(dir, sun) < cos_outer && l < -margin_rad) ground_max = std::max(ground_max, red);
    }
  ASSERT_GT(below_max, 0.0f) << "no disk pixel below the horizon";
  ASSERT_LT(above_min, INFINITY) << "no disk pixel above the horizon";
  EXPECT_GT(above_min, 100.0f * ground_max) << "the visible part of the disk shines";
  EXPECT_LT(below_max, 1.5f * ground_max) << "the ground hides the rest";
}
