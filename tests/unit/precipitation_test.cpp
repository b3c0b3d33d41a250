// Rain and snow as a medium (shaders/common/precipitation_inc.glsl, the precipitation module's
// parameters): the extinction against an independent integration of Marshall and Palmer's drop
// sizes and against the visibilities observers report for snow, the profile's column against
// numerical integration, and where the clouds let it fall.
#include "render/modules/precipitation/precipitation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/trigonometric.hpp>
#include <glm/vec2.hpp>

#include "nephele/error.h"
#include "nephele/scene.h"
#include "nephele/scene_io.h"
#include "render/glsl.h"

namespace {

namespace g = nephele::glsl;
constexpr double kKoschmieder = 3.912;

// sigma_t = the drops' cross-section per volume (efficiency 1: their diffraction counted as
// unscattered), integrating Marshall-Palmer's N(D) (m^-3 per mm of diameter) numerically in
// double: an independent statement of the closed form.
double marshall_palmer_sigma_t(double rate_mm_per_h) {
  const double n0 = 8000.0;                                    // m^-3 mm^-1
  const double lambda = 4.1 * std::pow(rate_mm_per_h, -0.21);  // mm^-1
  double sum = 0.0;
  const double step_mm = 1e-4;
  for (double d = 0.5 * step_mm; d < 60.0; d += step_mm) {
    const double d_m = d * 1e-3;
    sum += 3.14159265358979 * d_m * d_m / 4.0 * n0 * std::exp(-lambda * d) * step_mm;
  }
  return sum;
}

nephele::PrecipitationParams falling(const char* kind, float rate) {
  nephele::PrecipitationParams p;
  p.kind = kind;
  p.rate_mm_per_h = rate;
  return p;
}

TEST(Precipitation, RainExtinctionIsMarshallPalmers) {
  for (float rate : {0.5f, 2.0f, 10.0f, 50.0f}) {
    const double expected = marshall_palmer_sigma_t(rate);
    EXPECT_NEAR(g::precipitation_sigma_t_per_m(g::PRECIPITATION_RAIN, rate), expected,
                1e-3 * expected)
        << rate << " mm/h";
  }
  // What a driver sees: some 5 km in heavy rain (10 mm/h), 20 km in light rain; and within
  // a third of Atlas' (1953) measured 0.25 R^0.63 per km.
  EXPECT_NEAR(nephele::precipitation_visibility_m(falling("rain", 10.0f)), 5030.0, 50.0);
  EXPECT_GT(nephele::precipitation_visibility_m(falling("rain", 1.0f)), 20000.0f);
  for (float rate : {1.0f, 10.0f, 50.0f}) {
    const double atlas = 0.25e-3 * std::pow(rate, 0.63);
    EXPECT_NEAR(g::precipitation_sigma_t_per_m(g::PRECIPITATION_RAIN, rate), atlas, atlas / 3.0);
  }
}

// Snow hides far more than rain of the same water: the US observers' classes (light snow 1 km
// or more, heavy a quarter mile, 400 m, or less) at the rates Rasmussen et al. (1999) measured
// with them (light under 1 mm/h, heavy 2.5 mm/h or more).
TEST(Precipitation, SnowVisibilityFollowsTheObservedClasses) {
  EXPECT_GT(nephele::precipitation_visibility_m(falling("snow", 0.8f)), 1000.0f);
  EXPECT_LT(nephele::precipitation_visibility_m(falling("snow", 3.0f)), 402.0f);
  for (float rate : {0.5f, 1.0f, 4.0f}) {
    const float snow = nephele::precipitation_visibility_m(falling("snow", rate));
    EXPECT_LT(snow, 0.25f * nephele::precipitation_visibility_m(falling("rain", rate))) << rate;
    // Sleet (wet, denser, faster flakes) and drizzle lie between.
    EXPECT_GT(nephele::precipitation_visibility_m(falling("sleet", rate)), snow);
  }
  // Linear in the rate: the particles' number grows with the flux at a fixed size and speed.
  EXPECT_NEAR(nephele::precipitation_visibility_m(falling("snow", 1.0f)) /
                  nephele::precipitation_visibility_m(falling("snow", 2.0f)),
              2.0, 1e-4);
  EXPECT_NEAR(nephele::precipitation_visibility_m(falling("snow", 1.0f)), kKoschmieder / 3.333e-3,
              2.0);
}

TEST(Precipitation, NoneWithoutARateOrAKnownKind) {
  EXPECT_EQ(nephele::precipitation_sigma_t_per_m(falling("rain", 0.0f)), 0.0f);
  EXPECT_EQ(nephele::precipitation_sigma_t_per_m(falling("hail", 5.0f)), 0.0f);
  EXPECT_EQ(nephele::precipitation_kind("hail"), -1);
  EXPECT_TRUE(std::isinf(nephele::precipitation_visibility_m(falling("rain", 0.0f))));
  for (const char* kind : {"rain", "drizzle", "snow", "sleet"})
    EXPECT_GT(nephele::precipitation_sigma_t_per_m(falling(kind, 1.0f)), 0.0f) << kind;
}

// Virga that would end at or above the base it falls from is refused in one line naming both;
// a kind outside the four too.
TEST(Precipitation, AVirgaBelowItsBaseAndAKnownKind) {
  nephele::Scene scene;
  scene.precipitation.rate_mm_per_h = 2.0f;
  scene.precipitation.bottom_m = scene.clouds.bottom_altitude_m;
  try {
    nephele::validate_scene(scene);
    ADD_FAILURE() << "virga ending at its base accepted";
  } catch (const nephele::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "precipitation.bottom_m = 1500: must be below clouds.bottom_altitude_m (1500)");
  }
  scene.precipitation.bottom_m = 0.0f;
  scene.precipitation.kind = "hail";
  try {
    nephele::validate_scene(scene);
    ADD_FAILURE() << "hail accepted";
  } catch (const nephele::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("precipitation.kind = \"hail\""), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("\"snow\""), std::string::npos) << e.what();
  }
}

// The column is the profile's integral: a midpoint rule for rain that reaches the ground and
// for virga that evaporates 600 m above it.
// Rain falls at its median volume diameter's speed (Gunn and Kinzer 1949 measured 4.03 m/s for
// a 1 mm drop and 6.49 m/s for a 2 mm one); the wind carries it sideways by 7/8 of the cloud
// base's wind over that speed, so that a shaft leans downwind.
TEST(Precipitation, ItFallsAtTheDropsSpeedAndLeansWithTheWind) {
  // Marshall-Palmer's D0 = 3.67 / lambda is 1 mm at 1.70 mm/h and 2 mm at 46 mm/h.
  const auto rate_for_d0 = [](double d0_mm) {
    return float(std::pow(d0_mm * 4.1 / 3.67, 1.0 / 0.21));
  };
  EXPECT_NEAR(g::precipitation_fall_mps(g::PRECIPITATION_RAIN, rate_for_d0(1.0)), 4.03f, 0.12f);
  EXPECT_NEAR(g::precipitation_fall_mps(g::PRECIPITATION_RAIN, rate_for_d0(2.0)), 6.49f, 0.2f);
  EXPECT_FLOAT_EQ(g::precipitation_fall_mps(g::PRECIPITATION_SNOW, 1.0f), 1.0f);
  // Snow in a 10 m/s wind at the base drifts 8.75 m per metre of fall; rain at 10 mm/h, 1.6.
  const glm::vec2 snow = g::precipitation_drift_slope(glm::vec2(10.0f, 0.0f), 1.0f);
  EXPECT_FLOAT_EQ(snow.x, 8.75f);
  EXPECT_FLOAT_EQ(snow.y, 0.0f);
  const float rain_fall = g::precipitation_fall_mps(g::PRECIPITATION_RAIN, 10.0f);
  EXPECT_NEAR(g::precipitation_drift_slope(glm::vec2(0.0f, 10.0f), rain_fall).y, 8.75f / 5.33f,
              0.02f);
}

TEST(Precipitation, TheColumnIsTheProfilesIntegral) {
  const float top = 1500.0f;
  for (float bottom : {0.0f, 600.0f}) {
    double sum = 0.0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
      const float z = top * (i + 0.5f) / n;
      sum += g::precipitation_profile(z, bottom, top) * top / n;
      if (i % 20000 == 0) {
        EXPECT_NEAR(g::precipitation_column_m(z, bottom, top), sum, 0.1 + 1e-4 * sum) << z;
      }
    }
    EXPECT_NEAR(g::precipitation_column_m(top, bottom, top), sum, 1e-3 * sum) << bottom;
    EXPECT_EQ(g::precipitation_column_m(top + 500.0f, bottom, top),
              g::precipitation_column_m(top, bottom, top));
  }
  // Virga: none below its bottom, all of it at the base, half-way up its fall still thinning.
  EXPECT_EQ(g::precipitation_profile(500.0f, 600.0f, top), 0.0f);
  EXPECT_EQ(g::precipitation_profile(1400.0f, 600.0f, top), 1.0f);
  EXPECT_NEAR(g::precipitation_profile(800.0f, 600.0f, top), 0.444f, 1e-3);
  EXPECT_EQ(g::precipitation_profile(1600.0f, 0.0f, top), 0.0f);  // above the base
}

// It falls under the storm cells' cores and under a nearly closed deck, not from fair-weather
// cumulus between them; a core's shaft is lit by a quarter of the clouds' mean light.
TEST(Precipitation, ItFallsUnderStormCoresAndClosedDecks) {
  // A scattered layer (coverage 0.4) away from storm cells: none; nor from its densest
  // clusters (the map's coverage 1).
  EXPECT_EQ(g::precipitation_shaft_share(0.5f, 0.0f, 0.4f, 0.0f).x, 0.0f);
  EXPECT_EQ(g::precipitation_shaft_share(1.0f, 0.0f, 0.4f, 0.0f).x, 0.0f);
  // An overcast (coverage 1) everywhere, from no core; a broken layer (0.6) not yet.
  EXPECT_EQ(g::precipitation_shaft_share(0.0f, 0.0f, 1.0f, 0.0f), glm::vec2(1.0f, 0.0f));
  EXPECT_EQ(g::precipitation_shaft_share(1.0f, 0.0f, 0.6f, 0.0f).x, 0.0f);
  // A storm cell's core (g 0.5 at full growth) under the same scattered layer: all of it; the
  // cell's rim (g 0.3, where the towers are half cumulonimbus) none yet; no growth, none.
  EXPECT_EQ(g::precipitation_shaft_share(0.5f, 0.5f, 0.4f, 1.0f), glm::vec2(1.0f, 1.0f));
  EXPECT_EQ(g::precipitation_shaft_share(0.5f, 0.3f, 0.4f, 1.0f).x, 0.0f);
  const float between = g::precipitation_shaft_share(0.5f, 0.4f, 0.4f, 1.0f).x;
  EXPECT_GT(between, 0.3f);
  EXPECT_LT(between, 0.7f);
  EXPECT_EQ(g::precipitation_shaft_share(0.5f, 0.5f, 0.4f, 0.0f).x, 0.0f);
  EXPECT_EQ(g::precipitation_core_light(0.0f), 1.0f);
  EXPECT_EQ(g::precipitation_core_light(1.0f), 0.25f);
}

// The march's samples on fixed horizontal distances, and their inverse, which compose uses to
// read the froxels at its own distance: sample k's place gives k back, a distance between two
// samples lies between their indices, and the samples outside a ray's stretch fall on its
// ends (a steep ray up through the rain: one step).
TEST(Precipitation, TheSamplesPlacesAndTheirInverse) {
  for (float horizontal : {1.0f, 0.5f, 0.05f}) {
    const glm::vec2 stretch(
        0.0f, std::min(150000.0f, 1500.0f / std::sqrt(1.0f - horizontal * horizontal + 1e-12f)));
    float last = -1.0f;
    for (int k = 0; k <= g::PRECIPITATION_STEPS; ++k) {
      const float t = g::precipitation_sample_t(k, stretch, horizontal);
      EXPECT_GE(t, last) << k;
      EXPECT_GE(t, stretch.x);
      EXPECT_LE(t, stretch.y);
      last = t;
    }
    EXPECT_EQ(g::precipitation_sample_t(g::PRECIPITATION_STEPS, stretch, horizontal), stretch.y);
    for (float u : {0.01f, 0.2f, 0.5f, 0.9f, 1.0f}) {
      const float t = u * stretch.y;
      const float k = g::precipitation_sample_at(t, stretch, horizontal);
      const int k0 = std::min(int(k), g::PRECIPITATION_STEPS - 1);
      EXPECT_LE(g::precipitation_sample_t(k0, stretch, horizontal), t + 1e-3f * t) << horizontal;
      EXPECT_GE(g::precipitation_sample_t(k0 + 1, stretch, horizontal), t - 1e-3f * t)
          << horizontal;
    }
  }
  // Horizontal rays: sample k lies 150 km (k / 24)^2 away; its own place gives k back.
  const glm::vec2 far(0.0f, 150000.0f);
  for (int k : {1, 5, 12, 23})
    EXPECT_NEAR(g::precipitation_sample_at(g::precipitation_sample_t(k, far, 1.0f), far, 1.0f), k,
                1e-3);
  // Straight up through 1.5 km of rain: one step from the eye to the base.
  const glm::vec2 up(0.0f, 1500.0f);
  EXPECT_EQ(g::precipitation_sample_t(1, up, 1e-4f), 1500.0f);
  EXPECT_NEAR(g::precipitation_sample_at(750.0f, up, 1e-4f), 0.5f, 1e-4);
}

// The slab's light: with nothing around, the sun's beam by the phase and the sky's light; deep
// inside, the beam gone and the diffuse light what a two-stream slab passes on.
TEST(Precipitation, TheSlabsLightIsTheBeamTheDiffuseLightAndTheSky) {
  const glm::vec3 sun(1.0f), sky(0.1f, 0.2f, 0.3f);
  const glm::vec3 clear = g::slab_medium_light(sun, 0.5f, sky, 0.3f, 0.85f, 0.0f, 0.0f, 0.0f);
  EXPECT_NEAR(clear.x, 0.3f + 0.1f, 1e-6f);
  EXPECT_NEAR(clear.z, 0.3f + 0.3f, 1e-6f);
  const glm::vec3 deep = g::slab_medium_light(sun, 0.5f, sky, 0.3f, 0.85f, 40.0f, 0.0f, 20.0f);
  const float down = 1.0f / (1.0f + 0.75f * 0.15f * 40.0f);
  EXPECT_NEAR(deep.x, down * 0.5f / (2.0f * 3.14159265f) + 0.1f / (1.0f + 0.75f * 0.15f * 20.0f),
              1e-5f);
}

// The particles drawn near the camera stand for the medium: as many of them per m^3 as carry
// its extinction. Rain at 5 mm/h: Marshall and Palmer's median volume diameter (1.26 mm), and
// the drops of that size that carry the integrated cross-section; snow at 1 mm/h: 85 flakes of
// 5 mm (twice their area each, the efficiency).
TEST(Precipitation, TheNearParticlesCarryTheMediumsExtinction) {
  const double d0_m = 3.67 / (4.1 * std::pow(5.0, -0.21)) * 1e-3;
  EXPECT_NEAR(g::precipitation_particle_m(g::PRECIPITATION_RAIN, 5.0f), d0_m, 1e-3 * d0_m);
  const double drops = marshall_palmer_sigma_t(5.0) / (0.25 * M_PI * d0_m * d0_m);
  EXPECT_NEAR(g::precipitation_particles_per_m3(g::PRECIPITATION_RAIN, 5.0f), drops, 0.01 * drops);
  EXPECT_NEAR(drops, 406.0, 5.0);
  EXPECT_NEAR(g::precipitation_particles_per_m3(g::PRECIPITATION_SNOW, 1.0f), 84.9, 0.5);
  // None without a rate.
  EXPECT_EQ(g::precipitation_particles_per_m3(g::PRECIPITATION_RAIN, 0.0f), 0.0f);
}

// A streak's opacity in a pixel: a drop of 1.25 mm streaked 9 cm, 5 m away in a 900-pixel,
// 60-degree image (6.4 mm a pixel) covers its cross-section over the streak's length and the
// pixel's width: 0.21%; half a metre away, over its own width (the pixel is narrower); a
// frozen flake larger than the pixel covers the disc's share of its square, pi / 4.
TEST(Precipitation, AStreaksOpacityIsItsShareOfThePixelAndTheShutter) {
  const float pixel_m = 5.0f * 2.0f * std::tan(glm::radians(30.0f)) / 900.0f;
  const double area = 0.25 * M_PI * 1.25e-3 * 1.25e-3;
  EXPECT_NEAR(g::precipitation_streak_opacity(1.25e-3f, 0.09f, pixel_m), area / (0.09125 * pixel_m),
              1e-6);
  EXPECT_NEAR(g::precipitation_streak_opacity(1.25e-3f, 0.09f, 0.1f * pixel_m),
              area / (0.09125 * 1.25e-3), 1e-6);
  EXPECT_NEAR(g::precipitation_streak_opacity(5e-3f, 0.0f, 1e-3f), 0.25 * M_PI, 1e-6);
}

// The wind that carries the particles near the camera: the base's by the 1/7 power law, the
// same everywhere above the base, and taken from 2 m below that.
TEST(Precipitation, TheWindNearTheGroundFollowsThePowerLaw) {
  const glm::vec2 base(12.0f, -4.0f);
  const glm::vec2 at_2m = g::precipitation_wind_at(base, 2.0f, 400.0f);
  EXPECT_NEAR(at_2m.x, 12.0 * std::pow(2.0 / 400.0, 1.0 / 7.0), 1e-4);
  EXPECT_NEAR(at_2m.y, -4.0 * std::pow(2.0 / 400.0, 1.0 / 7.0), 1e-4);
  EXPECT_EQ(g::precipitation_wind_at(base, 0.0f, 400.0f), at_2m);
  EXPECT_EQ(g::precipitation_wind_at(base, 900.0f, 400.0f), base);
}

}  // namespace
