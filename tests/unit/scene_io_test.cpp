// Scene files, presets, validation, TOML round trip.
#include "nephele/scene_io.h"

#include <gtest/gtest.h>

#include <cctype>
#include <cstdint>

#include <algorithm>
#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "nephele/camera_path.h"
#include "nephele/error.h"
#include "nephele/image.h"
#include "nephele/sky.h"
#include <glm/geometric.hpp>
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

namespace nephele {
namespace {

namespace fs = std::filesystem;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// The message of the InputError `fn` throws; fails the test when it throws nothing.
std::string input_error(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const InputError& error) {
    return error.what();
  }
  ADD_FAILURE() << "no InputError thrown";
  return "";
}

std::string parse_error(const std::string& toml) {
  return input_error([&] { parse_scene_toml(toml, "scene.toml"); });
}

std::string validate_error(const std::function<void(Scene&)>& change) {
  Scene scene;
  change(scene);
  return input_error([&] { validate_scene(scene); });
}

// Bit-exact comparison of every field (NaN-free scenes only).
void expect_same_scene(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.camera.position_m, b.camera.position_m);
  EXPECT_EQ(a.camera.view_dir, b.camera.view_dir);
  EXPECT_EQ(a.camera.fov_deg, b.camera.fov_deg);
  EXPECT_EQ(a.camera.roll_deg, b.camera.roll_deg);
  EXPECT_EQ(a.sun.direction, b.sun.direction);
  EXPECT_EQ(a.sun.illuminance_lux, b.sun.illuminance_lux);
  EXPECT_EQ(a.sun.disk_angular_radius_deg, b.sun.disk_angular_radius_deg);
  EXPECT_EQ(a.sun.from_time, b.sun.from_time);
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.location.lat_deg, b.location.lat_deg);
  EXPECT_EQ(a.location.lon_deg, b.location.lon_deg);
  EXPECT_EQ(a.location.altitude_m, b.location.altitude_m);
  const AtmosphereParams &aa = a.atmosphere, &ba = b.atmosphere;
  EXPECT_EQ(aa.planet_radius_km, ba.planet_radius_km);
  EXPECT_EQ(aa.atmosphere_height_km, ba.atmosphere_height_km);
  EXPECT_EQ(aa.rayleigh_scattering_per_m, ba.rayleigh_scattering_per_m);
  EXPECT_EQ(aa.rayleigh_scale_height_m, ba.rayleigh_scale_height_m);
  EXPECT_EQ(aa.mie_scattering_per_m, ba.mie_scattering_per_m);
  EXPECT_EQ(aa.mie_extinction_per_m, ba.mie_extinction_per_m);
  EXPECT_EQ(aa.mie_scale_height_m, ba.mie_scale_height_m);
  EXPECT_EQ(aa.mie_g, ba.mie_g);
  EXPECT_EQ(aa.view_samples, ba.view_samples);
  EXPECT_EQ(aa.ozone_absorption_per_m, ba.ozone_absorption_per_m);
  EXPECT_EQ(aa.ground_albedo, ba.ground_albedo);
  EXPECT_EQ(aa.model, ba.model);
  EXPECT_EQ(aa.turbidity, ba.turbidity);
  const CloudParams &ac = a.clouds, &bc = b.clouds;
  EXPECT_EQ(ac.bottom_altitude_m, bc.bottom_altitude_m);
  EXPECT_EQ(ac.top_altitude_m, bc.top_altitude_m);
  EXPECT_EQ(ac.coverage, bc.coverage);
  EXPECT_EQ(ac.density, bc.density);
  EXPECT_EQ(ac.extinction_per_m, bc.extinction_per_m);
  EXPECT_EQ(ac.attenuation, bc.attenuation);
  EXPECT_EQ(ac.light_attenuation, bc.light_attenuation);
  EXPECT_EQ(ac.albedo, bc.albedo);
  EXPECT_EQ(ac.phase_g_forward, bc.phase_g_forward);
  EXPECT_EQ(ac.phase_g_backward, bc.phase_g_backward);
  EXPECT_EQ(ac.phase_lobe_weight, bc.phase_lobe_weight);
  EXPECT_EQ(ac.powder_strength, bc.powder_strength);
  EXPECT_EQ(ac.ambient_strength, bc.ambient_strength);
  EXPECT_EQ(ac.wind_mps, bc.wind_mps);
  EXPECT_EQ(ac.wind_shear_mps, bc.wind_shear_mps);
  EXPECT_EQ(ac.wind_skew_s, bc.wind_skew_s);
  EXPECT_EQ(ac.detail_drift_mps, bc.detail_drift_mps);
  EXPECT_EQ(ac.curl_distortion_m, bc.curl_distortion_m);
  EXPECT_EQ(ac.flow_speed_mps, bc.flow_speed_mps);
  EXPECT_EQ(ac.flow_cycle_s, bc.flow_cycle_s);
  const HighCloudParams &ah = a.high_clouds, &bh = b.high_clouds;
  EXPECT_EQ(ah.bottom_altitude_m, bh.bottom_altitude_m);
  EXPECT_EQ(ah.top_altitude_m, bh.top_altitude_m);
  EXPECT_EQ(ah.coverage, bh.coverage);
  EXPECT_EQ(ah.type, bh.type);
  EXPECT_EQ(ah.density, bh.density);
  EXPECT_EQ(ah.wind_mps, bh.wind_mps);
  EXPECT_EQ(ac.base_noise_period_m, bc.base_noise_period_m);
  EXPECT_EQ(ac.detail_noise_period_m, bc.detail_noise_period_m);
  EXPECT_EQ(ac.detail_erosion, bc.detail_erosion);
  EXPECT_EQ(ac.weather_period_m, bc.weather_period_m);
  EXPECT_EQ(ac.weather_map, bc.weather_map);
  EXPECT_EQ(a.quality.mode, b.quality.mode);
  EXPECT_EQ(a.quality.primary_steps, b.quality.primary_steps);
  EXPECT_EQ(a.quality.light_steps, b.quality.light_steps);
  EXPECT_EQ(a.quality.voxel_march, b.quality.voxel_march);
  EXPECT_EQ(a.quality.voxel_shadow, b.quality.voxel_shadow);
  EXPECT_EQ(a.quality.sdf_light_tangent, b.quality.sdf_light_tangent);
  ASSERT_EQ(a.voxel_clouds.size(), b.voxel_clouds.size());
  for (size_t i = 0; i < a.voxel_clouds.size(); ++i) {
    SCOPED_TRACE("voxel cloud " + std::to_string(i));
    const VoxelCloudParams &av = a.voxel_clouds[i], &bv = b.voxel_clouds[i];
    EXPECT_EQ(av.file, bv.file);
    EXPECT_EQ(av.preset, bv.preset);
    EXPECT_EQ(av.seed, bv.seed);
    EXPECT_EQ(av.position_m, bv.position_m);
    EXPECT_EQ(av.scale, bv.scale);
    EXPECT_EQ(av.rotation_deg, bv.rotation_deg);
    EXPECT_EQ(av.density, bv.density);
    EXPECT_EQ(av.follow_wind, bv.follow_wind);
    EXPECT_EQ(av.wind_mps, bv.wind_mps);
    EXPECT_EQ(av.resolution, bv.resolution);
  }
  EXPECT_EQ(a.output.width, b.output.width);
  EXPECT_EQ(a.output.height, b.output.height);
  EXPECT_EQ(a.output.ev100, b.output.ev100);
  EXPECT_EQ(a.output.auto_exposure, b.output.auto_exposure);
  EXPECT_EQ(a.output.ev100_min, b.output.ev100_min);
  EXPECT_EQ(a.output.ev100_max, b.output.ev100_max);
  EXPECT_EQ(a.output.exposure_compensation_ev, b.output.exposure_compensation_ev);
  EXPECT_EQ(a.output.adaptation_ev_per_s, b.output.adaptation_ev_per_s);
  EXPECT_EQ(a.camera.horizontal_fov_deg, b.camera.horizontal_fov_deg);
  EXPECT_EQ(a.camera.focal_length_mm, b.camera.focal_length_mm);
  EXPECT_EQ(a.camera.sensor_width_mm, b.camera.sensor_width_mm);
  EXPECT_EQ(a.time_s, b.time_s);
  EXPECT_EQ(a.noise_seed, b.noise_seed);
}

void expect_near(const glm::vec3& actual, const glm::vec3& expected) {
  EXPECT_NEAR(actual.x, expected.x, 1e-6f);
  EXPECT_NEAR(actual.y, expected.y, 1e-6f);
  EXPECT_NEAR(actual.z, expected.z, 1e-6f);
}

// A scene in which every field differs from the defaults, with awkward float values.
Scene unusual_scene() {
  Scene s;
  s.camera = {{-12.5f, 3e4f, 123.456f}, {0.1f, -0.2f, 0.3f}, 33.3f, 0.0f, 0.0f, 24.25f, -47.125f};
  s.sun = {{-0.3f, 0.4f, 1e-7f}, 7.25f, 0.55f, true};
  s.time = "1999-12-31T23:59:59.5-03:30";
  s.location = {-33.8688f, 151.2093f, 58.0f};
  s.atmosphere = {SkyModel::Preetham, 6371.5f, 80.0f, {1e-6f, 2.5e-5f, 3.3333e-5f}, 7994.0f,
                  2.1e-5f, 2.3e-5f, 1234.5f, 0.76f, {1.5e-6f, 2e-6f, 1e-7f}, 22000.5f, 14000.0f,
                  0.27f, 3.25f, 12};
  s.clouds = {CloudModel::Blinn,
              800.0f,
              5321.25f,
              0.123f,
              0.3125f,
              0.4375f,
              0.987f,
              0.0421f,
              1.7f,
              0.6f,
              0.93f,
              0.66f,
              -0.41f,
              0.33f,
              0.25f,
              1.9f,
              {-3.5f, 12.0f},
              {1.5f, -0.25f},
              75.5f,
              {4.0f, -5.0f, 0.75f},
              33.25f,
              2.5f,
              45.5f,
              7000.5f,
              850.0f,
              0.12f,
              35000.0f,
              1234.5f,
              "/maps/\"quoted\" \\ weather.png"};
  s.high_clouds = {6100.5f, 7300.25f, 0.35f, 0.625f, 0.45f, {17.5f, -2.25f}};
  s.quality = {MarchMode::Baseline, 64, 4};
  s.quality.voxel_march = VoxelMarch::Plain;
  s.quality.voxel_shadow = VoxelShadow::SdfCone;
  s.quality.sdf_light_tangent = 0.3333f;
  s.voxel_clouds.resize(2);
  s.voxel_clouds[0].file = "/clouds/\"big\" one.NVDB";
  s.voxel_clouds[0].seed = 77;  // unused with a file, but kept
  s.voxel_clouds[0].position_m = {-1234.5f, 5e6f, -12.25f};
  s.voxel_clouds[0].follow_wind = false;
  s.voxel_clouds[0].wind_mps = {-3.25f, 1e-3f};
  s.voxel_clouds[1].preset = "cumulonimbus";
  s.voxel_clouds[1].seed = 4294967295u;
  s.voxel_clouds[1].scale = 0.1f;
  s.voxel_clouds[1].rotation_deg = -33.3f;
  s.voxel_clouds[1].density = 2.5f;
  s.voxel_clouds[1].resolution = 200;
  s.output = {1920, 1080, false, 9.25f, -3.5f, 16.5f, 0.75f, 3.0f};
  s.time_s = 12.75f;
  s.noise_seed = 4294967295u;
  return s;
}

// ---------------------------------------------------------------- defaults and presets

TEST(SceneDefaults, Validate) {
  EXPECT_NO_THROW(validate_scene(Scene{}));
}

TEST(SceneDefaults, MarchModeNamesRoundTrip) {
  EXPECT_STREQ(to_string(MarchMode::Default), "default");
  EXPECT_STREQ(to_string(MarchMode::Baseline), "baseline");
  EXPECT_EQ(parse_march_mode("default"), MarchMode::Default);
  EXPECT_EQ(parse_march_mode("baseline"), MarchMode::Baseline);
  EXPECT_EQ(parse_march_mode("Baseline"), std::nullopt);
  EXPECT_EQ(parse_march_mode(""), std::nullopt);
}

TEST(ScenePresets, AllPresentLoadAndValidate) {
  std::vector<std::string> names = preset_names();
  for (const char* expected :
       {"default", "seed-baseline", "overcast", "sunset", "above-clouds", "inside-cloud"})
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
  EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    Scene scene;
    ASSERT_NO_THROW(scene = load_preset(name));
    EXPECT_NO_THROW(validate_scene(scene));
  }
}

TEST(ScenePresets, EachStartsWithADescriptiveComment) {
  for (const std::string& name : preset_names()) {
    std::ifstream file(std::string(NEPHELE_SOURCE_DIR) + "/presets/" + name + ".toml");
    std::string first_line;
    std::getline(file, first_line);
    EXPECT_TRUE(first_line.starts_with("# ") && first_line.size() > 20) << name;
  }
}

TEST(ScenePresets, UnknownNameListsAvailable) {
  std::string message = input_error([] { load_preset("foo"); });
  EXPECT_NE(message.find("'foo'"), std::string::npos) << message;
  EXPECT_NE(message.find("unknown preset"), std::string::npos) << message;
  EXPECT_NE(message.find("default, "), std::string::npos) << message;
  EXPECT_NE(message.find("overcast"), std::string::npos) << message;
}

// Loose bounds on purpose: the values get tuned by eye, the character must stay.
TEST(ScenePresets, ShowWhatTheirNamesSay) {
  Scene fair = load_preset("default");
  SunAngles sun = sun_angles_from_direction(fair.sun.direction);
  EXPECT_GT(sun.elevation_deg, 20.0);
  EXPECT_LT(sun.elevation_deg, 50.0);
  // Sun behind the camera: horizontal sun and view directions point apart.
  glm::vec3 view = fair.camera.view_dir;
  EXPECT_LT(view.x * fair.sun.direction.x + view.y * fair.sun.direction.y, 0.0f);
  EXPECT_LT(fair.camera.position_m.z, fair.clouds.bottom_altitude_m);

  Scene baseline = load_preset("seed-baseline");
  EXPECT_EQ(baseline.quality.mode, MarchMode::Baseline);
  EXPECT_EQ(baseline.clouds.phase_g_backward, -baseline.clouds.phase_g_forward);

  Scene overcast = load_preset("overcast");
  EXPECT_GE(overcast.clouds.coverage, fair.clouds.coverage + 0.2f);
  EXPECT_GT(overcast.clouds.top_altitude_m - overcast.clouds.bottom_altitude_m,
            fair.clouds.top_altitude_m - fair.clouds.bottom_altitude_m);

  Scene sunset = load_preset("sunset");
  SunAngles low = sun_angles_from_direction(sunset.sun.direction);
  EXPECT_GT(low.elevation_deg, 0.0);
  EXPECT_LT(low.elevation_deg, 10.0);
  // Camera looks towards the sun's azimuth.
  glm::vec3 look = sunset.camera.view_dir;
  EXPECT_GT(look.x * sunset.sun.direction.x + look.y * sunset.sun.direction.y, 0.0f);

  Scene above = load_preset("above-clouds");
  EXPECT_GT(above.camera.position_m.z, above.clouds.top_altitude_m);
  EXPECT_LT(above.camera.view_dir.z, 0.0f);

  Scene inside = load_preset("inside-cloud");
  EXPECT_GT(inside.camera.position_m.z, inside.clouds.bottom_altitude_m);
  EXPECT_LT(inside.camera.position_m.z, inside.clouds.top_altitude_m);
}

// ---------------------------------------------------------------- parsing

TEST(SceneToml, EmptyTextGivesDefaults) {
  expect_same_scene(parse_scene_toml("", "scene.toml"), Scene{});
}

TEST(SceneToml, AppliesValuesOnTopOfDefaults) {
  Scene scene = parse_scene_toml(R"(
time_s = 3.5
noise_seed = 42
[camera]
position_m = [10, 20.5, 30]
fov_deg = 50
[clouds]
coverage = 0.8
wind_mps = [-1.5, 4]
[quality]
mode = "baseline"
light_steps = 12
[output]
width = 640
)",
                                 "scene.toml");
  EXPECT_EQ(scene.time_s, 3.5f);
  EXPECT_EQ(scene.noise_seed, 42u);
  EXPECT_EQ(scene.camera.position_m, glm::vec3(10.0f, 20.5f, 30.0f));
  EXPECT_EQ(scene.camera.fov_deg, 50.0f);  // an integer where a float is expected
  EXPECT_EQ(scene.clouds.coverage, 0.8f);
  EXPECT_EQ(scene.clouds.wind_mps, glm::vec2(-1.5f, 4.0f));
  EXPECT_EQ(scene.quality.mode, MarchMode::Baseline);
  EXPECT_EQ(scene.quality.light_steps, 12);
  EXPECT_EQ(scene.output.width, 640);
  // Untouched fields keep the defaults.
  Scene defaults;
  EXPECT_EQ(scene.output.height, defaults.output.height);
  EXPECT_EQ(scene.clouds.density, defaults.clouds.density);
  EXPECT_EQ(scene.camera.view_dir, defaults.camera.view_dir);
}

TEST(SceneToml, InlineAndDottedTablesWork) {
  Scene scene = parse_scene_toml("clouds.coverage = 0.2\noutput = { height = 300 }\n", "s.toml");
  EXPECT_EQ(scene.clouds.coverage, 0.2f);
  EXPECT_EQ(scene.output.height, 300);
}

TEST(SceneToml, PresetIsTheStartingPointWhereverItIsWritten) {
  // `preset` after a table header would belong to the table, so it sits first; the values
  // below it must win over the preset's even though toml++ sorts keys.
  Scene scene = parse_scene_toml("preset = \"overcast\"\n[clouds]\ncoverage = 0.3\n", "scene.toml");
  Scene overcast = load_preset("overcast");
  EXPECT_EQ(scene.clouds.coverage, 0.3f);
  EXPECT_EQ(scene.clouds.bottom_altitude_m, overcast.clouds.bottom_altitude_m);
  EXPECT_NE(overcast.clouds.bottom_altitude_m, Scene{}.clouds.bottom_altitude_m);
}

TEST(SceneToml, UnknownPresetIsAnError) {
  std::string message = parse_error("preset = \"nope\"\n");
  EXPECT_NE(message.find("preset = \"nope\": unknown preset (available: "), std::string::npos)
      << message;
}

TEST(SceneToml, UnknownKeyListsAllowedKeys) {
  std::string message = parse_error("[clouds]\ncovrage = 0.5\n");
  EXPECT_EQ(message.rfind("scene.toml:2:1: unknown key 'clouds.covrage' (allowed in [clouds]: model, "
                          "bottom_altitude_m, top_altitude_m, coverage",
                          0),
            0u)
      << message;
  EXPECT_NE(message.find("weather_map, two_stream_light)"), std::string::npos) << message;
}

TEST(SceneToml, UnknownTopLevelKeyAndTable) {
  std::string message = parse_error("tme_s = 1\n");
  EXPECT_NE(message.find("unknown key 'tme_s' (allowed at the top level: time, time_s, noise_seed, "
                         "preset, [location], [camera]"),
            std::string::npos)
      << message;
  message = parse_error("[cloud]\ncoverage = 0.5\n");
  EXPECT_NE(message.find("unknown key 'cloud'"), std::string::npos) << message;
  message = parse_error("[clouds.extra]\nx = 1\n");
  EXPECT_NE(message.find("unknown key 'clouds.extra'"), std::string::npos) << message;
}

TEST(SceneToml, WrongTypesNameKeyAndValue) {
  EXPECT_EQ(parse_error("[clouds]\ncoverage = \"abc\"\n"),
            "scene.toml:2:12: clouds.coverage = \"abc\": expected a number");
  EXPECT_NE(parse_error("[camera]\nview_dir = [1, 2]\n")
                .find("camera.view_dir = [1, 2]: expected an array of 3 numbers"),
            std::string::npos);
  EXPECT_NE(parse_error("[camera]\nview_dir = [1, 2, \"x\"]\n")
                .find("camera.view_dir = [1, 2, \"x\"]: expected an array of 3 numbers"),
            std::string::npos);
  EXPECT_NE(parse_error("[clouds]\nwind_mps = 3\n")
                .find("clouds.wind_mps = 3: expected an array of 2 numbers"),
            std::string::npos);
  EXPECT_NE(
      parse_error("[output]\nwidth = 900.5\n").find("output.width = 900.5: expected an integer"),
      std::string::npos);
  EXPECT_NE(parse_error("[output]\nwidth = 3000000000\n").find("output.width = 3000000000"),
            std::string::npos);
  EXPECT_NE(parse_error("noise_seed = -1\n")
                .find("noise_seed = -1: expected an integer in [0, 4294967295]"),
            std::string::npos);
  EXPECT_NE(parse_error("[quality]\nmode = \"fast\"\n")
                .find("quality.mode = \"fast\": expected \"default\" or \"baseline\""),
            std::string::npos);
  EXPECT_NE(
      parse_error("[clouds]\nweather_map = 5\n").find("clouds.weather_map = 5: expected a string"),
      std::string::npos);
  EXPECT_NE(parse_error("camera = 5\n").find("camera = 5: expected a table [camera]"),
            std::string::npos);
  EXPECT_NE(parse_error("time_s = true\n").find("time_s = true: expected a number"),
            std::string::npos);
}

TEST(SceneToml, MalformedTomlGivesPosition) {
  std::string message = parse_error("time_s = 1\n\n[camera\nfov_deg = 3\n");
  EXPECT_EQ(message.rfind("scene.toml:3:", 0), 0u) << message;
  EXPECT_NE(message.find("malformed TOML: "), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(SceneToml, AltitudeSetsPositionUp) {
  Scene scene = parse_scene_toml("[camera]\naltitude_m = 250\n", "scene.toml");
  EXPECT_EQ(scene.camera.position_m, glm::vec3(0.0f, 0.0f, 250.0f));
  std::string message = parse_error("[camera]\nposition_m = [0, 0, 5]\naltitude_m = 250\n");
  EXPECT_NE(message.find("camera.altitude_m = 250: camera.position_m is given too"),
            std::string::npos)
      << message;
}

TEST(SceneSunAngles, ConvertToDirections) {
  expect_near(sun_direction_from_angles(90.0, 0.0), {0.0f, 0.0f, 1.0f});
  expect_near(sun_direction_from_angles(90.0, 123.0), {0.0f, 0.0f, 1.0f});
  expect_near(sun_direction_from_angles(0.0, 90.0), {1.0f, 0.0f, 0.0f});  // east
  expect_near(sun_direction_from_angles(0.0, 0.0), {0.0f, 1.0f, 0.0f});   // north
  expect_near(sun_direction_from_angles(0.0, 270.0), {-1.0f, 0.0f, 0.0f});
  expect_near(sun_direction_from_angles(30.0, 180.0),
              {0.0f, -std::sqrt(3.0f) / 2.0f, 0.5f});  // south, 30 deg up
  expect_near(sun_direction_from_angles(45.0, 45.0), {0.5f, 0.5f, std::sqrt(0.5f)});
  // Exact at the cardinal points, not merely close.
  EXPECT_EQ(sun_direction_from_angles(90.0, 0.0), glm::vec3(0.0f, 0.0f, 1.0f));
  EXPECT_EQ(sun_direction_from_angles(0.0, 90.0), glm::vec3(1.0f, 0.0f, 0.0f));
}

TEST(SceneSunAngles, InverseConversion) {
  for (double elevation : {-30.0, 0.0, 4.0, 35.0, 89.0})
    for (double azimuth : {0.0, 10.0, 90.0, 150.0, 270.0, 359.0}) {
      SunAngles angles =
          sun_angles_from_direction(3.0f * sun_direction_from_angles(elevation, azimuth));
      EXPECT_NEAR(angles.elevation_deg, elevation, 1e-4);
      EXPECT_NEAR(angles.azimuth_deg, azimuth, 1e-4);
    }
}

TEST(SceneToml, SunAnglesReplaceDirection) {
  Scene scene = parse_scene_toml("[sun]\nelevation_deg = 0\nazimuth_deg = 90\n", "scene.toml");
  expect_near(scene.sun.direction, {1.0f, 0.0f, 0.0f});
  scene = parse_scene_toml("[sun]\nelevation_deg = 90\n", "scene.toml");
  expect_near(scene.sun.direction, {0.0f, 0.0f, 1.0f});
  // Only the azimuth: the default direction's elevation is kept.
  scene = parse_scene_toml("[sun]\nazimuth_deg = 90\n", "scene.toml");
  double default_elevation = sun_angles_from_direction(Scene{}.sun.direction).elevation_deg;
  SunAngles angles = sun_angles_from_direction(scene.sun.direction);
  EXPECT_NEAR(angles.elevation_deg, default_elevation, 1e-4);
  EXPECT_NEAR(angles.azimuth_deg, 90.0, 1e-4);
}

// clouds.lighting chooses the clouds' lighting; the old switch two_stream_light reads as it,
// and both together, or a switch that is not true or false, are refused naming the new key.
TEST(SceneToml, LightingReplacesTheOldTwoStreamSwitch) {
  EXPECT_EQ(Scene{}.clouds.lighting, "diffusion");
  EXPECT_EQ(parse_scene_toml("[clouds]\nlighting = \"two-stream\"\n", "s.toml").clouds.lighting,
            "two-stream");
  EXPECT_EQ(parse_scene_toml("[clouds]\ntwo_stream_light = true\n", "s.toml").clouds.lighting,
            "two-stream");
  EXPECT_EQ(parse_scene_toml("[clouds]\ntwo_stream_light = false\n", "s.toml").clouds.lighting,
            "seed");
  EXPECT_NE(parse_error("[clouds]\ntwo_stream_light = true\nlighting = \"seed\"\n")
                .find("clouds.two_stream_light and clouds.lighting are both given; give lighting"),
            std::string::npos);
  EXPECT_NE(parse_error("[clouds]\ntwo_stream_light = 1\n")
                .find("clouds.two_stream_light = 1: expected true or false (the old switch; "
                      "clouds.lighting"),
            std::string::npos);
  EXPECT_NE(validate_error([](Scene& s) {
              s.clouds.lighting = "octaves";
            }).find("clouds.lighting = \"octaves\": must be \"seed\", \"two-stream\" or "
                    "\"diffusion\""),
            std::string::npos);
  // Written back as the new key only.
  Scene s;
  s.clouds.lighting = "two-stream";
  const std::string text = scene_to_toml(s);
  EXPECT_NE(text.find("lighting = \"two-stream\""), std::string::npos);
  EXPECT_EQ(text.find("\ntwo_stream_light"), std::string::npos);
  EXPECT_EQ(parse_scene_toml(text, "s.toml").clouds.lighting, "two-stream");
}

TEST(SceneToml, SunFormsConflictAndAnglesAreChecked) {
  std::string message = parse_error("[sun]\ndirection = [0, 1, 1]\nelevation_deg = 30\n");
  EXPECT_NE(message.find("sun.direction and sun.elevation_deg/azimuth_deg are both given"),
            std::string::npos)
      << message;
  message = parse_error("[sun]\nelevation_deg = 95\n");
  EXPECT_NE(message.find("sun.elevation_deg = 95: must be in [-90, 90]"), std::string::npos)
      << message;
  message = parse_error("[sun]\nazimuth_deg = nan\n");
  EXPECT_NE(message.find("sun.azimuth_deg = nan: must be finite"), std::string::npos) << message;
}

TEST(SceneToml, RelativeWeatherMapResolvesAgainstBaseDir) {
  std::string toml = "[clouds]\nweather_map = \"maps/w.png\"\n";
  EXPECT_EQ(parse_scene_toml(toml, "s.toml", "/data/scenes").clouds.weather_map,
            "/data/scenes/maps/w.png");
  EXPECT_EQ(parse_scene_toml(toml, "s.toml", "").clouds.weather_map, "maps/w.png");
  EXPECT_EQ(parse_scene_toml("[clouds]\nweather_map = \"/abs/w.png\"\n", "s.toml", "/data")
                .clouds.weather_map,
            "/abs/w.png");
  EXPECT_EQ(
      parse_scene_toml("[clouds]\nweather_map = \"\"\n", "s.toml", "/data").clouds.weather_map, "");
}

// ---------------------------------------------------------------- voxel clouds and their modes

TEST(SceneVoxelClouds, NoneByDefault) {
  EXPECT_TRUE(Scene{}.voxel_clouds.empty());
  EXPECT_TRUE(parse_scene_toml("", "scene.toml").voxel_clouds.empty());
  // Only the voxel presets have them (two each: the generated and the mesh-baked cumulus).
  for (const std::string& name : preset_names())
    EXPECT_EQ(load_preset(name).voxel_clouds.size(), name.rfind("voxel-", 0) == 0 ? 2u : 0u) << name;
}

TEST(SceneVoxelClouds, ReadEveryKeyAndBothPositionForms) {
  // The location comes after the clouds: lat/lon are converted with the file's final one.
  const Scene scene = parse_scene_toml(
      "[[voxel_clouds]]\n"
      "preset = \"cumulus-congestus\"\nseed = 7\nposition_m = [100, -200.5, 1200]\n"
      "scale = 2.5\nrotation_deg = -45\ndensity = 3\nfollow_wind = false\n"
      "wind_mps = [4, -5]\nresolution = 64\n"
      "[[voxel_clouds]]\n"
      "file = \"/abs/c.vdb\"\nlat_deg = 45.01\nlon_deg = 7.02\naltitude_m = 1500\n"
      "[location]\nlat_deg = 45.0\nlon_deg = 7.0\n"
      "[atmosphere]\nplanet_radius_km = 6371\n",
      "scene.toml");
  ASSERT_EQ(scene.voxel_clouds.size(), 2u);
  const VoxelCloudParams& a = scene.voxel_clouds[0];
  EXPECT_EQ(a.preset, "cumulus-congestus");
  EXPECT_EQ(a.file, "");
  EXPECT_EQ(a.seed, 7u);
  EXPECT_EQ(a.position_m, glm::vec3(100.0f, -200.5f, 1200.0f));
  EXPECT_EQ(a.scale, 2.5f);
  EXPECT_EQ(a.rotation_deg, -45.0f);
  EXPECT_EQ(a.density, 3.0f);
  EXPECT_FALSE(a.follow_wind);
  EXPECT_EQ(a.wind_mps, glm::vec2(4.0f, -5.0f));
  EXPECT_EQ(a.resolution, 64);
  const VoxelCloudParams& b = scene.voxel_clouds[1];
  EXPECT_EQ(b.file, "/abs/c.vdb");
  EXPECT_EQ(b.position_m, glm::vec3(enu_from_lat_lon(scene, 45.01, 7.02, 1500.0)));
  EXPECT_NEAR(b.position_m.y, 1112.0f, 2.0f);  // 0.01 deg of latitude north
  EXPECT_GT(b.position_m.x, 1500.0f);          // 0.02 deg of longitude east at 45 deg
  EXPECT_EQ(b.scale, 1.0f);                    // the rest at their defaults
  EXPECT_TRUE(b.follow_wind);
  EXPECT_EQ(b.resolution, 128);
  Scene generated_only = scene;  // the file does not exist
  generated_only.voxel_clouds.resize(1);
  EXPECT_NO_THROW(validate_scene(generated_only));
}

TEST(SceneVoxelClouds, QualityModes) {
  Scene scene = parse_scene_toml(
      "[quality]\nvoxel_march = \"plain\"\nvoxel_shadow = \"sdf-cone\"\nsdf_light_tangent = 0.5\n",
      "scene.toml");
  EXPECT_EQ(scene.quality.voxel_march, VoxelMarch::Plain);
  EXPECT_EQ(scene.quality.voxel_shadow, VoxelShadow::SdfCone);
  EXPECT_EQ(scene.quality.sdf_light_tangent, 0.5f);
  EXPECT_EQ(Scene{}.quality.voxel_march, VoxelMarch::ThreePhase);
  EXPECT_EQ(Scene{}.quality.voxel_shadow, VoxelShadow::LightMarch);
  EXPECT_EQ(
      parse_error("[quality]\nvoxel_march = \"fast\"\n"),
      "scene.toml:2:15: quality.voxel_march = \"fast\": expected \"plain\" or \"three-phase\"");
  EXPECT_EQ(parse_error("[quality]\nvoxel_shadow = 1\n"),
            "scene.toml:2:16: quality.voxel_shadow = 1: expected \"march\" or \"sdf-cone\"");
  for (VoxelMarch m : {VoxelMarch::Plain, VoxelMarch::ThreePhase})
    EXPECT_EQ(parse_voxel_march(to_string(m)), m);
  for (VoxelShadow m : {VoxelShadow::LightMarch, VoxelShadow::SdfCone})
    EXPECT_EQ(parse_voxel_shadow(to_string(m)), m);
  EXPECT_EQ(parse_voxel_march("three_phase"), std::nullopt);
  EXPECT_EQ(parse_voxel_shadow("sdf"), std::nullopt);
}

TEST(SceneVoxelClouds, ReadingErrorsNameTheCloudAndKey) {
  EXPECT_EQ(parse_error("[[voxel_clouds]]\npreset = \"cumulus\"\n[[voxel_clouds]]\nfoo = 1\n")
                .rfind("scene.toml:4:1: unknown key 'voxel_clouds[1].foo' (allowed in "
                       "[[voxel_clouds]]: file, preset, seed, position_m, scale, rotation_deg, "
                       "density, follow_wind, wind_mps, resolution, lat_deg, lon_deg, altitude_m)",
                       0),
            0u);
  EXPECT_EQ(parse_error("[[voxel_clouds]]\ndensity = \"x\"\n"),
            "scene.toml:2:11: voxel_clouds[0].density = \"x\": expected a number");
  EXPECT_EQ(parse_error("[[voxel_clouds]]\nposition_m = [1, 2]\n"),
            "scene.toml:2:14: voxel_clouds[0].position_m = [1, 2]: expected an array of 3 numbers");
  EXPECT_EQ(parse_error("voxel_clouds = 1\n"),
            "scene.toml:1:16: voxel_clouds = 1: expected an array of tables [[voxel_clouds]]");
  EXPECT_EQ(parse_error("voxel_clouds = [1]\n"),
            "scene.toml:1:16: voxel_clouds = [1]: expected an array of tables [[voxel_clouds]]");
  EXPECT_NE(parse_error("[voxel_clouds]\npreset = \"cumulus\"\n")
                .find("voxel_clouds = {...}: expected an array of tables [[voxel_clouds]]"),
            std::string::npos);
  // The top level's unknown-key message lists the array too.
  EXPECT_NE(parse_error("voxel_cloud = 1\n").find(", [[voxel_clouds]])"), std::string::npos);
}

TEST(SceneVoxelClouds, PositionFormsAreExclusiveAndComplete) {
  EXPECT_EQ(parse_error("[[voxel_clouds]]\npreset = \"cumulus\"\nposition_m = [0, 0, 1000]\n"
                        "lat_deg = 1\nlon_deg = 2\naltitude_m = 3\n"),
            "scene.toml:4:11: voxel_clouds[0]: position_m and lat_deg/lon_deg/altitude_m are "
            "both given; give one form");
  EXPECT_EQ(parse_error("[[voxel_clouds]]\nlat_deg = 1\nlon_deg = 2\n"),
            "scene.toml:2:11: voxel_clouds[0].altitude_m is missing (lat_deg, lon_deg and "
            "altitude_m go together)");
  EXPECT_EQ(parse_error("[[voxel_clouds]]\nlat_deg = 91\nlon_deg = 2\naltitude_m = 3\n"),
            "scene.toml:2:11: voxel_clouds[0].lat_deg = 91: must be in [-90, 90]");
  EXPECT_EQ(parse_error("[[voxel_clouds]]\nlat_deg = 1\nlon_deg = nan\naltitude_m = 3\n"),
            "scene.toml:3:11: voxel_clouds[0].lon_deg = nan: must be in [-180, 360]");
  EXPECT_EQ(parse_error("[[voxel_clouds]]\nlat_deg = 1\nlon_deg = 2\naltitude_m = 1e6\n"),
            "scene.toml:4:14: voxel_clouds[0].altitude_m = 1e+06: must be in [-1000, 1e+05]");
}

TEST(SceneVoxelClouds, RelativeFilesResolveAgainstTheSceneFile) {
  const std::string toml = "[[voxel_clouds]]\nfile = \"clouds/c.vdb\"\n";
  EXPECT_EQ(parse_scene_toml(toml, "s.toml", "/data/scenes").voxel_clouds[0].file,
            "/data/scenes/clouds/c.vdb");
  EXPECT_EQ(parse_scene_toml(toml, "s.toml", "").voxel_clouds[0].file, "clouds/c.vdb");
  EXPECT_EQ(parse_scene_toml("[[voxel_clouds]]\nfile = \"/abs/c.vdb\"\n", "s.toml", "/data")
                .voxel_clouds[0]
                .file,
            "/abs/c.vdb");
  EXPECT_EQ(parse_scene_toml("[[voxel_clouds]]\npreset = \"cumulus\"\n", "s.toml", "/data")
                .voxel_clouds[0]
                .file,
            "");
}

// A scene with one voxel cloud, generated, changed by `change`.
std::string voxel_error(const std::function<void(VoxelCloudParams&)>& change) {
  return validate_error([&](Scene& s) {
    s.voxel_clouds.resize(1);
    s.voxel_clouds[0].preset = "cumulus";
    change(s.voxel_clouds[0]);
  });
}

TEST(SceneVoxelClouds, ValidationNamesTheCloudTheValueAndTheRange) {
  EXPECT_EQ(voxel_error([](VoxelCloudParams& c) { c.preset = ""; }),
            "voxel_clouds[0].preset = \"\": a voxel cloud needs exactly one of file (.vdb or "
            ".nvdb) and preset (cumulus, cumulus-congestus, cumulonimbus or cumulus-mesh); neither is given");
  EXPECT_EQ(voxel_error([](VoxelCloudParams& c) { c.file = "a.vdb"; }),
            "voxel_clouds[0].file = \"a.vdb\": preset = \"cumulus\" is given too; give exactly "
            "one of file and preset");
  EXPECT_EQ(voxel_error([](VoxelCloudParams& c) { c.preset = "cirrus"; }),
            "voxel_clouds[0].preset = \"cirrus\": must be cumulus, cumulus-congestus, "
            "cumulonimbus or cumulus-mesh");
  EXPECT_EQ(voxel_error([](VoxelCloudParams& c) {
              c.position_m = {2e7f, 0.0f, 1500.0f};
            }),
            "voxel_clouds[0].position_m = (2e+07, 0, 1500): east and north must be in [-1e+07, "
            "1e+07] m");
  EXPECT_EQ(voxel_error([](VoxelCloudParams& c) {
              c.position_m = {0.0f, 0.0f, -1001.0f};
            }),
            "voxel_clouds[0].position_m = (0, 0, -1001): up must be in [-1000, 1e+05] m");
  EXPECT_EQ(voxel_error([](VoxelCloudParams& c) {
              c.position_m = {0.0f, kNaN, 0.0f};
            }),
            "voxel_clouds[0].position_m = (0, nan, 0): must be finite");
  EXPECT_EQ(voxel_error([](VoxelCloudParams& c) { c.scale = 0.0f; }),
            "voxel_clouds[0].scale = 0: must be in (0, 100]");
  EXPECT_EQ(voxel_error([](VoxelCloudParams& c) { c.scale = kInf; }),
            "voxel_clouds[0].scale = inf: must be in (0, 100]");
  EXPECT_EQ(voxel_error([](VoxelCloudParams& c) { c.rotation_deg = 361.0f; }),
            "voxel_clouds[0].rotation_deg = 361: must be in [-360, 360]");
  EXPECT_EQ(voxel_error([](VoxelCloudParams& c) { c.density = kNaN; }),
            "voxel_clouds[0].density = nan: must be in [0, 100]");
  EXPECT_EQ(voxel_error([](VoxelCloudParams& c) { c.density = -1.0f; }),
            "voxel_clouds[0].density = -1: must be in [0, 100]");
  EXPECT_EQ(voxel_error([](VoxelCloudParams& c) {
              c.wind_mps = {0.0f, 201.0f};
            }),
            "voxel_clouds[0].wind_mps = (0, 201): every component must be in [-200, 200]");
  EXPECT_EQ(voxel_error([](VoxelCloudParams& c) { c.resolution = 15; }),
            "voxel_clouds[0].resolution = 15: must be in [16, 256]");
  EXPECT_EQ(voxel_error([](VoxelCloudParams& c) { c.resolution = 257; }),
            "voxel_clouds[0].resolution = 257: must be in [16, 256]");
  EXPECT_EQ(validate_error([](Scene& s) { s.quality.sdf_light_tangent = 0.0f; }),
            "quality.sdf_light_tangent = 0: must be in [0.001, 10]");
  EXPECT_EQ(validate_error([](Scene& s) { s.quality.sdf_light_tangent = kNaN; }),
            "quality.sdf_light_tangent = nan: must be in [0.001, 10]");
  EXPECT_EQ(validate_error([](Scene& s) { s.quality.voxel_march = static_cast<VoxelMarch>(7); }),
            "quality.voxel_march = 7: must be plain or three-phase");
  EXPECT_EQ(validate_error([](Scene& s) { s.quality.voxel_shadow = static_cast<VoxelShadow>(7); }),
            "quality.voxel_shadow = 7: must be march or sdf-cone");
  // The index is the cloud's, from 0.
  EXPECT_EQ(validate_error([](Scene& s) {
              s.voxel_clouds.resize(3);
              for (VoxelCloudParams& c : s.voxel_clouds) c.preset = "cumulus";
              s.voxel_clouds[2].density = 101.0f;
            }),
            "voxel_clouds[2].density = 101: must be in [0, 100]");
}

TEST(SceneVoxelClouds, AtMostSixteen) {
  EXPECT_EQ(validate_error([](Scene& s) {
              s.voxel_clouds.resize(kMaxVoxelClouds + 1);
              for (VoxelCloudParams& c : s.voxel_clouds) c.preset = "cumulus";
            }),
            "voxel_clouds = 17 clouds: at most 16 voxel clouds per scene");
  Scene scene;
  scene.voxel_clouds.resize(kMaxVoxelClouds);
  for (VoxelCloudParams& c : scene.voxel_clouds) c.preset = "cumulonimbus";
  EXPECT_NO_THROW(validate_scene(scene));
}

TEST(SceneVoxelClouds, BoundaryValuesAreAccepted) {
  const std::vector<std::function<void(VoxelCloudParams&)>> fine = {
      [](VoxelCloudParams& c) {
        c.position_m = {-1e7f, 1e7f, -1000.0f};
      },
      [](VoxelCloudParams& c) {
        c.position_m = {1e7f, -1e7f, 1e5f};
      },
      [](VoxelCloudParams& c) { c.scale = 100.0f; },
      [](VoxelCloudParams& c) { c.scale = 1e-6f; },
      [](VoxelCloudParams& c) { c.rotation_deg = -360.0f; },
      [](VoxelCloudParams& c) { c.rotation_deg = 360.0f; },
      [](VoxelCloudParams& c) { c.density = 0.0f; },
      [](VoxelCloudParams& c) { c.density = 100.0f; },
      [](VoxelCloudParams& c) {
        c.wind_mps = {-200.0f, 200.0f};
      },
      [](VoxelCloudParams& c) { c.resolution = 16; },
      [](VoxelCloudParams& c) { c.resolution = 256; },
      [](VoxelCloudParams& c) { c.preset = "cumulus-congestus"; },
      [](VoxelCloudParams& c) { c.preset = "cumulonimbus"; },
  };
  for (size_t i = 0; i < fine.size(); ++i) {
    Scene scene;
    scene.voxel_clouds.resize(1);
    scene.voxel_clouds[0].preset = "cumulus";
    fine[i](scene.voxel_clouds[0]);
    EXPECT_NO_THROW(validate_scene(scene)) << "case " << i;
  }
  for (float tangent : {0.001f, 10.0f}) {
    Scene scene;
    scene.quality.sdf_light_tangent = tangent;
    EXPECT_NO_THROW(validate_scene(scene)) << tangent;
  }
}

// ---------------------------------------------------------------- files

class SceneFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() /
        ("nephele_scene_test_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
         "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "maps");
  }
  void TearDown() override { fs::remove_all(dir_); }
  void write(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }
  fs::path dir_;
};

TEST_F(SceneFile, LoadResolvesWeatherMapNextToTheFile) {
  const unsigned char rgba[2 * 2 * 4] = {};
  ASSERT_TRUE(stbi_write_png((dir_ / "maps" / "w.png").c_str(), 2, 2, 4, rgba, 2 * 4));
  write(dir_ / "scene.toml", "[clouds]\nweather_map = \"maps/w.png\"\ncoverage = 0.7\n");
  Scene scene = load_scene_file((dir_ / "scene.toml").string());
  EXPECT_EQ(scene.clouds.coverage, 0.7f);
  EXPECT_EQ(fs::path(scene.clouds.weather_map), dir_ / "maps" / "w.png");
  EXPECT_NO_THROW(validate_scene(scene));
}

TEST_F(SceneFile, VoxelCloudFilesAreCheckedButNotRead) {
  write(dir_ / "maps" / "c.vdb", "not a grid: the importer reads it, not validation");
  write(dir_ / "maps" / "c.NVDB", "");
  write(dir_ / "maps" / "c.obj", "");
  fs::create_directories(dir_ / "maps" / "d.vdb");
  write(dir_ / "scene.toml",
        "[[voxel_clouds]]\nfile = \"maps/c.vdb\"\n[[voxel_clouds]]\nfile = \"maps/c.NVDB\"\n");
  const Scene scene = load_scene_file((dir_ / "scene.toml").string());
  EXPECT_EQ(scene.voxel_clouds[0].file, (dir_ / "maps" / "c.vdb").string());
  EXPECT_NO_THROW(validate_scene(scene));

  auto error_for = [&](const std::string& file) {
    Scene s;
    s.voxel_clouds.resize(1);
    s.voxel_clouds[0].file = file;
    return input_error([&] { validate_scene(s); });
  };
  const std::string maps = (dir_ / "maps").string();
  // Long paths are shortened in messages: the start and the end are compared.
  const auto expect_error = [&](const std::string& file, const std::string& what) {
    const std::string message = error_for(file);
    EXPECT_EQ(message.rfind("voxel_clouds[0].file = \"/", 0), 0u) << message;
    EXPECT_TRUE(message.ends_with("\": " + what) || message.ends_with("...: " + what)) << message;
  };
  expect_error(maps + "/c.obj", "must be an OpenVDB (.vdb) or NanoVDB (.nvdb) file");
  expect_error(maps + "/d.vdb", "is not a regular file");
}

TEST_F(SceneFile, ErrorsNameTheFile) {
  std::string path = (dir_ / "bad.toml").string();
  write(path, "[clouds]\ncoverage = \"abc\"\n");
  std::string message = input_error([&] { load_scene_file(path); });
  EXPECT_EQ(message.rfind(path + ":2:", 0), 0u) << message;
}

TEST_F(SceneFile, MissingFileOrDirectoryIsAnInputError) {
  std::string missing = (dir_ / "missing.toml").string();
  std::string message = input_error([&] { load_scene_file(missing); });
  EXPECT_NE(message.find(missing), std::string::npos) << message;
  message = input_error([&] { load_scene_file(dir_.string()); });
  EXPECT_NE(message.find("directory"), std::string::npos) << message;
}

TEST_F(SceneFile, OnlyRegularFilesOfAtMostOneMebibyteAreRead) {
  // A device would be read without end (/dev/zero), a pipe would block.
  std::string message = input_error([] { load_scene_file("/dev/zero"); });
  EXPECT_EQ(message, "/dev/zero: cannot read the scene file: it is not a regular file (a device, "
                     "a pipe or a socket)");
  const std::string big = (dir_ / "big.toml").string();
  write(big, "# " + std::string(1u << 20, 'x') + "\n");
  message = input_error([&] { load_scene_file(big); });
  EXPECT_NE(message.find("larger than 1 MiB"), std::string::npos) << message;
  // Just under the limit is read.
  write(big, "# " + std::string((1u << 20) - 40, 'x') + "\n[clouds]\ncoverage = 0.3\n");
  EXPECT_LE(fs::file_size(big), 1u << 20);
  EXPECT_EQ(load_scene_file(big).clouds.coverage, 0.3f);
}

TEST(SceneParse, DeeplyNestedKeysAreRefusedBeforeParsing) {
  // 50,000 levels overflowed the stack inside the TOML library.
  std::string deep = "[clouds]\ncoverage = 0.5\n";
  for (int i = 0; i < 50000; ++i) deep += "a.";
  deep += "b = 1\n";
  EXPECT_EQ(parse_error(deep),
            "scene.toml:3: a key with more than 32 dotted parts (nephele's keys have at most 4)");
  std::string header = "[";
  for (int i = 0; i < 40; ++i) header += "\"q\" . ";
  EXPECT_NE(parse_error(header + "x]\n").find("scene.toml:1: a key with more than 32"),
            std::string::npos);
  std::string digits = "1";
  for (int i = 0; i < 40; ++i) digits += ".1";
  EXPECT_NE(parse_error(digits + " = 2\n").find("more than 32 dotted parts"), std::string::npos);
  // Dots in values, strings and comments are not key dots.
  std::string fine = "time = \"" + std::string(100, '.') + "\" # " + std::string(100, '.') +
                     "\n[clouds]\nwind_mps = [1.5, 2.25]\n";
  EXPECT_NO_THROW(parse_scene_toml(fine, "scene.toml"));
  EXPECT_EQ(parse_scene_toml("[camera]\nposition_m = [1.5, 2.5, 3.5]\n# a.b.c.d.e.f.g.h.i.j.k."
                             "l.m.n.o.p.q.r.s.t.u.v.w.x.y.z.a.b.c.d.e.f.g.h\n",
                             "scene.toml")
                .camera.position_m.y,
            2.5f);
}

TEST(SceneParse, LongValuesAreShortenedInMessages) {
  const std::string huge(1u << 20, '7');
  const std::string message = parse_error("[clouds]\ncoverage = \"" + huge + "\"\n");
  EXPECT_LT(message.size(), 200u) << message.substr(0, 300);
  EXPECT_NE(message.find("clouds.coverage = \"777"), std::string::npos) << message;
  Scene scene;
  scene.time = huge;
  const std::string time_message = input_error([&] { validate_scene(scene); });
  EXPECT_LT(time_message.size(), 200u);
  EXPECT_EQ(time_message.rfind("time = \"777", 0), 0u) << time_message;
  EXPECT_NE(time_message.find("...: must be an ISO 8601 date"), std::string::npos);
}

TEST(SceneParse, AnEmptyTimeThatPlacesTheSunIsBlamedOnTheTime) {
  EXPECT_EQ(input_error([] { validate_scene(parse_scene_toml("time = \"\"\n", "s.toml")); }),
            "time = \"\": the sun is placed by the date (sun.from_time = true): give a date and "
            "time like 2026-06-21T18:30:00Z, or a sun direction");
}

// ---------------------------------------------------------------- validation

struct BadValue {
  const char* expected;  // start of the message: "key = value"
  std::function<void(Scene&)> change;
};

class SceneValidate : public ::testing::TestWithParam<BadValue> {};

TEST_P(SceneValidate, RejectsWithKeyAndValue) {
  std::string message = validate_error(GetParam().change);
  EXPECT_EQ(message.rfind(GetParam().expected, 0), 0u) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

const BadValue kBadValues[] = {
    {"camera.position_m = (nan, 0, 2)", [](Scene& s) { s.camera.position_m.x = kNaN; }},
    {"camera.altitude_m = -1", [](Scene& s) { s.camera.position_m.z = -1.0f; }},
    {"camera.view_dir = (0, 0, 0)", [](Scene& s) { s.camera.view_dir = glm::vec3(0.0f); }},
    {"camera.view_dir = (nan, 1, 0)",
     [](Scene& s) {
       s.camera.view_dir = {kNaN, 1.0f, 0.0f};
     }},
    {"camera.view_dir = (0, inf, 0)",
     [](Scene& s) {
       s.camera.view_dir = {0.0f, kInf, 0.0f};
     }},
    {"camera.fov_deg = 0", [](Scene& s) { s.camera.fov_deg = 0.0f; }},
    {"camera.fov_deg = 180", [](Scene& s) { s.camera.fov_deg = 180.0f; }},
    {"camera.fov_deg = nan", [](Scene& s) { s.camera.fov_deg = kNaN; }},
    {"camera.roll_deg = 180.5: must be in [-180, 180]",
     [](Scene& s) { s.camera.roll_deg = 180.5f; }},
    {"camera.roll_deg = nan", [](Scene& s) { s.camera.roll_deg = kNaN; }},
    {"sun.direction = (0, 0, 0)", [](Scene& s) { s.sun.direction = glm::vec3(0.0f); }},
    {"sun.direction = (0, -inf, 1)",
     [](Scene& s) {
       s.sun.direction = {0.0f, -kInf, 1.0f};
     }},
    {"sun.illuminance_lux = -1", [](Scene& s) { s.sun.illuminance_lux = -1.0f; }},
    {"sun.illuminance_lux = inf", [](Scene& s) { s.sun.illuminance_lux = kInf; }},
    {"camera.horizontal_fov_deg = 180: must be in [0.01, 180)",
     [](Scene& s) { s.camera.horizontal_fov_deg = 180.0f; }},
    {"camera.focal_length_mm = -35: must be in [0.1, 1e+05]",
     [](Scene& s) { s.camera.focal_length_mm = -35.0f; }},
    {"camera.sensor_width_mm = 0: must be in [1, 1000]",
     [](Scene& s) { s.camera.sensor_width_mm = 0.0f; }},
    {"camera.focal_length_mm = 35: camera.horizontal_fov_deg (60) is given too; give one of "
     "fov_deg, horizontal_fov_deg, focal_length_mm",
     [](Scene& s) {
       s.camera.focal_length_mm = 35.0f;
       s.camera.horizontal_fov_deg = 60.0f;
     }},
    {"sun.disk_angular_radius_deg = 90", [](Scene& s) { s.sun.disk_angular_radius_deg = 90.0f; }},
    {"atmosphere.planet_radius_km = 0", [](Scene& s) { s.atmosphere.planet_radius_km = 0.0f; }},
    {"atmosphere.atmosphere_height_km = -5",
     [](Scene& s) { s.atmosphere.atmosphere_height_km = -5.0f; }},
    {"atmosphere.rayleigh_scattering_per_m = (-1, 0, 0)",
     [](Scene& s) {
       s.atmosphere.rayleigh_scattering_per_m = {-1.0f, 0.0f, 0.0f};
     }},
    {"atmosphere.rayleigh_scale_height_m = 0",
     [](Scene& s) { s.atmosphere.rayleigh_scale_height_m = 0.0f; }},
    {"atmosphere.mie_scattering_per_m = nan",
     [](Scene& s) { s.atmosphere.mie_scattering_per_m = kNaN; }},
    {"atmosphere.mie_extinction_per_m = 1e-06",
     [](Scene& s) { s.atmosphere.mie_extinction_per_m = 1e-6f; }},
    {"atmosphere.mie_scale_height_m = nan",
     [](Scene& s) { s.atmosphere.mie_scale_height_m = kNaN; }},
    {"atmosphere.mie_g = 1", [](Scene& s) { s.atmosphere.mie_g = 1.0f; }},
    {"atmosphere.mie_g = -0.1", [](Scene& s) { s.atmosphere.mie_g = -0.1f; }},
    {"atmosphere.view_samples = 0", [](Scene& s) { s.atmosphere.view_samples = 0; }},
    {"atmosphere.ground_albedo = 1.5", [](Scene& s) { s.atmosphere.ground_albedo = 1.5f; }},
    {"atmosphere.turbidity = 1", [](Scene& s) { s.atmosphere.turbidity = 1.0f; }},
    {"clouds.top_altitude_m = 4000: must be below the top of the atmosphere",
     [](Scene& s) { s.atmosphere.atmosphere_height_km = 3.0f; }},
    {"clouds.bottom_altitude_m = -1", [](Scene& s) { s.clouds.bottom_altitude_m = -1.0f; }},
    {"clouds.bottom_altitude_m = 4000: must be below clouds.top_altitude_m (4000)",
     [](Scene& s) { s.clouds.bottom_altitude_m = 4000.0f; }},
    {"clouds.bottom_altitude_m = 1500: must be below clouds.top_altitude_m (1000)",
     [](Scene& s) { s.clouds.top_altitude_m = 1000.0f; }},
    {"clouds.top_altitude_m = inf", [](Scene& s) { s.clouds.top_altitude_m = kInf; }},
    {"clouds.coverage = 1.5: must be in [0, 1]", [](Scene& s) { s.clouds.coverage = 1.5f; }},
    {"clouds.coverage = -0.01", [](Scene& s) { s.clouds.coverage = -0.01f; }},
    {"clouds.coverage = nan", [](Scene& s) { s.clouds.coverage = kNaN; }},
    {"clouds.density = 1.01", [](Scene& s) { s.clouds.density = 1.01f; }},
    {"clouds.extinction_per_m = 0", [](Scene& s) { s.clouds.extinction_per_m = 0.0f; }},
    {"clouds.extinction_per_m = inf", [](Scene& s) { s.clouds.extinction_per_m = kInf; }},
    {"clouds.attenuation = -0.5", [](Scene& s) { s.clouds.attenuation = -0.5f; }},
    {"clouds.light_attenuation = nan", [](Scene& s) { s.clouds.light_attenuation = kNaN; }},
    {"clouds.albedo = 1.1", [](Scene& s) { s.clouds.albedo = 1.1f; }},
    {"clouds.phase_g_forward = 1: must be in [0, 1)",
     [](Scene& s) { s.clouds.phase_g_forward = 1.0f; }},
    {"clouds.phase_g_forward = -0.2", [](Scene& s) { s.clouds.phase_g_forward = -0.2f; }},
    {"clouds.phase_g_backward = 0.1", [](Scene& s) { s.clouds.phase_g_backward = 0.1f; }},
    {"clouds.phase_g_backward = -1: must be in (-1, 0]",
     [](Scene& s) { s.clouds.phase_g_backward = -1.0f; }},
    {"clouds.phase_lobe_weight = 1.5", [](Scene& s) { s.clouds.phase_lobe_weight = 1.5f; }},
    {"clouds.powder_strength = 2", [](Scene& s) { s.clouds.powder_strength = 2.0f; }},
    {"clouds.ambient_strength = -1", [](Scene& s) { s.clouds.ambient_strength = -1.0f; }},
    {"clouds.wind_mps = (nan, 2)", [](Scene& s) { s.clouds.wind_mps.x = kNaN; }},
    {"clouds.base_noise_period_m = 0", [](Scene& s) { s.clouds.base_noise_period_m = 0.0f; }},
    {"clouds.detail_noise_period_m = -900",
     [](Scene& s) { s.clouds.detail_noise_period_m = -900.0f; }},
    {"clouds.detail_erosion = 2", [](Scene& s) { s.clouds.detail_erosion = 2.0f; }},
    {"clouds.weather_period_m = inf", [](Scene& s) { s.clouds.weather_period_m = kInf; }},
    {"clouds.weather_map = \"/nonexistent/nephele/w.png\": cannot read the file",
     [](Scene& s) { s.clouds.weather_map = "/nonexistent/nephele/w.png"; }},
    {"quality.primary_steps = 0", [](Scene& s) { s.quality.primary_steps = 0; }},
    {"quality.primary_steps = 1025: must be in [1, 1024]",
     [](Scene& s) { s.quality.primary_steps = 1025; }},
    {"quality.light_steps = 0", [](Scene& s) { s.quality.light_steps = 0; }},
    {"quality.light_steps = 65: must be in [1, 64]", [](Scene& s) { s.quality.light_steps = 65; }},
    {"quality.march_stride = 3: must be 1, 2 or 4", [](Scene& s) { s.quality.march_stride = 3; }},
    {"quality.march_stride = 0: must be 1, 2 or 4", [](Scene& s) { s.quality.march_stride = 0; }},
    {"quality.cloud_downsample = 5: must be in [1, 4]",
     [](Scene& s) { s.quality.cloud_downsample = 5; }},
    {"quality.light_volume_km = -1: must be in [0, 1000]",
     [](Scene& s) { s.quality.light_volume_km = -1; }},
    {"output.width = 0", [](Scene& s) { s.output.width = 0; }},
    {"output.width = 16385: must be in [1, 16384]", [](Scene& s) { s.output.width = 16385; }},
    {"output.height = -1", [](Scene& s) { s.output.height = -1; }},
    {"output.ev100 = 31: must be in [-20, 30]", [](Scene& s) { s.output.ev100 = 31.0f; }},
    {"output.ev100 = nan", [](Scene& s) { s.output.ev100 = kNaN; }},
    {"output.ev100_min = 5: must be <= output.ev100_max (4)",
     [](Scene& s) {
       s.output.ev100_min = 5.0f;
       s.output.ev100_max = 4.0f;
     }},
    {"output.ev100_max = -21: must be in [-20, 30]", [](Scene& s) { s.output.ev100_max = -21.0f; }},
    {"output.exposure_compensation_ev = 11: must be in [-10, 10]",
     [](Scene& s) { s.output.exposure_compensation_ev = 11.0f; }},
    {"output.adaptation_ev_per_s = -1: must be in [0, 1e+06]",
     [](Scene& s) { s.output.adaptation_ev_per_s = -1.0f; }},
    {"time_s = inf", [](Scene& s) { s.time_s = kInf; }},
    {"time = \"2026-06-21 18:30\": must be an ISO 8601 date and time with a zone, like "
     "2026-06-21T18:30:00Z",
     [](Scene& s) { s.time = "2026-06-21 18:30"; }},
    {"time = \"\": the sun is placed by the date (sun.from_time = true)",
     [](Scene& s) { s.sun.from_time = true; }},
    {"location.lat_deg = 91: must be in [-90, 90]", [](Scene& s) { s.location.lat_deg = 91.0f; }},
    {"location.lon_deg = -181: must be in [-180, 360]",
     [](Scene& s) { s.location.lon_deg = -181.0f; }},
    {"location.altitude_m = nan", [](Scene& s) { s.location.altitude_m = kNaN; }},
    // Upper bounds: each of these rendered NaN, inf, a wrong view or crashed when accepted.
    {"camera.position_m = (1e+30, 0, 2): east and north must be in [-1e+09, 1e+09] m",
     [](Scene& s) { s.camera.position_m.x = 1e30f; }},
    {"camera.position_m = (0, -1e+20, 2)", [](Scene& s) { s.camera.position_m.y = -1e20f; }},
    {"camera.altitude_m = 1e+38: must be in [0, 1e+09]",
     [](Scene& s) { s.camera.position_m.z = 1e38f; }},
    {"camera.view_dir = (1e-25, 0, 0): must be a finite vector of length in [1e-06, 1e+06]",
     [](Scene& s) { s.camera.view_dir = {1e-25f, 0.0f, 0.0f}; }},
    {"camera.view_dir = (1e+20, 1e+20, 1e+20)",
     [](Scene& s) { s.camera.view_dir = glm::vec3(1e20f); }},
    {"camera.fov_deg = 0.001: must be in [0.01, 180)", [](Scene& s) { s.camera.fov_deg = 1e-3f; }},
    {"sun.direction = (0, 0, 1e-07)", [](Scene& s) { s.sun.direction = {0.0f, 0.0f, 1e-7f}; }},
    {"sun.illuminance_lux = 1e+11: must be in [0, 1e+10]",
     [](Scene& s) { s.sun.illuminance_lux = 1e11f; }},
    {"atmosphere.planet_radius_km = 1e+30", [](Scene& s) { s.atmosphere.planet_radius_km = 1e30f; }},
    {"atmosphere.atmosphere_height_km = 1e+08",
     [](Scene& s) { s.atmosphere.atmosphere_height_km = 1e8f; }},
    {"atmosphere.mie_extinction_per_m = 3e+38: must be in [0, 0.01]",
     [](Scene& s) { s.atmosphere.mie_extinction_per_m = 3e38f; }},
    {"atmosphere.rayleigh_scattering_per_m = (1, 0, 0): every component must be in [0, 0.01]",
     [](Scene& s) { s.atmosphere.rayleigh_scattering_per_m = {1.0f, 0.0f, 0.0f}; }},
    {"clouds.ambient_strength = 1e+09: must be in [0, 100]",
     [](Scene& s) { s.clouds.ambient_strength = 1e9f; }},
    {"clouds.extinction_per_m = 1e+30", [](Scene& s) { s.clouds.extinction_per_m = 1e30f; }},
    {"clouds.wind_mps = (1e+30, 2): every component must be in [-200, 200]",
     [](Scene& s) { s.clouds.wind_mps.x = 1e30f; }},
    {"clouds.flow_cycle_s = 1e-30: must be in [1, 86400]",
     [](Scene& s) { s.clouds.flow_cycle_s = 1e-30f; }},
    {"clouds.weather_evolution_s = 1e-30: must be in [1, 1e+07]",
     [](Scene& s) { s.clouds.weather_evolution_s = 1e-30f; }},
    {"cirrus.altitude_m = 1e+38: must be in [0, 1e+06]", [](Scene& s) { s.cirrus.altitude_m = 1e38f; }},
    {"output.ev100 = 1e+38", [](Scene& s) { s.output.ev100 = 1e38f; }},
    {"time_s = 3e+38: must be in [-1e+06, 1e+06]", [](Scene& s) { s.time_s = 3e38f; }},
};

// Test names from the expected message: "clouds.coverage = 1.5" -> "3_clouds_coverage_1_5".
INSTANTIATE_TEST_SUITE_P(Scene, SceneValidate, ::testing::ValuesIn(kBadValues),
                         [](const ::testing::TestParamInfo<BadValue>& info) {
                           std::string name = std::to_string(info.index) + "_";
                           for (const char* c = info.param.expected; *c; ++c)
                             if (std::isalnum(static_cast<unsigned char>(*c))) name += *c;
                             else if (name.back() != '_') name += '_';
                           while (name.back() == '_') name.pop_back();
                           return name;
                         });

TEST(SceneValidateExact, MessagesAreOneCompleteLine) {
  EXPECT_EQ(validate_error([](Scene& s) { s.clouds.coverage = 1.5f; }),
            "clouds.coverage = 1.5: must be in [0, 1]");
  EXPECT_EQ(validate_error([](Scene& s) { s.camera.view_dir = glm::vec3(0.0f); }),
            "camera.view_dir = (0, 0, 0): must be a finite vector of length in [1e-06, 1e+06]");
  EXPECT_EQ(validate_error([](Scene& s) { s.output.ev100 = -22.0f; }),
            "output.ev100 = -22: must be in [-20, 30]");
}

TEST(SceneValidateExact, BoundaryValuesAreAccepted) {
  std::vector<std::function<void(Scene&)>> fine = {
      [](Scene& s) { s.clouds.coverage = 0.0f; },
      [](Scene& s) { s.clouds.coverage = 1.0f; },
      [](Scene& s) { s.clouds.density = 0.0f; },
      [](Scene& s) { s.clouds.bottom_altitude_m = 0.0f; },
      [](Scene& s) { s.camera.position_m.z = 0.0f; },
      [](Scene& s) { s.camera.fov_deg = 179.9f; },
      [](Scene& s) {
        s.camera.view_dir = {0.0f, 0.0f, -1e-3f};
      },
      [](Scene& s) { s.quality.primary_steps = 1; },
      [](Scene& s) { s.quality.primary_steps = 1024; },
      [](Scene& s) { s.quality.light_steps = 64; },
      [](Scene& s) { s.quality.march_stride = 1; },
      [](Scene& s) { s.quality.march_stride = 2; },
      [](Scene& s) { s.quality.cloud_downsample = 1; },
      [](Scene& s) { s.quality.light_volume_km = 0; },
      [](Scene& s) { s.output.width = 16384; },
      [](Scene& s) { s.output.height = 1; },
      [](Scene& s) { s.atmosphere.view_samples = 256; },
      [](Scene& s) { s.sun.illuminance_lux = 0.0f; },
      [](Scene& s) { s.camera.focal_length_mm = 0.1f; },
      [](Scene& s) { s.camera.horizontal_fov_deg = 179.9f; },
      [](Scene& s) { s.time_s = -5.0f; },
      // The far ends of the documented ranges.
      [](Scene& s) {
        s.camera.position_m = {-1e9f, 1e9f, 1e9f};
      },
      [](Scene& s) {
        s.camera.view_dir = {1e-6f, 0.0f, 0.0f};
      },
      [](Scene& s) {
        s.camera.view_dir = {0.0f, 1e6f, 0.0f};
      },
      [](Scene& s) { s.camera.fov_deg = 0.01f; },
      [](Scene& s) { s.camera.roll_deg = -180.0f; },
      [](Scene& s) { s.camera.roll_deg = 180.0f; },
      [](Scene& s) { s.sun.illuminance_lux = 1e10f; },
      [](Scene& s) {
        s.atmosphere.mie_scattering_per_m = s.atmosphere.mie_extinction_per_m = 0.01f;
      },
      [](Scene& s) { s.clouds.ambient_strength = 100.0f; },
      [](Scene& s) {
        s.clouds.wind_mps = {-200.0f, 200.0f};
      },
      [](Scene& s) { s.clouds.weather_evolution_s = 0.0f; },
      [](Scene& s) { s.time_s = 1e6f; },
      [](Scene& s) { s.output.ev100 = 30.0f; },
      [](Scene& s) { s.output.ev100_min = s.output.ev100_max = -20.0f; },
      [](Scene& s) { s.output.adaptation_ev_per_s = 1e6f; },
  };
  for (size_t i = 0; i < fine.size(); ++i) {
    Scene scene;
    fine[i](scene);
    EXPECT_NO_THROW(validate_scene(scene)) << "case " << i;
  }
  // The seed's optical keys, with the seed's optics (droplets refuse a changed one).
  const std::vector<std::function<void(nephele::CloudParams&)>> seed_optics = {
      [](nephele::CloudParams& c) { c.albedo = 1.0f; },
      [](nephele::CloudParams& c) { c.phase_g_forward = 0.0f; },
      [](nephele::CloudParams& c) { c.phase_g_backward = 0.0f; },
      [](nephele::CloudParams& c) { c.phase_lobe_weight = 1.0f; },
  };
  for (size_t i = 0; i < seed_optics.size(); ++i) {
    Scene scene;
    scene.clouds.optics = "seed";
    seed_optics[i](scene.clouds);
    EXPECT_NO_THROW(validate_scene(scene)) << "seed optics case " << i;
  }
}

TEST(SceneValidateExact, NamerCanShowFlags) {
  ParamNamer namer = [](const std::string& key) -> std::string {
    if (key == "clouds.coverage") return "--coverage";
    if (key == "camera.view_dir") return "--view-dir";
    if (key == "clouds.top_altitude_m") return "--cloud-top-m";
    if (key == "clouds.weather_map") return "--weather-map";
    if (key == "output.width") return "my.toml: output.width";
    return "";
  };
  auto error_with = [&](const std::function<void(Scene&)>& change) {
    Scene scene;
    change(scene);
    return input_error([&] { validate_scene(scene, namer); });
  };
  EXPECT_EQ(error_with([](Scene& s) { s.clouds.coverage = 1.5f; }),
            "--coverage 1.5: must be in [0, 1]");
  EXPECT_EQ(error_with([](Scene& s) { s.camera.view_dir = glm::vec3(0.0f); }),
            "--view-dir 0,0,0: must be a finite vector of length in [1e-06, 1e+06]");
  EXPECT_EQ(error_with([](Scene& s) { s.clouds.top_altitude_m = 1000.0f; }),
            "clouds.bottom_altitude_m = 1500: must be below --cloud-top-m (1000)");
  EXPECT_EQ(error_with([](Scene& s) { s.clouds.weather_map = "/nonexistent/w.png"; }),
            "--weather-map /nonexistent/w.png: cannot read the file");
  EXPECT_EQ(error_with([](Scene& s) { s.output.width = 0; }),
            "my.toml: output.width = 0: must be in [1, 16384]");
}

// ---------------------------------------------------------------- weather-map files

// Big-endian bytes of a 32-bit value.
void append_u32(std::string& out, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out += char((v >> shift) & 0xff);
}

// A PNG chunk: length, type, data, CRC-32 of type and data.
void append_png_chunk(std::string& out, const std::string& type, const std::string& data) {
  append_u32(out, uint32_t(data.size()));
  const std::string body = type + data;
  uint32_t crc = 0xffffffffu;
  for (unsigned char byte : body) {
    crc ^= byte;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  out += body;
  append_u32(out, crc ^ 0xffffffffu);
}

// A 16-bit RGBA PNG (stb cannot write one): samples row by row, 4 a pixel; the image data
// in stored (uncompressed) deflate blocks.
std::string png16_rgba(int width, int height, const std::vector<uint16_t>& samples) {
  std::string rows;
  for (int y = 0; y < height; ++y) {
    rows += char(0);  // filter: none
    for (int i = 0; i < width * 4; ++i) {
      const uint16_t v = samples[size_t(y) * size_t(width) * 4 + size_t(i)];
      rows += char(v >> 8);
      rows += char(v & 0xff);
    }
  }
  std::string zlib = "\x78\x01";
  for (size_t at = 0; at < rows.size(); at += 65535) {
    const size_t n = std::min<size_t>(65535, rows.size() - at);
    zlib += char(at + n == rows.size() ? 1 : 0);  // BFINAL, stored
    zlib += char(n & 0xff);
    zlib += char(n >> 8);
    zlib += char(~n & 0xff);
    zlib += char((~n >> 8) & 0xff);
    zlib += rows.substr(at, n);
  }
  uint32_t a = 1, b = 0;  // Adler-32
  for (unsigned char byte : rows) {
    a = (a + byte) % 65521;
    b = (b + a) % 65521;
  }
  append_u32(zlib, (b << 16) | a);
  std::string header;
  append_u32(header, uint32_t(width));
  append_u32(header, uint32_t(height));
  header += std::string("\x10\x06\x00\x00\x00", 5);  // 16 bits, RGBA, deflate, no interlace
  std::string png = "\x89PNG\r\n\x1a\n";
  append_png_chunk(png, "IHDR", header);
  append_png_chunk(png, "IDAT", zlib);
  append_png_chunk(png, "IEND", "");
  return png;
}

class SceneWeatherMap : public SceneFile {
 protected:
  // An 8-bit PNG of 4x4 pixels with `channels` channels; returns its path.
  std::string png8(const std::string& name, int channels) {
    const std::vector<unsigned char> pixels(4 * 4 * size_t(channels), 200);
    const std::string path = (dir_ / name).string();
    EXPECT_TRUE(stbi_write_png(path.c_str(), 4, 4, channels, pixels.data(), 4 * channels));
    return path;
  }
  std::string error_for(const std::string& path) {
    return validate_error([&](Scene& s) { s.clouds.weather_map = path; });
  }
};

// A grey, grey-and-alpha or RGB PNG would be read as RGBA with other meanings (stb fills the
// missing channels: storm cells and cloud type from the grey, alpha 1 doubling the density):
// refused with one line that names the file, what it holds and what a weather map needs.
TEST_F(SceneWeatherMap, PngsWithoutFourChannelsAreRefused) {
  const std::string needs =
      "a weather map needs 4 channels (RGBA: R coverage, G storm cells, B cloud type around "
      "clouds.type, A density)";
  const std::string grey = png8("grey.png", 1), grey_alpha = png8("grey_alpha.png", 2),
                    rgb = png8("rgb.png", 3);
  EXPECT_EQ(error_for(grey),
            "clouds.weather_map = \"" + grey + "\": has 1 channel (grey); " + needs);
  EXPECT_EQ(error_for(grey_alpha), "clouds.weather_map = \"" + grey_alpha +
                                       "\": has 2 channels (grey and alpha); " + needs);
  EXPECT_EQ(error_for(rgb), "clouds.weather_map = \"" + rgb + "\": has 3 channels (RGB); " + needs);
  // As a flag the path is shown as typed.
  Scene scene;
  scene.clouds.weather_map = grey;
  EXPECT_EQ(input_error([&] {
              validate_scene(scene, [](const std::string& key) {
                return key == "clouds.weather_map" ? std::string("--weather-map") : std::string();
              });
            }),
            "--weather-map " + grey + ": has 1 channel (grey); " + needs);
}

TEST_F(SceneWeatherMap, RgbaPngsAreAccepted) {
  Scene scene;
  scene.clouds.weather_map = png8("rgba.png", 4);
  EXPECT_NO_THROW(validate_scene(scene));
}

// Neither a PNG nor an EXR: refused before anything is rendered, not when the map is uploaded.
TEST_F(SceneWeatherMap, OtherFilesAreRefused) {
  const std::string text = (dir_ / "map.png").string();
  write(text, "not an image\n");
  EXPECT_EQ(error_for(text),
            "clouds.weather_map = \"" + text + "\": is neither a PNG nor an EXR file");
}

// 16 bits per channel: accepted, each value cut to the texture's 8 bits (stb keeps the high
// byte), so 0xc8ff reads as 200 / 255.
TEST_F(SceneWeatherMap, SixteenBitRgbaPngsAreAcceptedAtEightBits) {
  std::vector<uint16_t> samples(4 * 4 * 4);
  for (size_t i = 0; i < samples.size(); ++i) samples[i] = uint16_t(0x0100 * (i % 256) + 0xff);
  const std::string path = (dir_ / "rgba16.png").string();
  write(path, png16_rgba(4, 4, samples));
  int w = 0, h = 0, channels = 0;
  ASSERT_TRUE(stbi_info(path.c_str(), &w, &h, &channels));
  ASSERT_TRUE(stbi_is_16_bit(path.c_str()));
  ASSERT_EQ(channels, 4);
  Scene scene;
  scene.clouds.weather_map = path;
  EXPECT_NO_THROW(validate_scene(scene));
  const Image image = read_image(path);
  ASSERT_EQ(image.width, 4);
  ASSERT_EQ(image.height, 4);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    for (int c = 0; c < 4; ++c)
      EXPECT_EQ(image.pixels[i][c], float((4 * i + size_t(c)) % 256) / 255.0f) << i << " " << c;
}

// ---------------------------------------------------------------- date, time and place

TEST(SceneTime, ATimeWithoutASunDirectionPlacesTheSun) {
  Scene s = parse_scene_toml(
      "time = \"2026-06-21T18:30:00Z\"\nlocation = { lat_deg = 48.85, lon_deg = 2.35 }\n",
      "scene.toml");
  EXPECT_TRUE(s.sun.from_time);
  EXPECT_EQ(s.location.lat_deg, 48.85f);
  // Paris, 20:30 local summer time: low in the west-north-west (astropy: 11.6 deg, 292.5 deg).
  const glm::vec3 sun = scene_sun_direction(s);
  const SunAngles a = sun_angles_from_direction(sun);
  EXPECT_NEAR(a.elevation_deg, 11.6, 0.1);
  EXPECT_NEAR(a.azimuth_deg, 292.5, 0.1);
  // Animation time moves the clock: an hour later the sun is below 3 deg.
  s.time_s = 3600.0f;
  EXPECT_LT(sun_angles_from_direction(scene_sun_direction(s)).elevation_deg, 3.0);
}

TEST(SceneTime, AnExplicitSunDirectionOverridesTheTime) {
  Scene s = parse_scene_toml(
      "time = \"2026-06-21T18:30:00Z\"\n[sun]\nelevation_deg = 40\nazimuth_deg = 100\n",
      "scene.toml");
  EXPECT_FALSE(s.sun.from_time);
  EXPECT_NEAR(sun_angles_from_direction(scene_sun_direction(s)).elevation_deg, 40.0, 1e-4);
  // A later file that gives only a time starts following it again.
  s = parse_scene_toml("preset = \"default\"\ntime = 2026-06-21T18:30:00Z\n", "scene.toml");
  EXPECT_TRUE(s.sun.from_time);
  EXPECT_EQ(s.time, "2026-06-21T18:30:00Z");  // a TOML date-time, unquoted, reads as the text
}

TEST(SceneTime, WithoutATimeThereIsNoEphemeris) {
  Scene s;
  EXPECT_FALSE(scene_ephemeris(s).has_value());
  EXPECT_EQ(scene_sun_direction(s), glm::normalize(s.sun.direction));
}

// ---------------------------------------------------------------- round trip

TEST(SceneRoundTrip, DefaultsAndPresets) {
  expect_same_scene(parse_scene_toml(scene_to_toml(Scene{}), "dump.toml"), Scene{});
  for (const std::string& name : preset_names()) {
    SCOPED_TRACE(name);
    Scene preset = load_preset(name);
    expect_same_scene(parse_scene_toml(scene_to_toml(preset), "dump.toml"), preset);
  }
}

TEST(SceneRoundTrip, EveryFieldExactly) {
  Scene scene = unusual_scene();
  std::string toml = scene_to_toml(scene);
  SCOPED_TRACE(toml);
  expect_same_scene(parse_scene_toml(toml, "dump.toml"), scene);
  // Sanity check of the comparison itself: it must notice a difference.
  Scene other = scene;
  other.clouds.detail_erosion = 0.5f;
  EXPECT_NE(scene_to_toml(other), toml);
}

TEST(SceneRoundTrip, AwkwardFloatsSurvive) {
  // Values whose shortest decimal form is long, tiny, huge or not a float literal at all.
  // 0x15ae43fd is the one float whose shortest digits ("7.038531e-26") read as a double and
  // then narrowed give a different float (found by trying all of them).
  const float values[] = {0.1f,
                          1.0f / 3.0f,
                          16777217.0f,
                          3.4028235e38f,
                          1.17549435e-38f,
                          1e-45f,
                          -0.0f,
                          2.0f,
                          123456789.0f,
                          0.3f,
                          5.802e-6f,
                          std::bit_cast<float>(0x15ae43fdu)};
  for (float value : values) {
    Scene scene;
    scene.time_s = value;
    Scene back = parse_scene_toml(scene_to_toml(scene), "dump.toml");
    EXPECT_EQ(back.time_s, value) << scene_to_toml(scene);
    EXPECT_EQ(std::signbit(back.time_s), std::signbit(value));
  }
}

TEST(SceneRoundTrip, VoxelCloudsAreArrayTablesWithoutTheUnusedSource) {
  Scene scene;
  scene.voxel_clouds.resize(2);
  scene.voxel_clouds[0].preset = "cumulus";
  scene.voxel_clouds[1].file = "c.vdb";
  const std::string toml = scene_to_toml(scene);
  const size_t clouds = toml.find("[[voxel_clouds]]");  // [terrain] has a file and a preset too
  ASSERT_NE(clouds, std::string::npos) << toml;
  EXPECT_EQ(toml.find("file = \"\"", clouds), std::string::npos) << toml;
  EXPECT_EQ(toml.find("preset = \"\"", clouds), std::string::npos) << toml;
  EXPECT_NE(toml.find("\n[[voxel_clouds]]\npreset = \"cumulus\"  # "), std::string::npos) << toml;
  EXPECT_NE(toml.find("\n[[voxel_clouds]]\nfile = \"c.vdb\"  # "), std::string::npos) << toml;
  expect_same_scene(parse_scene_toml(toml, "dump.toml"), scene);
  EXPECT_NE(toml.find("voxel_march = \"three-phase\""), std::string::npos) << toml;
  EXPECT_NE(toml.find("voxel_shadow = \"march\""), std::string::npos) << toml;
  EXPECT_NE(toml.find("sdf_light_tangent = 0.1"), std::string::npos) << toml;
}

TEST(SceneRoundTrip, OutputIsCommentedAndHasAllTables) {
  std::string toml = scene_to_toml(Scene{});
  for (const char* table :
       {"[location]", "[camera]", "[sun]", "[atmosphere]", "[clouds]", "[quality]", "[output]"})
    EXPECT_NE(toml.find(table), std::string::npos) << table;
  EXPECT_NE(toml.find("mode = \"default\""), std::string::npos) << toml;
  EXPECT_NE(toml.find("# towards the sun, ENU (when from_time is false); elevation"), std::string::npos) << toml;
}

}  // namespace
}  // namespace nephele

// toml++ quotes what it read in its descriptions: a carriage return among those bytes must not
// split nephele's one-line message (found by the fuzz tests).
TEST(SceneIo, MalformedTomlMessagesStayOnOneLine) {
  try {
    nephele::parse_scene_toml("[particle_clouds]\nrayleigh_phase = tr\r\n", "s.toml");
    FAIL() << "accepted";
  } catch (const nephele::InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.find_first_of("\r\n"), std::string::npos) << m;
    EXPECT_NE(m.find("s.toml:2"), std::string::npos) << m;
    EXPECT_NE(m.find("malformed TOML"), std::string::npos) << m;
  }
  EXPECT_EQ(nephele::one_line_for_message("a\nb\rc\x7f"), "a b?c?");
  // Issue 40: invisible reordering characters, C1 controls and bytes that are not UTF-8 too;
  // letters of any script pass.
  EXPECT_EQ(nephele::shorten_for_message("evil\u202egnp.exe"), "evil?gnp.exe");
  EXPECT_EQ(nephele::shorten_for_message("a\u2066b\u2069c\u200fd\u2028e"), "a?b?c?d?e");
  EXPECT_EQ(nephele::shorten_for_message("x\xc2\x9by"), "x?y");
  EXPECT_EQ(nephele::shorten_for_message("x\xff\xc0\xafy\xe2\x80"), "x???y??");
  EXPECT_EQ(nephele::shorten_path_for_message("облака/云.toml"), "облака/云.toml");
  EXPECT_EQ(nephele::one_line_for_message("\xef\xbb\xbf" "a\u202e"), "?a?");
}
