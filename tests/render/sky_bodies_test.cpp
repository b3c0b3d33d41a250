// The moon and the stars: the moon disk shows the phase of the date, lit on the side facing
// the sun, and takes over lighting the sky and the clouds at night; stars stand where they are.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <libnova/precession.h>
#include <libnova/transform.h>
#include <vector>
#include <glm/geometric.hpp>

#include "nephele/image_compare.h"
#include "nephele/scene_io.h"
#include "nephele/sky.h"
#include "render/frame_params.h"
#include "render/frame_atmosphere.h"
#include "render/render_fixture.h"

namespace nephele {
namespace {

// A narrow view centred on the moon at `time` in Paris, no clouds.
Scene moon_view(const std::string& time) {
  Scene s = load_preset("default");
  s.time = time;
  s.sun.from_time = true;
  s.location = {48.85f, 2.35f, 35.0f};
  s.clouds.coverage = 0.0f;
  s.output.width = 160;
  s.output.height = 160;
  s.camera.fov_deg = 1.2f;
  s.camera.view_dir = scene_ephemeris(s)->moon.direction;
  return s;
}

struct DiskShape {
  double lit_share;  // lit pixels over the disk's area
  glm::vec2 lit_offset_px;  // centroid of the lit pixels from the image centre (x right, y down)
};

DiskShape measure_disk(const Scene& s, const Image& image) {
  const Ephemeris e = *scene_ephemeris(s);
  const double radius_rad = std::asin(1737.4 / e.moon.distance_km);
  const double radius_px = std::tan(radius_rad) / std::tan(glm::radians(s.camera.fov_deg) / 2.0) *
                           (s.output.height / 2.0);
  double max_lum = 0.0;
  for (const glm::vec4& p : image.pixels) max_lum = std::max(max_lum, double(luminance(p)));
  int lit = 0;
  glm::dvec2 sum(0.0);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (luminance(image.at(x, y)) > 0.05 * max_lum) {
        ++lit;
        sum += glm::dvec2(x + 0.5 - image.width / 2.0, y + 0.5 - image.height / 2.0);
      }
  return {lit / (M_PI * radius_px * radius_px), lit ? glm::vec2(sum / double(lit)) : glm::vec2(0)};
}

class MoonTest : public RenderTest {};

TEST_F(MoonTest, DiskShowsThePhaseLitTowardsTheSun) {
  // Waxing gibbous (0.78) in the evening and a waning crescent before dawn.
  for (const char* time : {"2026-06-24T21:30:00Z", "2026-07-11T02:30:00Z"}) {
    SCOPED_TRACE(time);
    const Scene s = moon_view(time);
    const Ephemeris e = *scene_ephemeris(s);
    ASSERT_GT(e.moon.elevation_deg, 5.0);
    const DiskShape disk = measure_disk(s, render(s).color);
    // The lit area is the illuminated fraction (the brightness falls towards the terminator,
    // so a threshold at 5% of the peak trims a little of it).
    std::printf("lit share %.3f, illuminated fraction %.3f\n", disk.lit_share, e.moon_illuminated_fraction);
    EXPECT_NEAR(disk.lit_share, e.moon_illuminated_fraction, 0.06)
        << "illuminated fraction " << e.moon_illuminated_fraction;
    // The lit side faces the sun: the direction from the moon to the sun, on the image.
    const CameraBasis b = camera_basis(s.camera.view_dir);
    const gpu::FrameParams f = make_frame_params(s, 0);
    const glm::vec3 to_sun(f.moon_sun_dir);
    const glm::vec2 expected = glm::normalize(glm::vec2(glm::dot(to_sun, b.right), -glm::dot(to_sun, b.up)));
    const float cos_angle = glm::dot(glm::normalize(disk.lit_offset_px), expected);
    EXPECT_GT(cos_angle, std::cos(glm::radians(15.0f)));
  }
}

TEST_F(MoonTest, StarsAreWhereTheyAreInTheSky) {
  // Vega (HR 7001) over Paris on a moonless night, placed independently: its J2000 position
  // precessed and turned into altitude and azimuth by libnova.
  Scene s = moon_view("2026-07-14T22:30:00Z");
  const double jd = *julian_day_from_iso8601(s.time);
  ln_equ_posn j2000{279.2340, 38.7836}, date;
  ln_get_equ_prec(&j2000, jd, &date);
  ln_lnlat_posn observer{2.35, 48.85};
  ln_hrz_posn hrz;
  ln_get_hrz_from_equ(&date, &observer, jd, &hrz);
  s.camera.view_dir = sun_direction_from_angles(hrz.alt, hrz.az + 180.0);
  s.camera.fov_deg = 1.0f;
  s.output.width = s.output.height = 64;
  const Image image = render(s).color;
  int best = 0;
  for (int i = 1; i < int(image.pixels.size()); ++i)
    if (luminance(image.pixels[i]) > luminance(image.pixels[best])) best = i;
  // The image centre lies between pixels 31 and 32: within 1.5 px = 0.023 deg.
  EXPECT_NEAR(best % 64 + 0.5, 32.0, 1.5);
  EXPECT_NEAR(best / 64 + 0.5, 32.0, 1.5);
  // A star, not the sky: far brighter than the median pixel.
  std::vector<float> l;
  for (const glm::vec4& p : image.pixels) l.push_back(luminance(p));
  std::nth_element(l.begin(), l.begin() + l.size() / 2, l.end());
  EXPECT_GT(luminance(image.pixels[best]), 100.0f * l[l.size() / 2]);
}

TEST(MoonLight, FullAndQuarterMoonIlluminance) {
  // Full moon -12.73 mag against the sun's -26.74; a quarter moon about a tenth of the full.
  EXPECT_NEAR(moon_illuminance_ratio(1.0, 384400.0), 2.44e-6, 1e-9);
  EXPECT_NEAR(moon_illuminance_ratio(0.5, 384400.0) / moon_illuminance_ratio(1.0, 384400.0), 0.091,
              0.005);
  // Nearer is brighter, as the inverse square of the distance.
  EXPECT_NEAR(moon_illuminance_ratio(1.0, 356500.0) / moon_illuminance_ratio(1.0, 384400.0),
              std::pow(384400.0 / 356500.0, 2.0), 1e-9);
}

TEST(MoonLight, TheMoonTakesOverAtNightAndNotByDay) {
  Scene s = moon_view("2026-06-24T21:30:00Z");  // sun -11 deg, moon 18.5 deg up
  EXPECT_TRUE(key_light(s).moon);
  EXPECT_LT(key_light(s).illuminance, s.sun.illuminance_lux * 3e-6f);
  s.time = "2026-06-24T15:30:00Z";  // afternoon: the sun
  EXPECT_FALSE(key_light(s).moon);
  EXPECT_EQ(key_light(s).illuminance, s.sun.illuminance_lux);
  s.time = "2026-06-24T20:00:00Z";  // sun -1 deg: it still lights the clouds, reddened
  EXPECT_FALSE(key_light(s).moon);
}

// Sun 12.4 deg down (Paris, 2026-06-24 02:00 UTC, no moon key): the horizon below the sun glows
// 6,500 times brighter than the zenith, in a band a few degrees high. The clouds' sky light is
// the cosine-weighted sky above them, not that glow: an isotropic mean over all directions
// made it 100 times the zenith's radiance and 27 times redder than blue, and the clouds glowed
// red against a black sky.
TEST(CloudLight, TwilightCloudsAreLitByTheSkyAboveNotByTheHorizonGlow) {
  Scene s = load_preset("default");
  s.time = "2026-06-24T02:00:00Z";
  s.sun.from_time = true;
  s.location = {48.85f, 2.35f, 35.0f};
  ASSERT_FALSE(sky_lights(s).key.moon);
  const nephele::AtmosphereTables t = compute_atmosphere_tables(s);
  const gpu::FrameParams f = make_frame_params(s, 0, sky_lights(s), t);
  ASSERT_NEAR(glm::degrees(std::asin(f.sun_dir.z)), -12.4f, 0.3f);
  const glm::vec3 above(f.ambient_at_clouds), below(f.ambient_below_clouds);
  EXPECT_GT(above.b, 0.0f);
  EXPECT_LT(above.r / above.b, 1.5f);
  // The zenith sky from the cloud layer's middle, per unit illuminance like the ambient.
  const glsl::Atmosphere a = frame_atmosphere(f);
  const glm::vec3 mid(0.0f, 0.0f, a.planet_radius_m + 2750.0f);
  const glm::vec3 zenith = glsl::sky_hillaire(a, t.transmittance_lut(), t.ms_lut(), t.ms_field_lut(),
                                              glsl::MS_ANGULAR, false, mid, glm::vec3(0, 0, 1),
                                              glm::vec3(f.sun_dir), 32, 0.3f, glm::vec3(0.0f))
                               .radiance *
                           glm::vec3(f.sun_illuminance);
  EXPECT_LT(above.g, 10.0f * zenith.g);
  EXPECT_GT(above.g, zenith.g);  // the horizon still adds some
  EXPECT_LT(below.g, above.g);   // the ground is darker than the sky at night
}

TEST(MoonLight, TheOtherBodyLightsTheSkyTooUntilItIsFarBelowTheHorizon) {
  Scene s = moon_view("2026-06-24T21:30:00Z");  // sun -11 deg under a moon key
  SkyLights lights = sky_lights(s);
  ASSERT_TRUE(lights.key.moon);
  EXPECT_FALSE(lights.second.moon);
  EXPECT_EQ(lights.second.illuminance, s.sun.illuminance_lux);
  EXPECT_NEAR(glm::dot(lights.second.direction, scene_sun_direction(s, lights.ephemeris)), 1.0f,
              1e-6f);
  s.time = "2026-06-24T20:00:00Z";  // sun key at -1 deg, moon up: the moon is the second
  lights = sky_lights(s);
  ASSERT_FALSE(lights.key.moon);
  EXPECT_TRUE(lights.second.moon);
  EXPECT_LT(lights.second.illuminance, s.sun.illuminance_lux * 3e-6f);
  s.time = "2026-06-24T15:30:00Z";  // by day: none
  EXPECT_EQ(sky_lights(s).second.illuminance, 0.0f);
  s.time = "2026-12-10T23:00:00Z";  // sun -63 deg, thin moon -56 deg: none
  lights = sky_lights(s);
  ASSERT_LT(lights.ephemeris->moon.elevation_deg, kSecondLightMinElevationDeg);
  EXPECT_FALSE(lights.key.moon);
  EXPECT_EQ(lights.second.illuminance, 0.0f);
}

}  // namespace
}  // namespace nephele
