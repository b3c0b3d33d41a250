// The weather state: read from a scene, applied to one, with oktas, winds by altitude and
// visibility in metres.
#include "weather/weather_state.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "nephele/error.h"
#include "nephele/scene_io.h"

namespace nephele::weather {
namespace {

std::string error_of(const WeatherState& state, Scene& scene) {
  try {
    apply_weather(state, scene);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(WeatherState, ReadingAndApplyingAPresetChangesNothingTheStateHolds) {
  for (const char* preset :
       {"default", "overcast", "cumulonimbus-storm", "stratus", "few", "cirrus", "sunset"}) {
    const Scene original = load_preset(preset);
    Scene scene = original;
    apply_weather(weather_state(original), scene);
    EXPECT_EQ(scene_to_toml(scene), scene_to_toml(original)) << preset;
  }
}

TEST(WeatherState, OktasGenusAndWindsByAltitude) {
  Scene scene{};
  WeatherState state = weather_state(scene);
  state.low = {Genus::Stratocumulus, -1.0f, 800.0f, 1800.0f, 6.0f, 0.6f, 0.0f};  // 6 oktas: broken
  state.sheet = {Genus::Cirrostratus, -1.0f, 9500.0f, 9500.0f, 2.0f, 0.0f, 0.5f};
  state.wind = {{0.0f, {2.0f, 0.0f}}, {1000.0f, {10.0f, 0.0f}}, {10000.0f, {40.0f, 10.0f}}};
  apply_weather(state, scene);
  // 6 oktas of stratocumulus: a coverage of 0.538 (the measured curve: 0.50 covers 59% of the
  // sky, 0.55 80%).
  EXPECT_NEAR(scene.clouds.coverage, 0.538f, 0.002f);
  EXPECT_FLOAT_EQ(scene.clouds.type, 0.25f);  // stratocumulus on clouds.type's scale
  EXPECT_FLOAT_EQ(scene.cirrus.type, 0.5f);
  // 2 oktas of cirrostratus: a quarter of the sky, between the measured 0.10 (0.228 of it) and
  // 0.12 (0.418).
  EXPECT_NEAR(scene.cirrus.coverage, 0.1023f, 0.0005f);
  EXPECT_FLOAT_EQ(scene.clouds.wind_mps.x, 8.4f);  // 800 m: 80% of the way from 2 to 10
  EXPECT_NEAR(scene.clouds.wind_shear_mps.x, 10.0f + 800.0f / 9000.0f * 30.0f - 8.4f, 1e-4f);
  EXPECT_NEAR(scene.cirrus.wind_mps.y, 9.5f / 10.0f * 10.0f - 1.0f / 9.0f * 0.5f, 0.1f);
  validate_scene(scene);
  EXPECT_NEAR(weather_state(scene).low.coverage_oktas, 6.0f, 1e-3f);
  EXPECT_EQ(weather_state(scene).low.genus, Genus::Stratocumulus);
  EXPECT_EQ(weather_state(scene).wind.size(), 4u);  // the layers' winds are one profile
  // A type between genera is kept, and named by the nearest genus.
  scene.clouds.type = 0.7f;
  EXPECT_EQ(weather_state(scene).low.genus, Genus::Cumulus);
  EXPECT_EQ(weather_state(scene).low.type, 0.7f);
}

// Oktas and coverage: the measured curves, inverted exactly; deep clouds cover the sky sooner;
// 8 oktas a closed deck.
TEST(WeatherState, OktasMapOntoTheMeasuredCoverage) {
  for (float type : {0.0f, 0.25f, 0.4f, 0.75f, 0.9f, 1.0f})
    for (float oktas = 0.5f; oktas < 8.0f; oktas += 0.5f) {
      const float coverage = coverage_for_oktas(oktas, type);
      EXPECT_NEAR(oktas_for_coverage(coverage, type), oktas, 1e-3f) << type << " " << oktas;
      EXPECT_GT(coverage, coverage_for_oktas(oktas - 0.5f, type));
    }
  // Cumulus: 1.5 oktas between the measured 0.35 (0.091 of the sky) and 0.40 (0.250).
  EXPECT_NEAR(coverage_for_oktas(1.5f, 0.75f), 0.3803f, 0.001f);
  EXPECT_NEAR(coverage_for_oktas(6.0f, 0.75f), 0.524f, 0.005f);
  EXPECT_LT(coverage_for_oktas(3.5f, 1.0f), coverage_for_oktas(3.5f, 0.75f) - 0.1f);
  EXPECT_EQ(coverage_for_oktas(8.0f, 0.0f), 1.0f);
  EXPECT_EQ(coverage_for_oktas(0.0f, 0.5f), 0.0f);
  EXPECT_EQ(oktas_for_coverage(1.0f, 0.5f), 8.0f);
  EXPECT_LT(oktas_for_coverage(0.99f, 0.5f), 8.0f);
  // The sheet's own curves: a cirrostratus veil covers the dome at a fifth of the coverage that
  // cirrus streaks or cirrocumulus cells need.
  for (float type : {0.0f, 0.25f, 0.5f, 0.8f, 1.0f})
    for (float oktas = 0.5f; oktas < 8.0f; oktas += 0.5f) {
      const float coverage = sheet_coverage_for_oktas(oktas, type);
      EXPECT_NEAR(oktas_for_sheet_coverage(coverage, type), oktas, 1e-3f) << type << " " << oktas;
      EXPECT_GT(coverage, sheet_coverage_for_oktas(oktas - 0.5f, type));
    }
  EXPECT_NEAR(sheet_coverage_for_oktas(6.0f, 0.5f), 0.1531f, 0.001f);  // BKN cirrostratus
  EXPECT_NEAR(sheet_coverage_for_oktas(4.0f, 0.0f), 0.4319f, 0.001f);  // SCT cirrus
  EXPECT_EQ(sheet_coverage_for_oktas(8.0f, 0.5f), 1.0f);
}

// Koschmieder: the visibility sets the haze's extinction, and reads back as itself.
TEST(WeatherState, VisibilityInMetresSetsTheHaze) {
  Scene scene{};
  WeatherState state = weather_state(scene);
  const float albedo =
      scene.atmosphere.mie_scattering_per_m / scene.atmosphere.mie_extinction_per_m;
  state.visibility_m = 10000.0f;  // 10 km: a hazy day
  apply_weather(state, scene);
  EXPECT_NEAR(scene.atmosphere.mie_extinction_per_m + scene.atmosphere.rayleigh_scattering_per_m.y,
              3.912e-4f, 1e-8f);
  EXPECT_NEAR(visibility_m(scene.atmosphere), 10000.0f, 1.0f);
  EXPECT_NEAR(scene.atmosphere.mie_scattering_per_m / scene.atmosphere.mie_extinction_per_m, albedo,
              1e-5f);
  validate_scene(scene);
  // The default haze: about 217 km; the clear air alone about 289 km.
  EXPECT_NEAR(visibility_m(Scene{}.atmosphere), 217000.0f, 2000.0f);
  EXPECT_NEAR(clear_air_visibility_m(Scene{}.atmosphere), 288540.0f, 100.0f);
}

// Rain in the state falls in the scene, and the visibility stays the one stated: the haze
// takes what the rain's own extinction leaves of it (a report's visibility is seen through
// the rain); where the rain alone hides more, the haze is none. Read back, the state is the
// same.
TEST(WeatherState, PrecipitationFallsAndTheVisibilityIncludesIt) {
  Scene scene{};
  WeatherState state = weather_state(scene);
  EXPECT_EQ(state.precipitation, PrecipitationKind::None);
  state.precipitation = PrecipitationKind::Rain;
  state.precipitation_mm_per_h = 10.0f;  // heavy rain: 5 km by itself
  state.visibility_m = 3000.0f;
  apply_weather(state, scene);
  EXPECT_EQ(scene.precipitation.kind, "rain");
  EXPECT_EQ(scene.precipitation.rate_mm_per_h, 10.0f);
  EXPECT_NEAR(visibility_m(scene), 3000.0f, 3.0f);
  EXPECT_GT(visibility_m(scene.atmosphere), 6000.0f);  // the haze alone: what the rain leaves
  validate_scene(scene);
  const WeatherState back = weather_state(scene);
  EXPECT_EQ(back.precipitation, PrecipitationKind::Rain);
  EXPECT_EQ(back.precipitation_mm_per_h, 10.0f);
  EXPECT_NEAR(back.visibility_m, 3000.0f, 3.0f);
  // Snow at 3 mm/h hides more than 2 km of visibility says: no haze left, the snow's own.
  state.precipitation = PrecipitationKind::Snow;
  state.precipitation_mm_per_h = 3.0f;
  state.visibility_m = 2000.0f;
  apply_weather(state, scene);
  EXPECT_EQ(scene.atmosphere.mie_extinction_per_m, 0.0f);
  EXPECT_LT(visibility_m(scene), 400.0f);
  // None: the rate falls to 0, the kind stays as it was.
  state.precipitation = PrecipitationKind::None;
  apply_weather(state, scene);
  EXPECT_EQ(scene.precipitation.rate_mm_per_h, 0.0f);
  EXPECT_NEAR(visibility_m(scene), 2000.0f, 2.0f);
}

// The wind as a report gives it, from where it blows in degrees at a speed in knots or m/s,
// and the visibility in metres, as [weather] keys: every layer's wind from the ground's by the
// 1/7 power law, the haze from the visibility; a direction without a speed, a speed without a
// direction or two speeds refused naming the key.
TEST(WeatherState, WindAndVisibilityKeysAsAReportGivesThem) {
  const Scene scene = parse_scene_toml(
      "[weather]\nwind_from_deg = 240\nwind_speed_kt = 15\nvisibility_m = 8000\n", "w.toml");
  validate_scene(scene);
  const float speed = 15.0f * 0.514444f * 1.93f;  // at 1 km and above
  // From the south-west, towards the north-east: east and north both positive, east larger.
  const glm::vec2 towards(std::sin(glm::radians(60.0f)), std::cos(glm::radians(60.0f)));
  EXPECT_NEAR(scene.clouds.wind_mps.x, speed * towards.x, 0.02f);
  EXPECT_NEAR(scene.clouds.wind_mps.y, speed * towards.y, 0.02f);
  EXPECT_NEAR(scene.high_clouds.wind_mps.x, speed * towards.x, 0.02f);
  EXPECT_NEAR(glm::length(scene.clouds.wind_shear_mps), 0.0f, 1e-4f);
  EXPECT_NEAR(visibility_m(scene), 8000.0f, 1.0f);
  const Scene mps =
      parse_scene_toml("[weather]\nwind_from_deg = 240\nwind_speed_mps = 7.71666\n", "w.toml");
  EXPECT_NEAR(glm::distance(mps.clouds.wind_mps, scene.clouds.wind_mps), 0.0f, 1e-3f);
  const auto error_of = [](const std::string& toml) -> std::string {
    try {
      parse_scene_toml(toml, "w.toml");
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(error_of("[weather]\nwind_from_deg = 240\n"),
            "w.toml:2:17: weather.wind_from_deg = 240: needs a speed, weather.wind_speed_kt or "
            "weather.wind_speed_mps");
  EXPECT_EQ(error_of("[weather]\nwind_speed_kt = 15\n"),
            "w.toml:2:17: weather.wind_speed_kt = 15: needs the direction it blows from, "
            "weather.wind_from_deg");
  EXPECT_EQ(error_of("[weather]\nwind_from_deg = 240\nwind_speed_kt = 15\nwind_speed_mps = 7\n"),
            "w.toml:3:17: weather.wind_speed_kt = 15: give the speed once, in knots or in m/s "
            "(weather.wind_speed_mps = 7)");
  EXPECT_NE(error_of("[weather]\nvisibility_m = 100\n").find("weather.visibility_m = 100"),
            std::string::npos);
}

TEST(WeatherState, WhatALayerCannotDrawIsOneLineAndChangesNothing) {
  const Scene original{};
  Scene scene = original;
  WeatherState state = weather_state(scene);
  state.low.genus = Genus::Cirrus;
  EXPECT_EQ(error_of(state, scene),
            "weather.low.genus = cirrus: this layer draws stratus, stratocumulus, altocumulus, "
            "cumulus or cumulonimbus");
  state = weather_state(scene);
  state.low.coverage_oktas = 9.0f;
  EXPECT_EQ(error_of(state, scene), "weather.low.coverage_oktas = 9: must be in [0, 8]");
  state = weather_state(scene);
  state.visibility_m = 100.0f;
  EXPECT_NE(error_of(state, scene).find("weather.visibility_m = 100: must be in [400, "),
            std::string::npos);
  state = weather_state(scene);
  state.wind = {{1000.0f, {1.0f, 0.0f}}, {500.0f, {2.0f, 0.0f}}};
  EXPECT_EQ(
      error_of(state, scene),
      "weather.wind[1].altitude_m = 500: must be above wind[0].altitude_m (1000): levels go up");
  EXPECT_EQ(scene_to_toml(scene), scene_to_toml(original));
}

}  // namespace
}  // namespace nephele::weather
