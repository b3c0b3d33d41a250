// Photometric units on the device: with the sun at the luminous solar constant (lux) and the
// renderer's radiances in cd/m^2, the exposures a photographer would use (EV100: about 15 on a
// sunny day, 12 to 13 overcast, 8 to 11 at sunset, 3 to 5 in civil twilight, -2 to -4 under a
// full moon) give frames of a sane mid-grey, and the meter reads about those EVs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "nephele/exposure.h"
#include "nephele/image.h"
#include "nephele/scene_io.h"
#include "render_fixture.h"

namespace {

using nephele::Scene;

struct Light {
  const char* name;
  Scene scene;
  double photographers_ev100;  // the exposure a photographer would use
};

Scene small(Scene s) {
  s.output.width = 96;
  s.output.height = 64;
  return s;
}

Scene sun_at(float elevation_deg, glm::vec3 view_dir) {
  Scene s = nephele::load_preset("default");
  s.sun.direction = nephele::sun_direction_from_angles(elevation_deg, 270.0);
  s.camera.view_dir = view_dir;
  return small(s);
}

// The mean of the 8-bit sRGB values of the frame as the PNG writer encodes it (0 to 1): about
// 0.45 for a frame whose log-average luminance is the meter's grey.
double mean_display_value(const nephele::Image& image, float exposure) {
  const std::vector<unsigned char> rgba = nephele::tonemap_srgb8(image, exposure);
  double sum = 0.0;
  for (size_t i = 0; i < rgba.size(); i += 4)
    sum += 0.2126 * rgba[i] + 0.7152 * rgba[i + 1] + 0.0722 * rgba[i + 2];
  return sum / (255.0 * double(rgba.size() / 4));
}

class ExposureRenderTest : public RenderTest {};

TEST_F(ExposureRenderTest, PhotographersExposuresGiveSaneFrames) {
  Scene moon = small(nephele::load_preset("default"));
  moon.time = "2026-12-24T21:00:00Z";  // Paris: the full moon 41 deg up, the sun 48 deg below
  moon.sun.from_time = true;
  moon.location = {48.85f, 2.35f, 35.0f};
  moon.camera.view_dir = {0.9f, -0.12f, 0.42f};
  const Light lights[] = {
      {"sunny day", small(nephele::load_preset("default")), 15.0},
      {"overcast", small(nephele::load_preset("overcast")), 12.5},
      {"sunset (sun at 0 deg, looking along the horizon)", sun_at(0.0f, {-1.0f, 0.3f, 0.1f}), 10.0},
      {"civil twilight (sun at -5 deg)", sun_at(-5.0f, {0.0f, 1.0f, 0.3f}), 4.0},
      {"full moon", moon, -3.0},
  };
  for (const Light& light : lights) {
    const nephele::Frame frame = render(light.scene);
    const double metered = nephele::ev100_from_luminance(nephele::metered_luminance(frame.color));
    const double grey = mean_display_value(
        frame.color, float(nephele::exposure_from_ev100(light.photographers_ev100)));
    std::printf("%-50s metered EV100 %6.2f (photographer %5.1f), mean luminance %.4g cd/m^2, "
                "display mean at the photographer's EV %.3f\n",
                light.name, metered, light.photographers_ev100, frame.stats.mean_luminance, grey);
    EXPECT_NEAR(metered, light.photographers_ev100, 1.5) << light.name;
    EXPECT_GT(grey, 0.2) << light.name << ": too dark at the photographer's exposure";
    EXPECT_LT(grey, 0.7) << light.name << ": too bright at the photographer's exposure";
  }
}

// Auto exposure is the default, so a civil-twilight frame is not black; at the old default
// (the old linear 0.5, EV100 13.38) it was.
TEST_F(ExposureRenderTest, CivilTwilightIsNotBlackByDefault) {
  const Scene s = sun_at(-4.0f, {0.0f, 1.0f, 0.3f});
  ASSERT_TRUE(s.output.auto_exposure);
  const nephele::Frame frame = render(s);
  const double auto_grey = mean_display_value(frame.color, nephele::still_exposure(s.output, frame.color));
  const double old_grey = mean_display_value(
      frame.color, float(nephele::exposure_from_ev100(nephele::ev100_from_legacy_exposure(0.5))));
  std::printf("civil twilight: display mean %.3f auto, %.4f at the old default\n", auto_grey,
              old_grey);
  EXPECT_GT(auto_grey, 0.3);
  EXPECT_LT(old_grey, 0.05);
}

// The device's exposure meter (meter.comp, FrameStats::metered_luminance) reads what the
// host's reads of the whole image (metered_luminance): 64 x 64 pixels of it, within 10%, by
// day, at sunset and in civil twilight (a reading 10% off is 0.14 EV).
TEST_F(ExposureRenderTest, TheDevicesMeterReadsWhatTheHostsDoes) {
  for (float elevation : {40.0f, 2.0f, -4.0f}) {
    const Scene s = sun_at(elevation, {0.0f, 1.0f, 0.3f});
    const nephele::Frame frame = render(s);
    const double host = nephele::metered_luminance(frame.color);
    std::printf("sun %.0f deg: device meter %.4g cd/m^2, host %.4g\n", elevation,
                frame.stats.metered_luminance, host);
    EXPECT_NEAR(frame.stats.metered_luminance, host, 0.1 * host) << elevation;
  }
}

// The old scale and the new give the same light: an old scene (sun.illuminance 20, exposure
// 0.5) renders as before, the HDR image now in cd/m^2, 6400 times the old values.
TEST_F(ExposureRenderTest, OldKeysRenderTheSameImage) {
  Scene now = small(nephele::load_preset("default"));
  now.output.auto_exposure = false;
  now.output.ev100 = float(nephele::ev100_from_legacy_exposure(0.5));
  const Scene old = small(nephele::parse_scene_toml(
      "preset = \"default\"\n[sun]\nilluminance = 20.0\n[output]\nexposure = 0.5\n", "old.toml"));
  EXPECT_EQ(old.sun.illuminance_lux, now.sun.illuminance_lux);
  EXPECT_EQ(old.output.ev100, now.output.ev100);
  EXPECT_FALSE(old.output.auto_exposure);
  // Half the solar constant: half the luminance everywhere.
  Scene half = now;
  half.sun.illuminance_lux = 0.5f * nephele::kSolarConstantLux;
  const nephele::Frame a = render(now), b = render(half);
  EXPECT_NEAR(b.stats.mean_luminance / a.stats.mean_luminance, 0.5, 1e-3);
}

}  // namespace
