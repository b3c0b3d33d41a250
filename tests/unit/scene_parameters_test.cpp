// The scene's parameters one at a time: scene_parameters(), get_scene_value, set_scene_value.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <set>
#include <sstream>

#include "nephele/error.h"
#include "nephele/scene_io.h"

namespace nephele {
namespace {

std::string input_error(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const InputError& error) {
    return error.what();
  }
  ADD_FAILURE() << "no InputError thrown";
  return "";
}

// "section.key" for every `key = value` line of scene_to_toml.
std::vector<std::string> keys_of_toml(const std::string& toml) {
  std::vector<std::string> keys;
  std::istringstream in(toml);
  std::string line, section;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (line[0] == '[') {
      section = line.substr(1, line.find(']') - 1);
      continue;
    }
    const std::string name = line.substr(0, line.find(" = "));
    keys.push_back(section.empty() ? name : section + "." + name);
  }
  return keys;
}

const SceneParameter& parameter(const std::string& key) {
  const auto& all = scene_parameters();
  auto it = std::find_if(all.begin(), all.end(), [&](const auto& p) { return p.key == key; });
  if (it == all.end()) throw std::runtime_error("no parameter " + key);
  return *it;
}

// A scene unlike the defaults in every section.
Scene unusual_scene() {
  Scene scene = load_preset(preset_names().back());
  scene.voxel_clouds.clear();  // an array: not in the parameter table
  scene.time = "2026-06-21T18:30:00Z";
  scene.time_s = 12.5f;
  scene.noise_seed = 7;
  scene.camera.position_m = {10.0f, -20.0f, 300.0f};
  scene.clouds.coverage = 0.8125f;
  scene.clouds.weather_map = "maps/w \"1\".png";
  scene.atmosphere.model = SkyModel::Preetham;
  scene.quality.mode = MarchMode::Baseline;
  scene.quality.voxel_march = VoxelMarch::Plain;
  scene.quality.voxel_shadow = VoxelShadow::SdfCone;
  scene.quality.sdf_light_tangent = 2.5f;
  scene.conditions.mode = ConditionsMode::Overlay;
  scene.conditions.bad.keys[3].set.fog_far_m = 1234.5f;
  scene.output.auto_exposure = true;
  scene.sun.from_time = true;
  return scene;
}

TEST(SceneParameters, AreTheKeysOfTheSceneFileInItsOrder) {
  std::vector<std::string> keys;
  for (const SceneParameter& p : scene_parameters()) keys.push_back(p.key);
  EXPECT_EQ(keys, keys_of_toml(scene_to_toml(Scene{})));
  EXPECT_EQ(std::set<std::string>(keys.begin(), keys.end()).size(), keys.size());
}

TEST(SceneParameters, KindsAllowedValuesAndNotes) {
  EXPECT_EQ(parameter("clouds.coverage").kind, SceneValueKind::kFloat);
  EXPECT_EQ(parameter("clouds.coverage").note, "[0, 1]: share of the sky the layer covers");
  EXPECT_EQ(parameter("clouds.coverage").allowed_values, "[0, 1]");
  EXPECT_EQ(parameter("clouds.coverage").meaning, "share of the sky the layer covers");
  EXPECT_EQ(parameter("clouds.coverage").min, 0.0);
  EXPECT_EQ(parameter("clouds.coverage").max, 1.0);
  EXPECT_EQ(parameter("clouds.weather_evolution_s").allowed_values, "0 or [1, 1e+07]");
  EXPECT_EQ(parameter("clouds.weather_evolution_s").off, 0.0);
  EXPECT_EQ(parameter("quality.march_stride").allowed_values, "1, 2 or 4");
  EXPECT_EQ(parameter("quality.primary_steps").kind, SceneValueKind::kInt);
  EXPECT_EQ(parameter("noise_seed").kind, SceneValueKind::kUint);
  EXPECT_EQ(parameter("clouds.wind_mps").kind, SceneValueKind::kVec2);
  EXPECT_EQ(parameter("camera.position_m").kind, SceneValueKind::kVec3);
  EXPECT_EQ(parameter("clouds.weather_map").kind, SceneValueKind::kString);
  EXPECT_EQ(parameter("output.auto_exposure").kind, SceneValueKind::kBool);
  EXPECT_EQ(parameter("atmosphere.model").kind, SceneValueKind::kEnum);
  EXPECT_EQ(parameter("atmosphere.model").allowed,
            (std::vector<std::string>{"hillaire", "preetham", "reference"}));
  EXPECT_EQ(parameter("quality.mode").allowed, (std::vector<std::string>{"default", "baseline"}));
  EXPECT_EQ(parameter("conditions.mode").allowed,
            (std::vector<std::string>{"off", "artist", "overlay"}));
  EXPECT_EQ(parameter("quality.voxel_march").kind, SceneValueKind::kEnum);
  EXPECT_EQ(parameter("quality.voxel_march").allowed,
            (std::vector<std::string>{"plain", "three-phase"}));
  EXPECT_EQ(parameter("quality.voxel_shadow").allowed,
            (std::vector<std::string>{"march", "sdf-cone"}));
  EXPECT_EQ(parameter("quality.sdf_light_tangent").kind, SceneValueKind::kFloat);
  EXPECT_EQ(parameter("quality.sdf_light_tangent").note,
            "[0.001, 10]: the SDF cone's half-angle tangent");
  EXPECT_TRUE(parameter("clouds.coverage").allowed.empty());
  EXPECT_NE(parameter("conditions.good.night.hour").note.find("[0, 24)"), std::string::npos);
}

TEST(SceneParameters, EveryKeyRoundTripsThroughGetAndSet) {
  const Scene source = unusual_scene();
  Scene copy;  // the defaults
  for (const SceneParameter& p : scene_parameters()) {
    const std::string value = get_scene_value(source, p.key);
    ASSERT_NO_THROW(set_scene_value(copy, p.key, value)) << p.key << " = " << value;
    EXPECT_EQ(get_scene_value(copy, p.key), value) << p.key;
  }
  EXPECT_EQ(scene_to_toml(copy), scene_to_toml(source));
}

TEST(SceneParameters, GetGivesTomlLiterals) {
  Scene scene;
  scene.clouds.coverage = 0.9f;
  EXPECT_EQ(get_scene_value(scene, "clouds.coverage"), "0.9");
  EXPECT_EQ(get_scene_value(scene, "clouds.wind_mps"), "[8.0, 2.0]");
  EXPECT_EQ(get_scene_value(scene, "atmosphere.model"), "\"hillaire\"");
  EXPECT_EQ(get_scene_value(scene, "output.width"), "900");
  EXPECT_EQ(get_scene_value(scene, "output.auto_exposure"), "true");
  EXPECT_EQ(get_scene_value(scene, "time"), "\"\"");
}

TEST(SceneParameters, SetChangesThatKeyAlone) {
  Scene scene;
  set_scene_value(scene, "clouds.coverage", "0.9");
  EXPECT_EQ(scene.clouds.coverage, 0.9f);
  set_scene_value(scene, "clouds.coverage", "1");  // an integer literal is a number too
  EXPECT_EQ(scene.clouds.coverage, 1.0f);
  set_scene_value(scene, "camera.position_m", "[1, 2, 3]");
  EXPECT_EQ(scene.camera.position_m, glm::vec3(1.0f, 2.0f, 3.0f));
  set_scene_value(scene, "clouds.weather_map", "\"file.png\"");
  EXPECT_EQ(scene.clouds.weather_map, "file.png");  // no folder to resolve it against
  set_scene_value(scene, "atmosphere.model", "'preetham'");
  EXPECT_EQ(scene.atmosphere.model, SkyModel::Preetham);
  set_scene_value(scene, "time", "2026-06-21T18:30:00Z");  // unquoted, as in a file
  EXPECT_EQ(scene.time, "2026-06-21T18:30:00Z");
  EXPECT_FALSE(scene.sun.from_time);  // a file would move the sun; one value does not
  set_scene_value(scene, "conditions.bad.morning.fog_near_m", "15.0  # a comment");
  EXPECT_EQ(scene.conditions.bad.keys[2].set.fog_near_m, 15.0f);

  Scene expected;
  expected.clouds.coverage = 1.0f;
  expected.camera.position_m = {1.0f, 2.0f, 3.0f};
  expected.clouds.weather_map = "file.png";
  expected.atmosphere.model = SkyModel::Preetham;
  expected.time = "2026-06-21T18:30:00Z";
  expected.conditions.bad.keys[2].set.fog_near_m = 15.0f;
  EXPECT_EQ(scene_to_toml(scene), scene_to_toml(expected));
}

TEST(SceneParameters, UnknownKeysAreNamedWithTheAllowedOnes) {
  Scene scene;
  EXPECT_EQ(input_error([&] { set_scene_value(scene, "clouds.cover", "0.5"); }).rfind(
                "unknown scene key 'clouds.cover' (allowed in [clouds]: model, bottom_altitude_m, ", 0),
            0u);
  EXPECT_NE(input_error([&] { get_scene_value(scene, "cloud.coverage"); })
                .find("unknown scene key 'cloud.coverage' (allowed tables: location camera sun"),
            std::string::npos);
  EXPECT_NE(input_error([&] { set_scene_value(scene, "seed", "1"); })
                .find("(allowed at the top level: time, time_s, noise_seed)"),
            std::string::npos);
  // A table is not a value.
  EXPECT_NE(input_error([&] { set_scene_value(scene, "clouds", "1"); }).find("'clouds'"),
            std::string::npos);
  EXPECT_NE(input_error([&] { set_scene_value(scene, "", "1"); }).find("unknown scene key ''"),
            std::string::npos);
}

TEST(SceneParameters, WrongTypesNameTheKeyAndLeaveTheSceneAlone) {
  Scene scene;
  const std::string before = scene_to_toml(scene);
  EXPECT_EQ(input_error([&] { set_scene_value(scene, "clouds.coverage", "\"x\""); }),
            "clouds.coverage = \"x\": expected a number");
  EXPECT_EQ(input_error([&] { set_scene_value(scene, "quality.primary_steps", "2.5"); }),
            "quality.primary_steps = 2.5: expected an integer in [1, 1024]");  // the key's range
  EXPECT_EQ(input_error([&] { set_scene_value(scene, "quality.march_stride", "2.5"); }),
            "quality.march_stride = 2.5: expected an integer: 1, 2 or 4");
  EXPECT_EQ(input_error([&] { set_scene_value(scene, "noise_seed", "-1"); }),
            "noise_seed = -1: expected an integer in [0, 4294967295]");
  EXPECT_EQ(input_error([&] { set_scene_value(scene, "clouds.wind_mps", "[1, 2, 3]"); }),
            "clouds.wind_mps = [1, 2, 3]: expected an array of 2 numbers");
  EXPECT_EQ(input_error([&] { set_scene_value(scene, "output.auto_exposure", "1"); }),
            "output.auto_exposure = 1: expected true or false");
  EXPECT_EQ(input_error([&] { set_scene_value(scene, "atmosphere.model", "\"bruneton\""); }),
            "atmosphere.model = \"bruneton\": expected \"hillaire\", \"preetham\" or "
            "\"reference\"");
  EXPECT_EQ(input_error([&] { set_scene_value(scene, "clouds.weather_map", "map.png"); })
                .rfind("clouds.weather_map = map.png: not a TOML value (", 0),
            0u);
  EXPECT_EQ(input_error([&] { set_scene_value(scene, "clouds.coverage", ""); })
                .rfind("clouds.coverage = : not a TOML value (", 0),
            0u);
  EXPECT_EQ(input_error([&] { set_scene_value(scene, "clouds.coverage", "0.5\nclouds.density = 1"); }),
            "clouds.coverage = 0.5?clouds.density = 1: expected one TOML value on one line");
  EXPECT_EQ(scene_to_toml(scene), before);
}

TEST(SceneParameters, VoxelModesAreSetByName) {
  Scene scene;
  EXPECT_EQ(get_scene_value(scene, "quality.voxel_march"), "\"three-phase\"");
  EXPECT_EQ(get_scene_value(scene, "quality.voxel_shadow"), "\"march\"");
  set_scene_value(scene, "quality.voxel_march", "\"plain\"");
  set_scene_value(scene, "quality.voxel_shadow", "\"sdf-cone\"");
  set_scene_value(scene, "quality.sdf_light_tangent", "0.25");
  EXPECT_EQ(scene.quality.voxel_march, VoxelMarch::Plain);
  EXPECT_EQ(scene.quality.voxel_shadow, VoxelShadow::SdfCone);
  EXPECT_EQ(scene.quality.sdf_light_tangent, 0.25f);
  EXPECT_EQ(input_error([&] { set_scene_value(scene, "quality.voxel_shadow", "\"cone\""); }),
            "quality.voxel_shadow = \"cone\": expected \"march\" or \"sdf-cone\"");
}

// The voxel clouds are an array of varying length: not one parameter each, and a scene's clouds
// are kept by get/set of the others.
TEST(SceneParameters, VoxelCloudsAreNotParameters) {
  for (const SceneParameter& p : scene_parameters())
    EXPECT_FALSE(p.key.starts_with("voxel_clouds")) << p.key;
  Scene scene;
  scene.voxel_clouds.resize(2);
  scene.voxel_clouds[1].preset = "cumulus";
  set_scene_value(scene, "clouds.coverage", "0.25");
  ASSERT_EQ(scene.voxel_clouds.size(), 2u);
  EXPECT_EQ(scene.voxel_clouds[1].preset, "cumulus");
  EXPECT_NE(input_error([&] { get_scene_value(scene, "voxel_clouds"); }).find("unknown scene key"),
            std::string::npos);
}

TEST(SceneParameters, RangesAreLeftToValidation) {
  Scene scene;
  set_scene_value(scene, "clouds.coverage", "1.5");
  EXPECT_EQ(input_error([&] { validate_scene(scene); }), "clouds.coverage = 1.5: must be in [0, 1]");
}

}  // namespace
}  // namespace nephele
