// [[cloud_layers]]: volumetric layers given as a weather report gives them (genus, where the
// clouds' bases and tops are, oktas), read, written back and checked with one clear line.
#include <gtest/gtest.h>

#include <string>

#include "nephele/error.h"
#include "nephele/scene_io.h"
#include "render/frame_params.h"
#include "weather/weather_state.h"

namespace {

using nephele::CloudLayerParams;
using nephele::InputError;
using nephele::Scene;

const std::string kTwoLayers = R"(
[clouds]
bottom_altitude_m = 500
top_altitude_m = 1500
type = 0.25

[[cloud_layers]]
genus = "altocumulus"
base_m = 2500
top_m = 3200
oktas = 5

[[cloud_layers]]
genus = "cumulus"
base_m = 4200
top_m = 5600
oktas = 3
wind_mps = [12, -3]
)";

std::string error_of(const std::string& toml) {
  try {
    nephele::validate_scene(nephele::parse_scene_toml(toml, "layers.toml"));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(CloudLayers, AreReadWrittenAndReadBack) {
  const Scene s = nephele::parse_scene_toml(kTwoLayers, "layers.toml");
  ASSERT_EQ(s.cloud_layers.size(), 2u);
  EXPECT_EQ(s.cloud_layers[0].genus, "altocumulus");
  EXPECT_EQ(s.cloud_layers[1].oktas, 3.0f);
  EXPECT_EQ(s.cloud_layers[1].wind_mps, glm::vec2(12.0f, -3.0f));
  EXPECT_EQ(s.cloud_layers[0].density, CloudLayerParams{}.density);
  EXPECT_NO_THROW(nephele::validate_scene(s));
  const Scene back = nephele::parse_scene_toml(nephele::scene_to_toml(s), "written.toml");
  EXPECT_EQ(back.cloud_layers, s.cloud_layers);
}

// The renderer's shell puts the clouds' bases and tops where they are given, for each genus
// and cover; the shell of the whole field spans every layer that is there.
TEST(CloudLayers, TheShellPutsTheCloudsWhereTheyAreGiven) {
  for (const char* genus : {"stratus", "stratocumulus", "altocumulus", "cumulus", "cumulonimbus"})
    for (float oktas : {1.0f, 4.0f, 8.0f}) {
      CloudLayerParams l;
      l.genus = genus;
      l.base_m = 3000.0f;
      l.top_m = 3800.0f;
      l.oktas = oktas;
      const float type = nephele::weather::genus_type(*nephele::weather::parse_genus(genus));
      const glm::vec2 clouds =
          nephele::weather::clouds_in_shell_m(type, nephele::weather::cloud_layer_coverage(l),
                                              nephele::weather::cloud_layer_shell_m(l));
      EXPECT_NEAR(clouds.x, 3000.0f, 0.5f) << genus << " " << oktas;
      EXPECT_NEAR(clouds.y, 3800.0f, 0.5f) << genus << " " << oktas;
    }
  Scene s = nephele::parse_scene_toml(kTwoLayers, "layers.toml");
  const glm::vec2 shell = nephele::cloud_shell_m(s);
  EXPECT_EQ(shell.x, 500.0f);
  EXPECT_EQ(shell.y, nephele::weather::cloud_layer_shell_m(s.cloud_layers[1]).y);
  EXPECT_EQ(nephele::volumetric_layers(s).size(), 3u);
  s.cloud_layers[1].oktas = 0.0f;  // a layer without oktas is not there
  EXPECT_EQ(nephele::volumetric_layers(s).size(), 2u);
  EXPECT_EQ(nephele::cloud_shell_m(s).y,
            nephele::weather::cloud_layer_shell_m(s.cloud_layers[0]).y);
}

TEST(CloudLayers, BadLayersAreRefusedNamingTheKey) {
  EXPECT_EQ(error_of(kTwoLayers +
                     "\n[[cloud_layers]]\ngenus = \"cirrus\"\nbase_m = 7000\ntop_m = 7500\n"),
            "cloud_layers[2].genus = \"cirrus\": must be \"stratus\", \"stratocumulus\", "
            "\"altocumulus\", \"cumulus\" or \"cumulonimbus\"");
  EXPECT_EQ(error_of("[[cloud_layers]]\nbase_m = 3000\ntop_m = 2000\n"),
            "cloud_layers[0].base_m = 3000: must be below cloud_layers[0].top_m (2000)");
  EXPECT_EQ(error_of("[[cloud_layers]]\noktas = 9\n"),
            "cloud_layers[0].oktas = 9: must be in [0, 8]");
  EXPECT_NE(error_of("[[cloud_layers]]\nbase_km = 3\n")
                .find("unknown key 'cloud_layers[0].base_km' (allowed in [[cloud_layers]]: genus, "
                      "base_m, top_m, oktas, density, wind_mps)"),
            std::string::npos);
  // Clouds that overlap another layer's: the message names both.
  const std::string overlap =
      error_of(kTwoLayers + "\n[[cloud_layers]]\nbase_m = 3000\ntop_m = 3500\n");
  EXPECT_NE(overlap.find("cloud_layers[2].base_m = 3000: its clouds (3000-3500 m) overlap "
                         "cloud_layers[0]'s clouds (2500-3200 m)"),
            std::string::npos)
      << overlap;
  // ... or the low layer's clouds, where its genus and coverage put them in its shell.
  const std::string low =
      error_of("[clouds]\ncoverage = 0.5\n[[cloud_layers]]\nbase_m = 1600\ntop_m = 1900\n");
  EXPECT_NE(low.find("cloud_layers[0].base_m = 1600: its clouds (1600-1900 m) overlap clouds' "
                     "clouds ("),
            std::string::npos)
      << low;
  EXPECT_NE(low.find("where its type and coverage put them in its shell); layers that are there "
                     "lie apart"),
            std::string::npos)
      << low;
  // Without oktas a layer is not there, and overlaps nothing.
  EXPECT_EQ(
      error_of(
          "[clouds]\ncoverage = 0.5\n[[cloud_layers]]\nbase_m = 1600\ntop_m = 1900\noktas = 0\n"),
      "");
  std::string five;
  for (int i = 0; i < 5; ++i)
    five += "[[cloud_layers]]\nbase_m = " + std::to_string(6000 + 1000 * i) +
            "\ntop_m = " + std::to_string(6500 + 1000 * i) + "\n";
  EXPECT_EQ(error_of(five), "cloud_layers = 5 layers: at most 4 besides clouds and high_clouds");
  EXPECT_NE(error_of("cloud_layers = 3\n").find("expected an array of tables [[cloud_layers]]"),
            std::string::npos);
}

}  // namespace
