// Photometric units on the device: with the sun at the luminous solar constant (lux) and the
// renderer's radiances in cd/m^2, an incident meter at the camera (the illuminance on level
// ground) reads the published illuminance of each light; the reflected meter (auto exposure)
// reads the exposure a photographer would use (EV100: about 15 on a sunny day, 8 to 11 at
// sunset, 3 to 5 in civil twilight, -2 to -4 under a full moon), and frames at those exposures
// are a sane mid-grey; an overcast sky, bright as a white card under it, reads about 2.5 EV
// above the incident meter (12.6 under the overcast preset).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>

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
  // The illuminance on level ground in such light (lux), as published, for an incident meter.
  double lux_low, lux_high;
  bool filled_by_cloud = false;  // the view is an overcast sky
  // Where the incident meter stands, on the ground: the camera's place unless given.
  std::optional<glm::vec3> meter_at_m = std::nullopt;
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

// An incident meter's EV100 for illuminance E (lux) on a flat receptor: log2(E S / C), S = 100,
// C = 250 (ISO 2720).
double incident_ev100_of(double lux) {
  return std::log2(lux * 100.0 / 250.0);
}

class ExposureRenderTest : public RenderTest {
 protected:
  // An incident meter's EV100 at the camera: E, the illuminance on level ground there, from the
  // ground's luminance straight below (the ground is Lambertian: L = albedo E / pi), the sun's, the
  // sky's and the light the clouds scatter down together.
  double incident_ev100(Scene s, std::optional<glm::vec3> at_m) {
    if (at_m) s.camera.position_m = *at_m;
    s.camera.view_dir = {0.0f, 0.01f, -1.0f};
    s.camera.fov_deg = 10.0f;
    s.output.width = s.output.height = 8;
    const nephele::Frame frame = render(s);
    return incident_ev100_of(M_PI * frame.stats.mean_luminance /
                             double(s.atmosphere.ground_albedo));
  }
};

TEST_F(ExposureRenderTest, PhotographersExposuresGiveSaneFrames) {
  Scene moon = small(nephele::load_preset("default"));
  moon.time = "2026-12-24T21:00:00Z";  // Paris: the full moon 41 deg up, the sun 48 deg below
  moon.sun.from_time = true;
  moon.location = {48.85f, 2.35f, 35.0f};
  moon.camera.view_dir = {0.9f, -0.12f, 0.42f};
  const Light lights[] = {
      // Illuminances: the sun 35 deg up, in its light, 60-100 klx (clear sky alone 65 klx
      // here); an overcast day 5-25 klx; the sun on the horizon 300-1,500 lx; civil twilight
      // at -5 deg 3-40 lx; a full moon 41 deg up 0.03-0.2 lx (0.27 at the zenith, clear).
      // Sunny 16 is for subjects in the sun: the camera's own place lies in a cumulus' shadow
      // (incident 13.6 there, 14.7 under a clear sky, 14.97 here, the clouds' light added).
      {"sunny day", small(nephele::load_preset("default")), 15.0, 60e3, 100e3, false,
       glm::vec3(3000.0f, 0.0f, 2.0f)},
      {"overcast", small(nephele::load_preset("overcast")), 12.5, 5e3, 25e3, true},
      {"sunset (sun at 0 deg, looking along the horizon)", sun_at(0.0f, {-1.0f, 0.3f, 0.1f}), 10.0,
       300.0, 1500.0},
      {"civil twilight (sun at -5 deg)", sun_at(-5.0f, {0.0f, 1.0f, 0.3f}), 4.0, 3.0, 40.0},
      {"full moon", moon, -3.0, 0.03, 0.2},
  };
  for (const Light& light : lights) {
    const nephele::Frame frame = render(light.scene);
    const double metered = nephele::ev100_from_luminance(nephele::metered_luminance(frame.color));
    const double incident = incident_ev100(light.scene, light.meter_at_m);
    const double grey = mean_display_value(
        frame.color, float(nephele::exposure_from_ev100(light.photographers_ev100)));
    std::printf(
        "%-50s incident EV100 %6.2f, metered %6.2f (photographer %5.1f), mean "
        "luminance %.4g cd/m^2, display mean at the photographer's EV %.3f\n",
        light.name, incident, metered, light.photographers_ev100, frame.stats.mean_luminance, grey);
    EXPECT_GE(incident, incident_ev100_of(light.lux_low)) << light.name;
    EXPECT_LE(incident, incident_ev100_of(light.lux_high)) << light.name;
    EXPECT_GT(grey, 0.2) << light.name << ": too dark at the photographer's exposure";
    if (light.filled_by_cloud) {
      // An overcast sky is about as bright as a white card under it, L = E / pi: a reflected
      // meter (calibrated on 18% grey) reads it about log2(1 / 0.18) = 2.5 EV above the
      // incident reading, and a photographer's exposure renders it near white.
      EXPECT_NEAR(metered - incident, 2.5, 1.0) << light.name;
    } else {
      EXPECT_NEAR(metered, light.photographers_ev100, 1.5) << light.name;
      EXPECT_LT(grey, 0.7) << light.name << ": too bright at the photographer's exposure";
    }
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
