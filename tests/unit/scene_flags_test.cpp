// CLI scene flags: registration with CLI11, overrides, error messages naming the flag.
#include "scene_flags.h"

#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <stb/stb_image_write.h>
#include <filesystem>
#include <fstream>
#include <functional>

#include "nephele/error.h"
#include "nephele/scene_io.h"

namespace nephele::cli {
namespace {

namespace fs = std::filesystem;

// Parses `args` (without the program name) with CLI11 and resolves the scene.
Scene resolve(std::vector<std::string> args) {
  CLI::App app("test");
  SceneFlags flags;
  add_scene_flags(app, flags);
  std::vector<const char*> argv = {"nephele"};
  for (const std::string& arg : args) argv.push_back(arg.c_str());
  app.parse(static_cast<int>(argv.size()), argv.data());
  return resolve_scene(flags);
}

std::string resolve_error(std::vector<std::string> args) {
  try {
    resolve(std::move(args));
  } catch (const InputError& error) {
    return error.what();
  }
  ADD_FAILURE() << "no InputError thrown";
  return "";
}

void expect_near(const glm::vec3& actual, const glm::vec3& expected) {
  EXPECT_NEAR(actual.x, expected.x, 1e-6f);
  EXPECT_NEAR(actual.y, expected.y, 1e-6f);
  EXPECT_NEAR(actual.z, expected.z, 1e-6f);
}

TEST(SceneFlags, NoFlagsGiveTheDefaultPreset) {
  Scene scene = resolve({});
  EXPECT_EQ(scene_to_toml(scene), scene_to_toml(load_preset("default")));
}

TEST(SceneFlags, PresetIsLoaded) {
  Scene scene = resolve({"--preset", "overcast"});
  EXPECT_EQ(scene_to_toml(scene), scene_to_toml(load_preset("overcast")));
}

TEST(SceneFlags, RegistersExactlyTheSceneSpellings) {
  CLI::App app("test");
  SceneFlags flags;
  add_scene_flags(app, flags);
  for (const char* flag : {"--scene",
                           "--preset",
                           "--width",
                           "--height",
                           "--camera-altitude-m",
                           "--camera-pos",
                           "--view-dir",
                           "--fov-deg",
                           "--roll-deg",
                           "--sun-dir",
                           "--sun-elevation-deg",
                           "--sun-azimuth-deg",
                           "--sun-illuminance",
                           "--coverage",
                           "--density",
                           "--cloud-bottom-m",
                           "--cloud-top-m",
                           "--extinction-per-m",
                           "--attenuation",
                           "--light-attenuation",
                           "--albedo",
                           "--g-forward",
                           "--g-backward",
                           "--lobe-weight",
                           "--powder",
                           "--ambient",
                           "--wind-mps",
                           "--time",
                           "--lat-deg",
                           "--lon-deg",
                           "--time-s",
                           "--seed",
                           "--steps",
                           "--light-steps",
                           "--march-stride",
                           "--cloud-downsample",
                           "--light-volume-km",
                           "--mode",
                           "--weather-map",
                           "--voxel-march",
                           "--voxel-shadow",
                           "--voxel-cloud",
                           "--exposure"})
    EXPECT_NO_THROW(app.get_option(flag)) << flag;
  for (const char* flag : {"--output", "--stats-json", "--verbose", "--device"})
    EXPECT_THROW(app.get_option(flag), CLI::OptionNotFound) << flag;
}

// One flag, its value, and a check that it landed in the right field.
struct Override {
  std::vector<std::string> args;
  std::function<bool(const Scene&)> landed;
};

TEST(SceneFlags, EveryOverrideLandsInItsField) {
  const Override overrides[] = {
      {{"--width", "640"}, [](const Scene& s) { return s.output.width == 640; }},
      {{"--height", "+480"}, [](const Scene& s) { return s.output.height == 480; }},
      {{"--camera-altitude-m", "123.5"},
       [](const Scene& s) { return s.camera.position_m.z == 123.5f; }},
      {{"--camera-pos", "1,2.5,3"},
       [](const Scene& s) { return s.camera.position_m == glm::vec3(1.0f, 2.5f, 3.0f); }},
      {{"--view-dir", "0, 1, -0.5"},
       [](const Scene& s) { return s.camera.view_dir == glm::vec3(0.0f, 1.0f, -0.5f); }},
      {{"--fov-deg", "45"}, [](const Scene& s) { return s.camera.fov_deg == 45.0f; }},
      {{"--roll-deg", "-12.5"}, [](const Scene& s) { return s.camera.roll_deg == -12.5f; }},
      {{"--sun-dir", "1,0,1"},
       [](const Scene& s) { return s.sun.direction == glm::vec3(1.0f, 0.0f, 1.0f); }},
      {{"--sun-illuminance", "3e1"},
       [](const Scene& s) { return s.sun.illuminance_lux == 30.0f * 6400.0f; }},
      {{"--sun-illuminance-lux", "1e5"},
       [](const Scene& s) { return s.sun.illuminance_lux == 1e5f; }},
      {{"--cloud-lighting", "two-stream"},
       [](const Scene& s) { return s.clouds.lighting == "two-stream"; }},
      {{"--two-stream-light", "true"},  // the old switch
       [](const Scene& s) { return s.clouds.lighting == "two-stream"; }},
      {{"--coverage", "0.9"}, [](const Scene& s) { return s.clouds.coverage == 0.9f; }},
      {{"--density", "0.1"}, [](const Scene& s) { return s.clouds.density == 0.1f; }},
      {{"--cloud-bottom-m", "900"},
       [](const Scene& s) { return s.clouds.bottom_altitude_m == 900.0f; }},
      {{"--cloud-top-m", "7000"},
       [](const Scene& s) { return s.clouds.top_altitude_m == 7000.0f; }},
      {{"--extinction-per-m", "0.02", "--cloud-optics", "seed"},
       [](const Scene& s) { return s.clouds.extinction_per_m == 0.02f; }},
      {{"--attenuation", "1.5"}, [](const Scene& s) { return s.clouds.attenuation == 1.5f; }},
      {{"--light-attenuation", "0.5"},
       [](const Scene& s) { return s.clouds.light_attenuation == 0.5f; }},
      {{"--albedo", "0.9", "--cloud-optics", "seed"},
       [](const Scene& s) { return s.clouds.albedo == 0.9f; }},
      {{"--g-forward", "0.6", "--cloud-optics", "seed"},
       [](const Scene& s) { return s.clouds.phase_g_forward == 0.6f; }},
      {{"--g-backward", "-0.6", "--cloud-optics", "seed"},
       [](const Scene& s) { return s.clouds.phase_g_backward == -0.6f; }},
      {{"--lobe-weight", "0.25", "--cloud-optics", "seed"},
       [](const Scene& s) { return s.clouds.phase_lobe_weight == 0.25f; }},
      {{"--powder", "0"}, [](const Scene& s) { return s.clouds.powder_strength == 0.0f; }},
      // A string field's flag takes the word as typed, or a quoted TOML string.
      {{"--cloud-optics", "seed"}, [](const Scene& s) { return s.clouds.optics == "seed"; }},
      {{"--cloud-optics", "\"seed\""}, [](const Scene& s) { return s.clouds.optics == "seed"; }},
      {{"--ambient", "2"}, [](const Scene& s) { return s.clouds.ambient_strength == 2.0f; }},
      {{"--wind-mps", "-3,4"},
       [](const Scene& s) { return s.clouds.wind_mps == glm::vec2(-3.0f, 4.0f); }},
      {{"--wind-shear-mps", "1,-2"},
       [](const Scene& s) { return s.clouds.wind_shear_mps == glm::vec2(1.0f, -2.0f); }},
      {{"--detail-drift-mps", "5,0,1.5"},
       [](const Scene& s) { return s.clouds.detail_drift_mps == glm::vec3(5.0f, 0.0f, 1.5f); }},
      {{"--flow-speed-mps", "2.5"}, [](const Scene& s) { return s.clouds.flow_speed_mps == 2.5f; }},
      {{"--high-coverage", "0.4"}, [](const Scene& s) { return s.high_clouds.coverage == 0.4f; }},
      {{"--high-cloud-type", "0.25"}, [](const Scene& s) { return s.high_clouds.type == 0.25f; }},
      {{"--high-bottom-m", "6500"},
       [](const Scene& s) { return s.high_clouds.bottom_altitude_m == 6500.0f; }},
      {{"--high-top-m", "8000"},
       [](const Scene& s) { return s.high_clouds.top_altitude_m == 8000.0f; }},
      {{"--high-wind-mps", "20,-1"},
       [](const Scene& s) { return s.high_clouds.wind_mps == glm::vec2(20.0f, -1.0f); }},
      {{"--time-s", "60"}, [](const Scene& s) { return s.time_s == 60.0f; }},
      {{"--time", "2026-06-21T18:30:00Z"},
       [](const Scene& s) { return s.time == "2026-06-21T18:30:00Z" && s.sun.from_time; }},
      {{"--lat-deg", "-33.5"}, [](const Scene& s) { return s.location.lat_deg == -33.5f; }},
      {{"--lon-deg", "151.25"}, [](const Scene& s) { return s.location.lon_deg == 151.25f; }},
      {{"--seed", "4294967295"}, [](const Scene& s) { return s.noise_seed == 4294967295u; }},
      {{"--steps", "128"}, [](const Scene& s) { return s.quality.primary_steps == 128; }},
      {{"--light-steps", "10"}, [](const Scene& s) { return s.quality.light_steps == 10; }},
      {{"--march-stride", "2"}, [](const Scene& s) { return s.quality.march_stride == 2; }},
      {{"--cloud-downsample", "1"}, [](const Scene& s) { return s.quality.cloud_downsample == 1; }},
      {{"--light-volume-km", "0"}, [](const Scene& s) { return s.quality.light_volume_km == 0; }},
      {{"--mode", "baseline"},
       [](const Scene& s) { return s.quality.mode == MarchMode::Baseline; }},
      {{"--exposure", "0.25"},  // the old linear exposure: log2(5333 / 0.25), manual
       [](const Scene& s) {
         return std::abs(s.output.ev100 - 14.3808f) < 1e-3f && !s.output.auto_exposure;
       }},
      {{"--ev100", "9"},
       [](const Scene& s) { return s.output.ev100 == 9.0f && !s.output.auto_exposure; }},
      {{"--ev100-min", "-3"}, [](const Scene& s) { return s.output.ev100_min == -3.0f; }},
      {{"--ev100-max", "16"}, [](const Scene& s) { return s.output.ev100_max == 16.0f; }},
      {{"--exposure-compensation-ev", "1.5"},
       [](const Scene& s) { return s.output.exposure_compensation_ev == 1.5f; }},
      {{"--adaptation-ev-per-s", "0"},
       [](const Scene& s) { return s.output.adaptation_ev_per_s == 0.0f; }},
      {{"--hfov", "90"},
       [](const Scene& s) {
         return s.camera.horizontal_fov_deg == 90.0f && s.camera.focal_length_mm == 0.0f;
       }},
      {{"--focal-length-mm", "50"},
       [](const Scene& s) {
         return s.camera.focal_length_mm == 50.0f && s.camera.horizontal_fov_deg == 0.0f;
       }},
      {{"--sensor-width-mm", "24"},
       [](const Scene& s) { return s.camera.sensor_width_mm == 24.0f; }},
      {{"--voxel-march", "plain"},
       [](const Scene& s) { return s.quality.voxel_march == VoxelMarch::Plain; }},
      {{"--voxel-march", "three-phase"},
       [](const Scene& s) { return s.quality.voxel_march == VoxelMarch::ThreePhase; }},
      {{"--voxel-shadow", "sdf-cone"},
       [](const Scene& s) { return s.quality.voxel_shadow == VoxelShadow::SdfCone; }},
      {{"--voxel-shadow", "march"},
       [](const Scene& s) { return s.quality.voxel_shadow == VoxelShadow::LightMarch; }},
  };
  for (const Override& o : overrides) {
    SCOPED_TRACE(o.args[0] + " " + o.args[1]);
    Scene scene;
    ASSERT_NO_THROW(scene = resolve(o.args));
    EXPECT_TRUE(o.landed(scene));
  }
}

TEST(SceneFlags, NegativeValuesAreValuesNotFlags) {
  Scene scene =
      resolve({"--sun-elevation-deg", "-5", "--cloud-optics", "seed", "--g-backward", "-0.2"});
  EXPECT_NEAR(sun_angles_from_direction(scene.sun.direction).elevation_deg, -5.0, 1e-4);
  EXPECT_EQ(scene.clouds.phase_g_backward, -0.2f);
  scene = resolve({"--view-dir=-1,0,0.2", "--wind-mps=-1,-2"});
  EXPECT_EQ(scene.camera.view_dir, glm::vec3(-1.0f, 0.0f, 0.2f));
  EXPECT_EQ(scene.clouds.wind_mps, glm::vec2(-1.0f, -2.0f));
}

TEST(SceneFlags, SunAnglesReplaceTheDirection) {
  expect_near(resolve({"--sun-elevation-deg", "90", "--sun-azimuth-deg", "0"}).sun.direction,
              {0.0f, 0.0f, 1.0f});
  expect_near(resolve({"--sun-elevation-deg", "0", "--sun-azimuth-deg", "90"}).sun.direction,
              {1.0f, 0.0f, 0.0f});
  // Only one angle: the other keeps the preset's value.
  SunAngles preset = sun_angles_from_direction(load_preset("default").sun.direction);
  SunAngles changed =
      sun_angles_from_direction(resolve({"--sun-azimuth-deg", "200"}).sun.direction);
  EXPECT_NEAR(changed.elevation_deg, preset.elevation_deg, 1e-4);
  EXPECT_NEAR(changed.azimuth_deg, 200.0, 1e-4);
  changed = sun_angles_from_direction(resolve({"--sun-elevation-deg", "10"}).sun.direction);
  EXPECT_NEAR(changed.elevation_deg, 10.0, 1e-4);
  EXPECT_NEAR(changed.azimuth_deg, preset.azimuth_deg, 1e-4);
}

TEST(SceneFlags, SunFlagsOverrideTheTime) {
  Scene s = resolve({"--time", "2026-06-21T18:30:00Z", "--sun-elevation-deg", "30"});
  EXPECT_FALSE(s.sun.from_time);
  EXPECT_NEAR(sun_angles_from_direction(s.sun.direction).elevation_deg, 30.0, 1e-4);
  s = resolve({"--time", "2026-06-21T18:30:00Z", "--sun-dir", "0,1,1"});
  EXPECT_FALSE(s.sun.from_time);
}

TEST(SceneFlags, ValidationErrorsNameTheFlag) {
  EXPECT_EQ(resolve_error({"--time", "tomorrow"}),
            "--time tomorrow: must be an ISO 8601 date and time with a zone, like "
            "2026-06-21T18:30:00Z");
  EXPECT_EQ(resolve_error({"--lat-deg", "-91"}), "--lat-deg -91: must be in [-90, 90]");
  EXPECT_EQ(resolve_error({"--coverage", "1.5"}), "--coverage 1.5: must be in [0, 1]");
  EXPECT_EQ(resolve_error({"--view-dir", "0,0,0"}),
            "--view-dir 0,0,0: must be a finite vector of length in [1e-06, 1e+06]");
  EXPECT_EQ(resolve_error({"--sun-dir", "0,0,0"}),
            "--sun-dir 0,0,0: must be a finite vector of length in [1e-06, 1e+06]");
  EXPECT_EQ(resolve_error({"--width", "0"}), "--width 0: must be in [1, 16384]");
  EXPECT_EQ(resolve_error({"--steps", "2000"}), "--steps 2000: must be in [1, 1024]");
  EXPECT_EQ(resolve_error({"--light-steps", "65"}), "--light-steps 65: must be in [1, 64]");
  EXPECT_EQ(resolve_error({"--march-stride", "3"}), "--march-stride 3: must be 1, 2 or 4");
  EXPECT_EQ(resolve_error({"--fov-deg", "180"}), "--fov-deg 180: must be in [0.01, 180)");
  EXPECT_EQ(resolve_error({"--roll-deg", "181"}), "--roll-deg 181: must be in [-180, 180]");
  EXPECT_EQ(resolve_error({"--g-backward", "0.5"}), "--g-backward 0.5: must be in (-1, 0]");
  EXPECT_EQ(resolve_error({"--exposure", "nan"}), "--exposure nan: must be in [5e-06, 1e+06] (the old linear exposure, read as --ev100 "
            "log2(5333 / X) in [-7.55, 30])");
  EXPECT_EQ(resolve_error({"--camera-altitude-m", "-1"}),
            "--camera-altitude-m -1: must be >= 0 (the camera is below the ground)");
  EXPECT_EQ(resolve_error({"--cloud-bottom-m", "5000", "--cloud-top-m", "4000"}),
            "--cloud-bottom-m 5000: must be below --cloud-top-m (4000)");
  // Layers may not overlap, and the cirrus sheet lies above the highest one.
  EXPECT_EQ(resolve_error({"--high-coverage", "0.3", "--high-bottom-m", "3500"}),
            "--high-bottom-m 3500: must be at or above clouds.top_altitude_m (4000)");
  EXPECT_EQ(resolve_error({"--high-coverage", "0.3", "--cirrus-coverage", "0.5",
                           "--cirrus-altitude-m", "6500"}),
            "preset 'default': high_clouds.top_altitude_m = 7000: must be below --cirrus-altitude-m "
            "(6500)");
  EXPECT_EQ(resolve_error({"--flow-speed-mps", "-1"}),
            "--flow-speed-mps -1: must be in [0, 200]");
  EXPECT_EQ(resolve_error({"--weather-map", "/nonexistent/nephele.png"}),
            "--weather-map /nonexistent/nephele.png: cannot read the file");
  EXPECT_EQ(resolve_error({"--camera-pos", "0,0,-3"}),
            "--camera-pos 0,0,-3: the up component must be >= 0 (the camera is below the ground)");
}

TEST(SceneFlags, ValuesNotFromFlagsNameTheirOrigin) {
  // The preset's cloud bottom is fine; lowering the top below it blames the bottom, which
  // came from the preset, and the flag that made it wrong.
  EXPECT_EQ(resolve_error({"--cloud-top-m", "1000"}),
            "preset 'default': clouds.bottom_altitude_m = 1500: must be below --cloud-top-m (1000)");
}

TEST(SceneFlags, MalformedValuesNameTheFlag) {
  EXPECT_EQ(resolve_error({"--coverage", "abc"}), "--coverage abc: expected a number");
  EXPECT_EQ(resolve_error({"--coverage", "0.5x"}), "--coverage 0.5x: expected a number");
  EXPECT_EQ(resolve_error({"--coverage", ""}), "--coverage : expected a number");
  EXPECT_EQ(resolve_error({"--view-dir", "1,2"}),
            "--view-dir 1,2: expected 3 comma-separated numbers E,N,U");
  EXPECT_EQ(resolve_error({"--sun-dir", "1,2,3,4"}),
            "--sun-dir 1,2,3,4: expected 3 comma-separated numbers E,N,U");
  EXPECT_EQ(resolve_error({"--camera-pos", "1,,3"}),
            "--camera-pos 1,,3: expected 3 comma-separated numbers E,N,U");
  EXPECT_EQ(resolve_error({"--wind-mps", "a,b"}),
            "--wind-mps a,b: expected 2 comma-separated numbers E,N");
  EXPECT_EQ(resolve_error({"--width", "12.5"}),
            "--width 12.5: expected an integer in [1, 16384]");  // the key's range, not int's
  EXPECT_EQ(resolve_error({"--march-stride", "2.5"}),
            "--march-stride 2.5: expected an integer: 1, 2 or 4");
  EXPECT_EQ(resolve_error({"--seed", "-1"}), "--seed -1: expected an integer in [0, 4294967295]");
  EXPECT_EQ(resolve_error({"--two-stream-light", "yes"}),
            "--two-stream-light yes: expected true or false");
  EXPECT_EQ(resolve_error({"--two-stream-light", "true", "--cloud-lighting", "seed"}),
            "--two-stream-light cannot be combined with --cloud-lighting (true is two-stream, "
            "false seed)");
  EXPECT_EQ(resolve_error({"--mode", "fast"}), "--mode fast: expected default or baseline");
  EXPECT_EQ(resolve_error({"--voxel-march", "three_phase"}),
            "--voxel-march three_phase: expected plain or three-phase");
  EXPECT_EQ(resolve_error({"--voxel-shadow", "cone"}),
            "--voxel-shadow cone: expected march or sdf-cone");
  EXPECT_EQ(resolve_error({"--sun-elevation-deg", "x"}),
            "--sun-elevation-deg x: expected a number");
  EXPECT_EQ(resolve_error({"--sun-elevation-deg", "91"}),
            "--sun-elevation-deg 91: must be in [-90, 90]");
  EXPECT_EQ(resolve_error({"--sun-azimuth-deg", "inf"}), "--sun-azimuth-deg inf: must be finite");
  EXPECT_EQ(resolve_error({"--density", "1e60"}), "--density 1e60: is out of range");
}

TEST(SceneFlags, VoxelCloudSpecsAppendClouds) {
  const Scene scene = resolve({"--voxel-cloud", "preset:cumulus:7@0,4000,1200", "--voxel-cloud",
                               "preset:cumulonimbus@-1.5,+2,1e3",
                               "--voxel-cloud=preset:cumulus-congestus:4294967295@0,0,0"});
  ASSERT_EQ(scene.voxel_clouds.size(), 3u);
  const VoxelCloudParams& a = scene.voxel_clouds[0];
  EXPECT_EQ(a.preset, "cumulus");
  EXPECT_EQ(a.file, "");
  EXPECT_EQ(a.seed, 7u);
  EXPECT_EQ(a.position_m, glm::vec3(0.0f, 4000.0f, 1200.0f));
  EXPECT_EQ(a.scale, VoxelCloudParams{}.scale);  // the rest at their defaults
  EXPECT_EQ(a.resolution, VoxelCloudParams{}.resolution);
  EXPECT_EQ(scene.voxel_clouds[1].preset, "cumulonimbus");
  EXPECT_EQ(scene.voxel_clouds[1].seed, VoxelCloudParams{}.seed);
  EXPECT_EQ(scene.voxel_clouds[1].position_m, glm::vec3(-1.5f, 2.0f, 1000.0f));
  EXPECT_EQ(scene.voxel_clouds[2].preset, "cumulus-congestus");
  EXPECT_EQ(scene.voxel_clouds[2].seed, 4294967295u);
  EXPECT_TRUE(resolve({}).voxel_clouds.empty());

  // A file: the last '@' starts the position; the path is taken as given.
  const VoxelCloudParams file = parse_voxel_cloud_spec("clouds/a@b.vdb@1,2,3");
  EXPECT_EQ(file.file, "clouds/a@b.vdb");
  EXPECT_EQ(file.preset, "");
  EXPECT_EQ(file.position_m, glm::vec3(1.0f, 2.0f, 3.0f));
}

TEST(SceneFlags, BadVoxelCloudSpecsNameTheFlagTheValueAndTheForms) {
  const std::string forms =
      "; expected FILE@E,N,U or preset:NAME[:SEED]@E,N,U, NAME one of cumulus, "
      "cumulus-congestus, cumulonimbus, cumulus-mesh (e.g. preset:cumulus:7@0,4000,1200)";
  const std::pair<const char*, const char*> bad[] = {
      {"preset:cumulus", "no @E,N,U position"},
      {"preset:cumulus@0,0", "the position is not 3 comma-separated numbers"},
      {"preset:cumulus@0,0,0,0", "the position is not 3 comma-separated numbers"},
      {"preset:cumulus@", "the position is not 3 comma-separated numbers"},
      {"preset:cumulus@a,0,0", "the position's 'a' is not a number"},
      {"preset:cumulus@0,,0", "the position's '' is not a number"},
      {"preset:cumulus@0,0,1e60", "the position's '1e60' is not a number"},
      {"preset:cirrus@0,0,0", "unknown preset 'cirrus'"},
      {"preset:@0,0,0", "unknown preset ''"},
      {"preset:cumulus:x@0,0,0", "the seed 'x' is not an integer in [0, 4294967295]"},
      {"preset:cumulus:-1@0,0,0", "the seed '-1' is not an integer in [0, 4294967295]"},
      {"preset:cumulus:@0,0,0", "the seed '' is not an integer in [0, 4294967295]"},
      {"preset:cumulus:4294967296@0,0,0",
       "the seed '4294967296' is not an integer in [0, 4294967295]"},
      {"@0,0,0", "no file before the @"},
      {"", "no @E,N,U position"},
  };
  for (const auto& [spec, why] : bad)
    EXPECT_EQ(resolve_error({"--voxel-cloud", spec}),
              std::string("--voxel-cloud ") + spec + ": " + why + forms);
}

TEST(SceneFlags, VoxelCloudsFromFlagsAreValidatedUnderTheFlag) {
  EXPECT_EQ(resolve_error({"--voxel-cloud", "preset:cumulus@0,0,2e5"}),
            "--voxel-cloud 0,0,2e+05: up must be in [-1000, 1e+05] m");
  EXPECT_EQ(resolve_error({"--voxel-cloud", "cloud.obj@0,0,0"}),
            "--voxel-cloud cloud.obj: must be an OpenVDB (.vdb) or NanoVDB (.nvdb) file");
  EXPECT_EQ(resolve_error({"--voxel-cloud", "/nonexistent/c.vdb@0,0,0"}),
            "--voxel-cloud /nonexistent/c.vdb: cannot read the file");
  std::vector<std::string> args;
  for (int i = 0; i <= kMaxVoxelClouds; ++i)
    args.insert(args.end(), {"--voxel-cloud", "preset:cumulus@0,0,1000"});
  EXPECT_EQ(resolve_error(args),
            "--voxel-cloud: 17 voxel clouds (0 in the scene, 17 from --voxel-cloud): at most 16 "
            "voxel clouds per scene");
  args.resize(args.size() - 2);
  EXPECT_EQ(resolve(args).voxel_clouds.size(), size_t(kMaxVoxelClouds));
}

TEST(SceneFlags, ConflictingFlags) {
  EXPECT_NE(resolve_error({"--scene", "a.toml", "--preset", "default"})
                .find("--scene and --preset cannot be combined"),
            std::string::npos);
  EXPECT_NE(resolve_error({"--sun-dir", "0,1,1", "--sun-elevation-deg", "20"})
                .find("--sun-dir cannot be combined with --sun-elevation-deg"),
            std::string::npos);
  EXPECT_NE(resolve_error({"--sun-dir", "0,1,1", "--sun-azimuth-deg", "20"})
                .find("--sun-dir cannot be combined"),
            std::string::npos);
  EXPECT_NE(resolve_error({"--camera-pos", "0,0,5", "--camera-altitude-m", "20"})
                .find("--camera-pos and --camera-altitude-m cannot be combined"),
            std::string::npos);
}

TEST(SceneFlags, UnknownPresetListsAvailable) {
  std::string message = resolve_error({"--preset", "foo"});
  EXPECT_EQ(message.rfind("--preset 'foo': unknown preset (available: ", 0), 0u) << message;
  EXPECT_NE(message.find("sunset"), std::string::npos) << message;
}

class SceneFlagsFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("nephele_flags_test_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(SceneFlagsFile, SceneFileThenOverrides) {
  std::string path = (dir_ / "scene.toml").string();
  std::ofstream(path) << "preset = \"sunset\"\n[clouds]\ncoverage = 0.6\ndensity = 0.3\n";
  Scene scene = resolve({"--scene", path, "--density", "0.8"});
  EXPECT_EQ(scene.clouds.coverage, 0.6f);  // from the file
  EXPECT_EQ(scene.clouds.density, 0.8f);   // the flag wins
  EXPECT_EQ(scene.sun.direction, load_preset("sunset").sun.direction);
}

TEST_F(SceneFlagsFile, FileValuesAreNamedWithTheFile) {
  std::string path = (dir_ / "scene.toml").string();
  std::ofstream(path) << "[clouds]\ncoverage = 1.5\n";
  EXPECT_EQ(resolve_error({"--scene", path}), path + ": clouds.coverage = 1.5: must be in [0, 1]");
  // A flag can repair what the file got wrong: validation runs after the overrides.
  EXPECT_EQ(resolve({"--scene", path, "--coverage", "0.5"}).clouds.coverage, 0.5f);
}

TEST_F(SceneFlagsFile, VoxelCloudFlagsFollowTheFilesClouds) {
  const std::string path = (dir_ / "scene.toml").string();
  std::ofstream(path) << "[[voxel_clouds]]\npreset = \"cumulus\"\ndensity = 200\n";
  // The file's cloud is named with the file, a flag's with the flag.
  EXPECT_EQ(resolve_error({"--scene", path, "--voxel-cloud", "preset:cumulonimbus@0,0,0"}),
            path + ": voxel_clouds[0].density = 200: must be in [0, 100]");
  std::ofstream(path) << "[[voxel_clouds]]\npreset = \"cumulus\"\n";
  const Scene scene = resolve({"--scene", path, "--voxel-cloud", "preset:cumulonimbus@0,0,0"});
  ASSERT_EQ(scene.voxel_clouds.size(), 2u);
  EXPECT_EQ(scene.voxel_clouds[0].preset, "cumulus");
  EXPECT_EQ(scene.voxel_clouds[1].preset, "cumulonimbus");
  std::vector<std::string> args = {"--scene", path};
  for (int i = 0; i < kMaxVoxelClouds; ++i)
    args.insert(args.end(), {"--voxel-cloud", "preset:cumulus@0,0,1000"});
  EXPECT_EQ(resolve_error(args),
            "--voxel-cloud: 17 voxel clouds (1 in the scene, 16 from --voxel-cloud): at most 16 "
            "voxel clouds per scene");
}

TEST_F(SceneFlagsFile, MissingSceneFile) {
  std::string path = (dir_ / "nope.toml").string();
  std::string message = resolve_error({"--scene", path});
  EXPECT_NE(message.find(path), std::string::npos) << message;
}

TEST_F(SceneFlagsFile, WeatherMapFlagIsTakenAsGiven) {
  std::string path = (dir_ / "w.png").string();
  const unsigned char rgba[2 * 2 * 4] = {};
  ASSERT_TRUE(stbi_write_png(path.c_str(), 2, 2, 4, rgba, 2 * 4));
  EXPECT_EQ(resolve({"--weather-map", path}).clouds.weather_map, path);
}

}  // namespace
}  // namespace nephele::cli
